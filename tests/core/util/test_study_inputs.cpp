// An output never replaces one of the study's inputs: a table written over a label file, an export over a hand
// pairs file or a figure over a picture is an error (exit 1), so the next table is computed from the inputs.
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "core/util/atomic_file.h"
#include "core/util/contained_file.h"
#include "core/util/study_inputs.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

const char* const kWhere =
    "an output written there would replace it, so nothing is written. Outputs go outside study.yaml, pairs/, "
    "review/, .ipd-cache/ and each domain's labels/, images/ and predictions/ (e.g. into STUDY/figures/)";

std::string refused_study_inputs(const std::string& path, const std::string& what) {
  return path + ": is one of the study's inputs (" + what + "); " + kWhere;
}

TEST(StudyInputs, EveryInputOfTheLayoutIsNamedAndEverythingElseMayTakeAnOutput) {
  test::TempDir d;
  const std::string s = d / "study";
  EXPECT_EQ(study_input_problem(s, s + "/study.yaml"), refused_study_inputs(s + "/study.yaml", "the study's settings"));
  EXPECT_EQ(
      study_input_problem(s, s + "/real/labels/scene_01.txt"),
      refused_study_inputs(s + "/real/labels/scene_01.txt", "the ground-truth labels of domain 'real', real/labels/"));
  EXPECT_EQ(study_input_problem(s, s + "/real/images/scene_01.png"),
            refused_study_inputs(s + "/real/images/scene_01.png", "the pictures of domain 'real', real/images/"));
  EXPECT_EQ(
      study_input_problem(s, s + "/real/predictions/det/s.txt"),
      refused_study_inputs(s + "/real/predictions/det/s.txt", "the predictions of domain 'real', real/predictions/"));
  EXPECT_EQ(study_input_problem(s, s + "/pairs/real__synth/s.json"),
            refused_study_inputs(s + "/pairs/real__synth/s.json", "the hand pairs, pairs/"));
  EXPECT_EQ(study_input_problem(s, s + "/review/real__synth.json"),
            refused_study_inputs(s + "/review/real__synth.json", "the review marks, review/"));
  EXPECT_EQ(study_input_problem(s, s + "/.ipd-cache/parsed-study.bin"),
            refused_study_inputs(s + "/.ipd-cache/parsed-study.bin", "the study's caches, .ipd-cache/"));
  // Reached through ".." it is still the same file.
  EXPECT_NE(study_input_problem(s, s + "/figures/../real/labels/scene_01.txt"), "");
  // Outputs: the studio's figures folder, the study's top level, a file beside a domain's folders.
  EXPECT_EQ(study_input_problem(s, s + "/figures/table.pdf"), "");
  EXPECT_EQ(study_input_problem(s, s + "/table.csv"), "");
  EXPECT_EQ(study_input_problem(s, s + "/real/notes.txt"), "");
  EXPECT_EQ(study_input_problem(s, s + "/figures/study.yaml"), "");
  EXPECT_EQ(study_input_problem(s, d / "elsewhere/labels/x.txt"), "");
  // write_output_file, which every output goes through, refuses it and writes nothing.
  test::write_text(s + "/real/labels/scene_01.txt", "0 0.5 0.5 0.1 0.1\n");
  EXPECT_THROW(write_output_file(s, s + "/real/labels/scene_01.txt", "model,ipd\n"), IoError);
  EXPECT_EQ(read_file(s + "/real/labels/scene_01.txt"), "0 0.5 0.5 0.1 0.1\n");
  write_output_file(s, s + "/figures/table.csv", "model,ipd\n");
  EXPECT_EQ(read_file(s + "/figures/table.csv"), "model,ipd\n");
}

TEST(StudyInputs, AUsersLinkThatPointsIntoTheStudyIsSeenThrough) {
  test::TempDir d;
  fs::create_directories(d / "study/real/labels");
  test::write_text(d / "study/real/labels/s1.txt", "0 0.5 0.5 0.1 0.1\n");
  fs::create_directory_symlink(d / "study/real/labels", d / "mine");
  EXPECT_EQ(study_input_problem(d / "study", d / "mine/s1.txt"),
            refused_study_inputs(d / "mine/s1.txt", "the ground-truth labels of domain 'real', real/labels/"));
  EXPECT_THROW(write_output_file(d / "study", d / "mine/s1.txt", "table"), IoError);
  EXPECT_EQ(read_file(d / "study/real/labels/s1.txt"), "0 0.5 0.5 0.1 0.1\n");
}

// Every command that writes a named file goes through write_output_file: each is refused, exit 1, the input
// unchanged, and a path outside the inputs still works.
TEST(StudyInputs, TableExportAndFigureRefuseToWriteOverTheStudysInputs) {
  test::TempDir d;
  test::write_two_rock_study(d);
  test::write_text(d / "study.yaml", "domains: [real, synth]\n");
  test::write_text(d / "pairs/real__synth/s1.json", "{\"pairs\": [[0, 1], [1, 0]]}\n");
  const std::string label = d / "real/labels/s1.txt", pairs = d / "pairs/real__synth/s1.json";
  fs::create_directories(d / "real/images");
  cv::imwrite(d / "real/images/s1.png", cv::Mat(60, 80, CV_8UC3, cv::Scalar(9, 9, 9)));
  const std::string picture = d / "real/images/s1.png";
  const std::string label_before = read_file(label), pairs_before = read_file(pairs),
                    picture_before = read_file(picture);
  struct Case {
    std::string args, path, what;
  };
  const std::vector<Case> cases = {
      {"table " + d.path() + " --format csv --out " + label, label,
       "the ground-truth labels of domain 'real', real/labels/"},
      {"export rocks " + d.path() + " --format json --out " + pairs, pairs, "the hand pairs, pairs/"},
      {"table " + d.path() + " --out " + d / "study.yaml", d / "study.yaml", "the study's settings"},
      {"figure pairs " + d.path() + " --scene s1 --out " + d / "real/images/s1.png", d / "real/images/s1.png",
       "the pictures of domain 'real', real/images/"},
  };
  for (const Case& c : cases) {
    const auto r = test::run_ipd(c.args);
    EXPECT_EQ(r.exit_code, 1) << c.args;
    EXPECT_NE(r.err.find("error: " + refused_study_inputs(c.path, c.what) + "\n"), std::string::npos) << c.args << "\n"
                                                                                                      << r.err;
    EXPECT_EQ(r.err.find("wrote"), std::string::npos) << r.err;
  }
  EXPECT_EQ(read_file(label), label_before);
  EXPECT_EQ(read_file(pairs), pairs_before);
  EXPECT_EQ(read_file(d / "study.yaml"), "domains: [real, synth]\n");
  EXPECT_EQ(read_file(picture), picture_before);
  const auto ok = test::run_ipd("table " + d.path() + " --format csv --out " + d / "table.csv");
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_TRUE(fs::exists(d / "table.csv"));
}

}  // namespace
}  // namespace ipd
