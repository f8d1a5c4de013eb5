// A study laid out wrong says what is wrong, each problem in its own words, and a command that would print a
// number from what such a problem left stops (exit 1) unless --skip-bad-lines asks for the number anyway.
#include <gtest/gtest.h>

#include <string>

#include "core/ipd/study_layout.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

const char* const kRocks = "0 0.2 0.2 0.1 0.1\n0 0.5 0.6 0.12 0.1\n0 0.8 0.3 0.08 0.09\n0 0.4 0.85 0.1 0.11\n";
const char* const kFound = "0 0.21 0.2 0.1 0.1 0.9\n0 0.5 0.61 0.12 0.1 0.8\n";

// Scenes s1..s3 in `real` and `synth`, GT and predictions of `det` in each, at the paths `where` gives.
void write_study(const test::TempDir& d, const std::string& real_labels, const std::string& synth_labels,
                 const std::string& real_predictions = "real/predictions/det/") {
  for (const std::string stem : {"s1", "s2", "s3"}) {
    test::write_text(d / (real_labels + stem + ".txt"), kRocks);
    test::write_text(d / (synth_labels + stem + ".txt"), kRocks);
    test::write_text(d / (real_predictions + stem + ".txt"), kFound);
    test::write_text(d / ("synth/predictions/det/s" + stem.substr(1) + ".txt"), kFound);
  }
  test::write_text(d / "study.yaml", "models: {det: {trained_on: real}}\n");
}

test::CommandResult table(const test::TempDir& d, const std::string& more = "") {
  return test::run_ipd("table " + d.path() + " --bootstrap 0" + more);
}

const char* const kStop =
    "error: the numbers would leave out most of the study's scenes or rocks; fix the layout, or pass "
    "--skip-bad-lines to print them anyway\n";

TEST(LayoutProblems, TwoDomainsSharingNoSceneShowTheirNamesAndThePrefixThatSetsThemApart) {
  test::TempDir d;
  write_study(d, "real/labels/1a2b3c4d-", "synth/labels/");
  auto r = table(d);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("error: 'real' and 'synth' share no scene (scenes pair across domains by file stem): real has "
                       "1a2b3c4d-s1, 1a2b3c4d-s2, 1a2b3c4d-s3 (3 scenes), synth has s1, s2, s3 (3 scenes); real's "
                       "names are synth's with the prefix '1a2b3c4d-' (1a2b3c4d-s1 against s1)"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find(kStop), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
  r = table(d, " --skip-bad-lines");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: 'real' and 'synth' share no scene"), std::string::npos) << r.err;
}

// A Roboflow export named as a study: its splits became domains that share no scene.
TEST(LayoutProblems, ASplitOfAToolsExportNamedAsADomainIsToldItsNamesAreTheTools) {
  test::TempDir d;
  const std::string hash = ".rf.0123456789abcdef0123456789abcdef";
  test::write_text(d / ("train/labels/a_jpg" + hash + ".txt"), kRocks);
  test::write_text(d / ("valid/labels/b_jpg" + hash + ".txt"), kRocks);
  test::write_text(d / ("train/predictions/det/a_jpg" + hash + ".txt"), kFound);
  test::write_text(d / ("valid/predictions/det/b_jpg" + hash + ".txt"), kFound);
  const auto r = test::run_ipd("table " + d.path() + " --bootstrap 0");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("; train's names are a tool's (a_jpg" + hash +
                       " is scene 'a' by the rules of docs/import.md): bring the export in with ipd import yolo, "
                       "which maps them back and merges its splits"),
            std::string::npos)
      << r.err;
}

TEST(LayoutProblems, LabelsOnlyInSubFoldersAreNamedWithTheirFolders) {
  test::TempDir d;
  write_study(d, "real/labels/train/", "synth/labels/");
  const auto r = table(d);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("error: " + d / "real/labels" +
                       "/: no label files of its own, but 3 in its sub-folder train/; a study reads "
                       "<domain>/labels/<stem>.txt only, so domain 'real' has no ground truth"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("share no scene"), std::string::npos) << r.err;  // one problem, said once
}

// The whole run folder copied into predictions/det/: its files are in det/exp/labels/, and every rock counted as
// missed gave a number, exit 0.
TEST(LayoutProblems, APredictionSetNestedTooDeepSaysWhereItsFilesAre) {
  test::TempDir d;
  write_study(d, "real/labels/", "synth/labels/", "real/predictions/det/exp/labels/");
  auto r = table(d);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("error: " + d / "real/predictions/det" +
                       "/: no prediction files of its own; they are nested too deep, 3 in " +
                       d / "real/predictions/det/exp/labels" + "/ (expected " + d / "real/predictions/det" +
                       "/<stem>.txt): every rock of 'real' would count as missed by 'det'"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.out, "");
  r = table(d, " --skip-bad-lines");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("det (real)"), std::string::npos) << r.out;
}

TEST(LayoutProblems, GroundTruthWithoutTheChosenClassSaysWhichClassesItHolds) {
  test::TempDir d;
  write_study(d, "real/labels/", "synth/labels/");
  test::write_text(d / "study.yaml",
                   "models: {det: {trained_on: real}}\nclasses: [rock, shadow]\nrock_class: shadow\n");
  const auto r = table(d);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("error: no ground-truth box of shadow (class 1) in the 3 scenes 'real' and 'synth' share; "
                       "their label files hold rock (class 0): 24 boxes: choose the class with --class or "
                       "study.yaml's rock_class"),
            std::string::npos)
      << r.err;
}

TEST(LayoutProblems, DomainsSharingLessThanHalfTheirScenesStop) {
  test::TempDir d;
  write_study(d, "real/labels/", "synth/labels/");
  for (const std::string stem : {"t1", "t2"}) test::write_text(d / ("synth/labels/" + stem + ".txt"), kRocks);
  std::remove((d / "synth/labels/s3.txt").c_str());
  // s1, s2 shared; s3 only in real, t1 and t2 only in synth: 3 of 5 scenes in no IPD.
  const auto r = table(d);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("error: 'real' and 'synth' share only 2 of their 5 scenes: 1 of real and 2 of synth have no "
                       "counterpart (e.g. s3), so most of the study is in no IPD"),
            std::string::npos)
      << r.err;
  // Half of them is still a number (with the warnings about the scenes without a counterpart).
  std::remove((d / "synth/labels/t2.txt").c_str());
  const auto half = table(d);
  EXPECT_EQ(half.exit_code, 0) << half.err;
  EXPECT_NE(half.out.find("det (real)"), std::string::npos) << half.out;
}

// --no-conf at import is said by every table made from the set, not only by the import.
TEST(LayoutProblems, APredictionSetImportedWithoutConfidencesIsSaidByTheTable) {
  test::TempDir d;
  write_study(d, "real/labels/", "synth/labels/");
  test::write_text(d / "real/predictions/det/import.json",
                   "{\"confidence\": \"none in the run's files: every box read with confidence 1 (--no-conf)\"}\n");
  const auto r = table(d);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: " + d / "real/predictions/det" +
                       "/: imported without confidences (--no-conf, real/predictions/det/import.json): every box has "
                       "confidence 1, so AP, --conf and the confidence breakdown say nothing about 'det'\n"),
            std::string::npos)
      << r.err;
}

TEST(LayoutProblems, AYoloDatasetNamedAsAStudyIsToldHowToBringItIn) {
  test::TempDir d;
  test::write_text(d / "ds/data.yaml", "train: images/train\nnames: [rock]\n");
  test::write_text(d / "ds/labels/train/s1.txt", "0 0.5 0.5 0.1 0.1\n");
  const auto ds = test::run_ipd("table " + d / "ds");
  EXPECT_EQ(ds.exit_code, 1);
  EXPECT_EQ(ds.err, "error: " + d / "ds" +
                        ": no domains found (expected subdirectories like real/labels/ with YOLO label files); it "
                        "holds data.yaml, as a YOLO dataset or a labelling tool's export does: ipd import yolo " +
                        d / "ds" + " --out STUDY/<domain> brings it into a study (docs/import.md)\n");
}

// yolo predict without save_conf: every line refused alike, and nothing said about why.
TEST(LayoutProblems, PredictionsWithoutAConfidenceColumnAreNamedAsARunSavedWithoutIt) {
  test::TempDir d;
  write_study(d, "real/labels/", "synth/labels/");
  for (const std::string stem : {"s1", "s2", "s3"})
    test::write_text(d / ("real/predictions/det/" + stem + ".txt"), "0 0.21 0.2 0.1 0.1\n");
  const auto r = table(d);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("\n" + d / "real/predictions/det" +
                       "/: its lines have no confidence column, as a YOLO run saved without it; run the detector "
                       "again with it (yolov5 detect.py --save-txt --save-conf, yolo predict save_txt=True "
                       "save_conf=True), or bring the run in with ipd import predictions RUN --out STUDY/<domain> "
                       "--model M --no-conf (docs/import.md)\n"),
            std::string::npos)
      << r.err;
}

TEST(LayoutProblems, ANameDifferenceIsAPrefixOrASuffixAndNothingElse) {
  EXPECT_EQ(name_difference("1a2b3c4d-0001", "0001"), "the prefix '1a2b3c4d-'");
  EXPECT_EQ(name_difference("0001", "0001_left"), "the suffix '_left'");
  EXPECT_EQ(name_difference("0001", "0002"), "");
  EXPECT_EQ(name_difference("a0001", "0001b"), "");
}

}  // namespace
}  // namespace ipd
