// `ipd import coco`: scores and boxes arrive as doubles and must reach the label files unchanged; a category's
// class number is its id, the same in every domain; a domain folder with files is replaced only when asked.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "core/study/coco_import.h"
#include "core/util/atomic_file.h"
#include "core/util/errors.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

const char* const kOneImage = "\"images\": [{\"id\": 1, \"file_name\": \"s1.png\", \"width\": 100, \"height\": 100}]";

// One GT rock (category 2) at [40, 40, 20, 20]; `categories` is the file's own list.
std::string ground_truth(const std::string& categories) {
  return std::string("{") + kOneImage + ", \"categories\": " + categories +
         ", \"annotations\": [{\"image_id\": 1, \"category_id\": 2, \"bbox\": [40, 40, 20, 20]}]}";
}

std::string import_args(const test::TempDir& d, const std::string& ann, const std::string& domain) {
  return "import coco " + d / ann + " --images " + d.path() + " --out " + d / ("study/" + domain);
}

// 0.50001 (on the rock), 0.50004 (elsewhere) and 0.24996 were written 0.5000, 0.5000, 0.2500: the tie put the
// true positive first (AP50 1.0 where pycocotools says 0.5: the false positive ranks first) and `--conf 0.25`
// kept the 0.24996 detection.
TEST(CocoImport, ScoresAndBoxesAreWrittenInFull) {
  test::TempDir d;
  test::write_text(d / "gt.json", ground_truth("[{\"id\": 2, \"name\": \"rock\"}]"));
  test::write_text(d / "res.json",
                   "[{\"image_id\": 1, \"category_id\": 2, \"bbox\": [40, 40, 20, 20], \"score\": 0.50001},"
                   " {\"image_id\": 1, \"category_id\": 2, \"bbox\": [0, 0, 10, 10], \"score\": 0.50004},"
                   " {\"image_id\": 1, \"category_id\": 2, \"bbox\": [70, 70, 10, 30], \"score\": 0.24996}]");
  const auto r = test::run_ipd(import_args(d, "gt.json", "real") + " --results " + d / "res.json" + " --model det");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_file(d / "study/real/predictions/det/s1.txt"),
            "2 0.5 0.5 0.2 0.2 0.50001\n2 0.05 0.05 0.1 0.1 0.50004\n2 0.75 0.85 0.1 0.3 0.24996\n");
  EXPECT_EQ(read_file(d / "study/real/labels/s1.txt"), "2 0.5 0.5 0.2 0.2\n");
  test::write_text(d / "study/study.yaml", "models: {det: {trained_on: real}}\n");
  const auto m = test::run_ipd("metrics " + d / "study" + " --json --conf 0.25");
  ASSERT_EQ(m.exit_code, 0) << m.err;
  EXPECT_NE(m.out.find("\"ap50\": 0.5,"), std::string::npos) << m.out;
  EXPECT_NE(m.out.find("\"detections\": 2\n"), std::string::npos) << m.out;
}

// "rock" (id 2) was class 1 beside {1: shadow} and class 0 alone: with rock_class 0 one domain's shadows were
// compared with the other's rocks.
TEST(CocoImport, AClassIsItsCategoryIdWhateverElseTheFileLists) {
  test::TempDir d;
  test::write_text(d / "real.json",
                   ground_truth("[{\"id\": 1, \"name\": \"shadow\"}, {\"id\": 2, \"name\": \"rock\"}]"));
  test::write_text(d / "synth.json", ground_truth("[{\"id\": 2, \"name\": \"rock\"}]"));
  auto r = test::run_ipd(import_args(d, "real.json", "real"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "1 images, 1 GT boxes, 0 detections, 2 classes, 0 pictures linked -> " + d / "study/real" + "\n");
  r = test::run_ipd(import_args(d, "synth.json", "synth"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_file(d / "study/real/labels/s1.txt"), "2 0.5 0.5 0.2 0.2\n");
  EXPECT_EQ(read_file(d / "study/synth/labels/s1.txt"), "2 0.5 0.5 0.2 0.2\n");
  EXPECT_EQ(read_file(d / "study/real/labels/classes.txt"), "\nshadow\nrock\n");
  EXPECT_EQ(read_file(d / "study/synth/labels/classes.txt"), "\n\nrock\n");
}

TEST(CocoImport, AClassNumberThatNamesAnotherCategoryInASiblingDomainIsRefusedNamingBothFiles) {
  test::TempDir d;
  test::write_text(d / "real.json", ground_truth("[{\"id\": 2, \"name\": \"rock\"}]"));
  test::write_text(d / "synth.json", ground_truth("[{\"id\": 2, \"name\": \"shadow\"}]"));
  ASSERT_EQ(test::run_ipd(import_args(d, "real.json", "real")).exit_code, 0);
  const auto r = test::run_ipd(import_args(d, "synth.json", "synth"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "error: " + d / "synth.json" + ": class 2 is \"shadow\" here but \"rock\" in " +
                       d / "study/real/labels/classes.txt" +
                       "; a class number must be the same category in every domain of a study (rock_class picks "
                       "one number for all), so nothing is written\n");
  EXPECT_FALSE(fs::exists(d / "study/synth"));
}

TEST(CocoImport, ACategoryIdThatCannotBeAClassIsRefused) {
  test::TempDir d;
  test::write_text(d / "gt.json", ground_truth("[{\"id\": 2, \"name\": \"rock\"}, {\"id\": 10000}]"));
  CocoImportOptions o;
  o.annotations = d / "gt.json";
  o.out_dir = d / "study/real";
  try {
    import_coco(o);
    ADD_FAILURE() << "accepted";
  } catch (const StudyError& e) {
    EXPECT_EQ(std::string(e.what()), d / "gt.json" +
                                         ": categories[1]: category id 10000 is not a class number from 0 to 9999 "
                                         "(the category id becomes the YOLO class, one line of labels/classes.txt "
                                         "each)");
  }
  EXPECT_FALSE(fs::exists(d / "study"));
}

// An import into a domain that had files replaced its own scenes and left the rest: two sets mixed, exit 0.
TEST(CocoImport, ADomainFolderWithFilesIsReplacedOnlyWhenAskedAndThenWhole) {
  test::TempDir d;
  test::write_text(d / "gt.json", ground_truth("[{\"id\": 2, \"name\": \"rock\"}]"));
  test::write_text(d / "s1.png", "picture");
  test::write_text(d / "study/real/labels/old.txt", "0 0.5 0.5 0.1 0.1\n");
  test::write_text(d / "study/real/labels/s1.txt", "0 0.5 0.5 0.1 0.1\n");
  test::write_text(d / "study/real/images/old.png", "old picture");
  test::write_text(d / "study/real/predictions/yolo/old.txt", "0 0.5 0.5 0.1 0.1 0.9\n");
  auto r = test::run_ipd(import_args(d, "gt.json", "real"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "error: " + d / "study/real" +
                       ": already exists and is not an empty directory; its labels, pictures and predictions would "
                       "mix with the imported ones, so nothing is written (--replace replaces them whole)\n");
  EXPECT_EQ(read_file(d / "study/real/labels/s1.txt"), "0 0.5 0.5 0.1 0.1\n");
  r = test::run_ipd(import_args(d, "gt.json", "real") + " --replace");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "1 images, 1 GT boxes, 0 detections, 1 classes, 1 pictures linked -> " + d / "study/real" +
                       " (2 old files removed)\n");
  EXPECT_EQ(r.err, "warning: " + d / "study/real" +
                       "/predictions/yolo/ is kept as it was; its predictions are of the labels before this import\n");
  EXPECT_EQ(read_file(d / "study/real/labels/s1.txt"), "2 0.5 0.5 0.2 0.2\n");
  EXPECT_FALSE(fs::exists(d / "study/real/labels/old.txt"));
  EXPECT_FALSE(fs::exists(d / "study/real/images/old.png"));
  EXPECT_EQ(read_file(d / "study/real/images/s1.png"), "picture");
  EXPECT_TRUE(fs::exists(d / "study/real/predictions/yolo/old.txt"));
  // An empty folder is a new domain.
  fs::create_directories(d / "study/synth");
  EXPECT_EQ(test::run_ipd(import_args(d, "gt.json", "synth")).exit_code, 0);
}

// Corrected annotations imported again with --images the domain's own images/ folder: each picture is its own
// source, and removing the destination before linking it deleted the only copy (exit 0, "0 pictures linked").
TEST(CocoImport, ReimportingFromTheDomainsOwnPicturesKeepsThem) {
  test::TempDir d;
  test::write_text(d / "gt.json", ground_truth("[{\"id\": 2, \"name\": \"rock\"}]"));
  test::write_text(d / "study/real/images/s1.png", "picture");
  const std::string args = "import coco " + d / "gt.json" + " --images " + d / "study/real/images" + " --out " +
                           d / "study/real" + " --replace";
  const auto r = test::run_ipd(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_file(d / "study/real/images/s1.png"), "picture");
  EXPECT_EQ(fs::directory_iterator(d / "study/real/images")->path().filename(), "s1.png");  // and nothing else
  EXPECT_EQ(std::distance(fs::directory_iterator(d / "study/real/images"), fs::directory_iterator()), 1);
  EXPECT_NE(r.out.find("1 pictures linked"), std::string::npos) << r.out;
  EXPECT_EQ(read_file(d / "study/real/labels/s1.txt"), "2 0.5 0.5 0.2 0.2\n");
}

// A received study whose domain holds links (`labels -> X`, `images -> Y`, `predictions/det -> Z`): --replace
// writes the new set into a folder beside the domain and renames it in, so the links are replaced, and nothing
// in X, Y or Z is written, replaced or removed. A domain folder that is itself a link is refused.
TEST(CocoImport, ReplacingADomainNeverWritesThroughItsLinks) {
  test::TempDir d, x, y, z;
  test::write_text(d / "gt.json", ground_truth("[{\"id\": 2, \"name\": \"rock\"}]"));
  test::write_text(d / "res.json",
                   "[{\"image_id\": 1, \"category_id\": 2, \"bbox\": [40, 40, 20, 20], \"score\": 0.9}]");
  test::write_text(d / "s1.png", "picture");
  for (const test::TempDir* t : {&x, &y, &z}) test::write_text(*t / "s1.txt", "precious\n");
  test::write_text(x / "classes.txt", "precious\n");
  test::write_text(y / "s1.png", "precious\n");
  fs::create_directories(d / "study/real/predictions");
  fs::create_directory_symlink(x.path(), d / "study/real/labels");
  fs::create_directory_symlink(y.path(), d / "study/real/images");
  fs::create_directory_symlink(z.path(), d / "study/real/predictions/det");
  const auto r =
      test::run_ipd(import_args(d, "gt.json", "real") + " --results " + d / "res.json" + " --model det --replace");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const std::string& f : {x / "s1.txt", x / "classes.txt", y / "s1.txt", y / "s1.png", z / "s1.txt"})
    EXPECT_EQ(read_file(f), "precious\n") << f;
  EXPECT_FALSE(fs::is_symlink(d / "study/real/labels"));
  EXPECT_FALSE(fs::is_symlink(d / "study/real/predictions/det"));
  EXPECT_EQ(read_file(d / "study/real/labels/s1.txt"), "2 0.5 0.5 0.2 0.2\n");
  EXPECT_EQ(read_file(d / "study/real/images/s1.png"), "picture");
  EXPECT_EQ(read_file(d / "study/real/predictions/det/s1.txt"), "2 0.5 0.5 0.2 0.2 0.9\n");
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(d / "study")) names.push_back(e.path().filename().string());
  EXPECT_EQ(names, std::vector<std::string>{"real"});  // the staging folder and the old domain are gone
  // The domain folder itself a link: refused before anything is written.
  fs::create_directory_symlink(x.path(), d / "study/synth");
  const auto s = test::run_ipd(import_args(d, "gt.json", "synth") + " --replace");
  EXPECT_EQ(s.exit_code, 1);
  EXPECT_EQ(s.err, "error: " + d / "study/synth" +
                       ": is a symbolic link; the import replaces a folder, never through a link\n");
  EXPECT_EQ(read_file(x / "s1.txt"), "precious\n");
}

}  // namespace
}  // namespace ipd
