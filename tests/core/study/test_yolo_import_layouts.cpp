// `ipd import yolo` and `ipd import predictions` on the layouts a team has besides the usual folders: a split
// given as a list of pictures, CVAT's list of its frames, a dataset without a names file, a few malformed lines
// to skip, and data kept one folder down; each with its exact message, nothing written on error.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "core/util/atomic_file.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

const char* const kBox = "0 0.5 0.5 0.1 0.1\n";

void expect_nothing_written_yolo_import_layouts(const test::TempDir& t) {
  EXPECT_FALSE(fs::exists(t / "study/real"));
  if (fs::exists(t / "study"))
    for (const auto& e : fs::directory_iterator(t / "study")) ADD_FAILURE() << "left behind: " << e.path();
}

test::CommandResult import(const test::TempDir& t, const std::string& args) {
  return test::run_ipd("import yolo " + args + " --out " + t / "study/real");
}

// Ultralytics reads `train: train.txt` as the pictures it lists: "./" below the list's folder, others below the
// dataset's root; each picture's label where the path's last images/ is labels/.
TEST(YoloImportLayouts, ASplitGivenAsAListOfPicturesIsRead) {
  test::TempDir t;
  test::write_text(t / "ds/data.yaml", "path: .\ntrain: lists/train.txt\nnames: [rock]\n");
  test::write_text(t / "ds/lists/train.txt", "./../images/train/s1.png\nimages/train/s2.png\n\n");
  test::write_text(t / "ds/images/train/s1.png", "not decoded");
  test::write_text(t / "ds/images/train/s2.png", "not decoded");
  test::write_text(t / "ds/images/train/s3.png", "not listed: not imported");
  test::write_text(t / "ds/labels/train/s1.txt", kBox);
  const auto r = import(t, t / "ds/data.yaml");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_file(t / "study/real/labels/s1.txt"), kBox);
  EXPECT_EQ(read_file(t / "study/real/labels/s2.txt"), "");  // no label file: no objects
  EXPECT_FALSE(fs::exists(t / "study/real/labels/s3.txt"));
  EXPECT_TRUE(fs::exists(t / "study/real/images/s2.png"));
}

TEST(YoloImportLayouts, AListedPictureThatIsNotThereIsRefusedWithItsLine) {
  test::TempDir t;
  test::write_text(t / "ds/data.yaml", "train: train.txt\nnames: [rock]\n");
  test::write_text(t / "ds/train.txt", "images/train/s1.png\nimages/train/s9.png\n");
  test::write_text(t / "ds/images/train/s1.png", "not decoded");
  const auto r = import(t, t / "ds/data.yaml");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "error: " + t / "ds/train.txt" + ":2: " + t / "ds/images/train/s9.png" +
                       " is not there, nor its label file " + t / "ds/labels/train/s9.txt" +
                       "; expected a picture of the split\n");
  expect_nothing_written_yolo_import_layouts(t);
  test::write_text(t / "ds/train.txt", "../elsewhere/s1.png\n");
  EXPECT_EQ(import(t, t / "ds/data.yaml").err, "error: " + t / "ds/train.txt" +
                                                   ":1: '../elsewhere/s1.png' leaves the dataset folder " + t / "ds" +
                                                   "; expected a picture below it\n");
  expect_nothing_written_yolo_import_layouts(t);
}

// CVAT's train.txt names every frame (data/obj_train_data/<frame>.<ext>), also in an export without pictures.
TEST(YoloImportLayouts, CvatsTrainListSaysWhichFramesTheExportHas) {
  test::TempDir t;
  test::write_text(t / "cvat/obj.names", "rock\n");
  test::write_text(t / "cvat/obj.data", "classes = 1\ntrain = data/train.txt\nnames = data/obj.names\n");
  test::write_text(t / "cvat/train.txt", "data/obj_train_data/f1.jpg\ndata/obj_train_data/f2.jpg\n");
  test::write_text(t / "cvat/obj_train_data/f1.txt", kBox);
  test::write_text(t / "cvat/obj_train_data/f2.txt", "");
  const auto r = import(t, t / "cvat");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out,
            "CVAT YOLO 1.1 (splits train): 2 scenes (0 without a label file: no objects), 1 GT boxes, 1 "
            "classes from " +
                t / "cvat/obj.names" + ", 0 pictures linked -> " + t / "study/real" + "\n");
  EXPECT_EQ(read_file(t / "study/real/labels/f1.txt"), kBox);
  // A label file the list leaves out would be left out of the study without a word: refused.
  fs::remove_all(t / "study");
  test::write_text(t / "cvat/obj_train_data/f3.txt", kBox);
  EXPECT_EQ(import(t, t / "cvat").err, "error: " + t / "cvat/obj_train_data/f3.txt" + ": a label file no line of " +
                                           t / "cvat/train.txt" +
                                           " names; add its picture to the list, or remove it\n");
  expect_nothing_written_yolo_import_layouts(t);
}

TEST(YoloImportLayouts, NamesGivenOnTheCommandLineNameTheClassesOfADatasetWithout) {
  test::TempDir t;
  test::write_text(t / "ds/labels/s1.txt", "1 0.5 0.5 0.1 0.1\n");
  auto r = import(t, t / "ds --names rock,shadow");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_file(t / "study/real/labels/classes.txt"), "rock\nshadow\n");
  // A class number the names leave unnamed is refused with its line, as with a names file.
  fs::remove_all(t / "study");
  r = import(t, t / "ds --names rock");
  EXPECT_EQ(r.err, t / "ds/labels/s1.txt" +
                       ":1: class 1 is not among the classes --names names (1 of them); expected a named class "
                       "number\nerror: 1 problem in the source's label files; nothing written (--skip-bad-lines "
                       "writes malformed lines as comments)\n");
  expect_nothing_written_yolo_import_layouts(t);
  // Beside a names file, --names would be a second opinion: refused.
  test::write_text(t / "ds/classes.txt", "rock\nshadow\n");
  r = import(t, t / "ds --names rock,shadow");
  EXPECT_EQ(r.err, "error: --names: " + t / "ds/classes.txt" +
                       " names the classes of this source already; --names is for a dataset without a names file\n");
  expect_nothing_written_yolo_import_layouts(t);
}

TEST(YoloImportLayouts, SkippedLinesAreWrittenAsCommentsUnlessTheyAreMostLines) {
  test::TempDir t;
  test::write_text(t / "ds/labels/s1.txt", "0 0.5 0.5 0.1 0.1\n0 0.5 0.5 0.1\n# a comment\n");
  test::write_text(t / "ds/labels/s2.txt", "0 0.2 0.2 0.1 0.1\n0 0.3 0.3 0.1 0.1\n");
  auto r = import(t, t / "ds --skip-bad-lines");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "warning: " + t / "ds/labels/s1.txt" +
                       ":2: expected 5 columns (class cx cy w h), found 4\nwarning: 1 malformed line(s) written as "
                       "comments (--skip-bad-lines)\n");
  EXPECT_EQ(read_file(t / "study/real/labels/s1.txt"),
            "0 0.5 0.5 0.1 0.1\n# skipped by ipd import yolo --skip-bad-lines: 0 0.5 0.5 0.1\n# a comment\n");
  EXPECT_EQ(read_file(t / "study/real/labels/s2.txt"), "0 0.2 0.2 0.1 0.1\n0 0.3 0.3 0.1 0.1\n");
  // Three bad lines of five: what is left is not the dataset.
  fs::remove_all(t / "study");
  test::write_text(t / "ds/labels/s2.txt", "0 0.2 0.2 0.1\n0 0.3 0.3\n");
  r = import(t, t / "ds --skip-bad-lines");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, t / "ds/labels/s1.txt" + ":2: expected 5 columns (class cx cy w h), found 4\n" +
                       t / "ds/labels/s2.txt" + ":1: expected 5 columns (class cx cy w h), found 4\n" +
                       t / "ds/labels/s2.txt" +
                       ":2: expected 5 columns (class cx cy w h), found 3\nerror: " + t / "ds" +
                       ": --skip-bad-lines would leave out 3 of its 4 box lines, more than half: what is left is not "
                       "the dataset; fix the lines (or the layout that makes them wrong), nothing is written\n");
  expect_nothing_written_yolo_import_layouts(t);
}

TEST(YoloImportLayouts, ADatasetUnzippedOneFolderDownIsNamed) {
  test::TempDir t;
  test::write_text(t / "download/rocks.v1/data.yaml", "train: train/images\nnames: [rock]\n");
  test::write_text(t / "download/README.txt", "from the zip\n");
  EXPECT_EQ(import(t, t / "download").err,
            "error: " + t / "download" +
                ": not a YOLO dataset itself, but its folder rocks.v1 holds data.yaml (the dataset unzipped one "
                "folder down): ipd import yolo " +
                t / "download/rocks.v1" + " --out STUDY/<domain>\n");
  expect_nothing_written_yolo_import_layouts(t);
}

TEST(PredictionImportLayouts, ARunKeptFoldersDownIsNamedWithTheCommandThatTakesIt) {
  test::TempDir t;
  test::write_text(t / "study/real/labels/s1.txt", kBox);
  test::write_text(t / "results/runs/detect/exp/labels/s1.txt", "0 0.5 0.5 0.1 0.1 0.9\n");
  const auto r = test::run_ipd("import predictions " + t / "results" + " --out " + t / "study/real" + " --model det");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "error: " + t / "results" + ": no label files here or in labels/, but " +
                       t / "results/runs/detect/exp" +
                       " holds a run's labels/ (1 label files): name that run, ipd "
                       "import predictions " +
                       t / "results/runs/detect/exp" + " --out ... --model ...\n");
  EXPECT_FALSE(fs::exists(t / "study/real/predictions"));
}

// ipd register stops, as ipd table does, when skipping bad lines would leave most of a file's rocks out.
TEST(RegisterSkipBadLines, MostLinesSkippedStopsThePair) {
  test::TempDir t;
  test::write_text(t / "a.txt", "0 0.5 0.5 0.1 0.1\n0 0.5 0.5\n0 0.2 0.2\n");
  test::write_text(t / "b.txt", "0 0.5 0.5 0.1 0.1\n0 0.3 0.3 0.1 0.1\n");
  const auto r = test::run_ipd("register " + t / "a.txt" + " " + t / "b.txt" + " --skip-bad-lines");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, t / "a.txt" + ":2: expected 5 columns (class cx cy w h), found 3\n" + t / "a.txt" +
                       ":3: expected 5 columns (class cx cy w h), found 3\n" + t / "a.txt" +
                       ": --skip-bad-lines would leave out 2 of its 3 box lines, more than half: the pairs would be "
                       "of what is left, not of the scene's rocks; fix the lines\n");
  // One bad line of three is skipped, as before.
  test::write_text(t / "a.txt", "0 0.5 0.5 0.1 0.1\n0 0.5 0.5\n0 0.2 0.2 0.1 0.1\n");
  EXPECT_EQ(test::run_ipd("register " + t / "a.txt" + " " + t / "b.txt" + " --skip-bad-lines").exit_code, 0);
}

// ipd register stops when the chosen class leaves one file without a box: the other file's rocks would all read
// as unpaired, as a study where --class removes a domain's rocks stops ipd table.
TEST(RegisterSkipBadLines, AClassOneFileLacksStopsThePair) {
  test::TempDir t;
  test::write_text(t / "a.txt", "0 0.5 0.5 0.1 0.1\n0 0.2 0.2 0.1 0.1\n");
  test::write_text(t / "b.txt", "1 0.5 0.5 0.1 0.1\n0 0.2 0.2 0.1 0.1\n");
  const auto r = test::run_ipd("register " + t / "a.txt" + " " + t / "b.txt" + " --class 1");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, t / "a.txt" +
                       ": no box of class 1 among its 2 (it holds class 0): nothing of that class to pair; choose a "
                       "class both files hold with --class\n");
  EXPECT_EQ(test::run_ipd("register " + t / "a.txt" + " " + t / "b.txt" + " --class 0").exit_code, 0);
}

}  // namespace
}  // namespace ipd
