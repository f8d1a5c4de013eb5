// `ipd rank` on the variants demo with bad candidates beside the good ones: each bad one said in its own words,
// the rest still ranked; and the outputs every format shares (Holm stated, provenance).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

// The variants demo (3 settings, 8 scenes) plus `lonely`, which shares no scene with real, and `dim`, whose
// detections all have confidence 0.1.
void write_study_with_bad_candidates(const test::TempDir& d) {
  ASSERT_EQ(test::run_ipd("demo " + d.path() + " --variants 3 --scenes 8").exit_code, 0);
  test::write_text(d / "lonely/labels/other_scene.txt", "0 0.5 0.5 0.1 0.1\n");
  test::write_text(d / "lonely/predictions/det-real/other_scene.txt", "0 0.5 0.5 0.1 0.1 0.9\n");
  for (const auto& e : fs::directory_iterator(d / "real/labels")) {
    const std::string stem = e.path().stem().string();
    fs::create_directories(d / "dim/labels");
    fs::copy_file(e.path(), d / ("dim/labels/" + stem + ".txt"));
    test::write_text(d / ("dim/predictions/det-real/" + stem + ".txt"), "0 0.5 0.5 0.1 0.1 0.1\n");
  }
}

TEST(RankCli, BadCandidatesAreSaidAndTheRestRanked) {
  test::TempDir d;
  write_study_with_bad_candidates(d);
  const auto r = test::run_ipd("rank " + d.path() + " --ref real --model det-real --conf 0.2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("det-real (real) against real: 4 candidates ranked (IPD, lower is better)"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("Not ranked: lonely: shares no scenes with real (no label file stem is in both real/labels/ and "
                       "lonely/labels/).\n"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("dim: no predictions of det-real at or above 0.2: every rock there counts as missed.\n"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("(Holm-corrected over 3 comparisons with the best)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Label files "), std::string::npos) << r.out;
  // Candidates are never compared with each other: their layouts against each other are not the ranking's.
  EXPECT_EQ(r.err.find("'dim' and 'lonely'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'real' and 'lonely' share no scene"), std::string::npos) << r.err;
}

TEST(RankCli, UnknownDomainIsAUsageOfTheStudysNames) {
  test::TempDir d;
  ASSERT_EQ(test::run_ipd("demo " + d.path() + " --variants 2 --scenes 2").exit_code, 0);
  const auto r = test::run_ipd("rank " + d.path() + " --ref real --candidates ambient-000,ambient-05");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "error: " + d.path() +
                       ": no domain 'ambient-05' in this study (--candidates; the study's domains: real, ambient-000, "
                       "ambient-100)\n");
}

TEST(RankCli, JsonNamesTheBestItsGroupAndHolm) {
  test::TempDir d;
  ASSERT_EQ(test::run_ipd("demo " + d.path() + " --variants 9").exit_code, 0);
  const auto r = test::run_ipd("rank " + d.path() + " --ref real --model det-real --format json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["best"], "ambient-038");
  EXPECT_EQ(j["correction"], "Holm");
  EXPECT_EQ(j["tests"], 8);
  EXPECT_EQ(j["ranked"][0]["params"]["ambient"], 0.375);
  EXPECT_TRUE(j["provenance"].contains("label_fingerprint"));
  const auto group = j["best_group"].get<std::vector<std::string>>();
  EXPECT_NE(std::find(group.begin(), group.end(), "ambient-025"), group.end());
  EXPECT_EQ(std::find(group.begin(), group.end(), "ambient-100"), group.end());
}

}  // namespace
}  // namespace ipd

namespace ipd {
namespace {

// The class every number is about is chosen as `ipd table` chooses it: the same refusal when the labels hold two
// classes and none was chosen, the same --class.
TEST(RankCli, ClassChoiceIsTheTables) {
  test::TempDir d;
  ASSERT_EQ(test::run_ipd("demo " + d.path() + " --variants 2 --scenes 3").exit_code, 0);
  test::write_text(d / "study.yaml",
                   "domains: {real: {}, ambient-000: {params: {ambient: 0}}, ambient-100: {params: "
                   "{ambient: 1}}}\nmodels: {det-real: {trained_on: real}}\nimage_size: [960, 600]\n");
  for (const auto& e : fs::directory_iterator(d / "real/labels")) {
    std::string text;
    {
      std::ifstream in(e.path());
      text.assign(std::istreambuf_iterator<char>(in), {});
    }
    test::write_text(e.path().string(), text + "1 0.5 0.5 0.05 0.05\n");
  }
  const auto table = test::run_ipd("table " + d.path());
  const auto rank = test::run_ipd("rank " + d.path() + " --ref real");
  EXPECT_EQ(table.exit_code, 1);
  EXPECT_EQ(rank.exit_code, table.exit_code);
  EXPECT_EQ(rank.err, table.err);
  const auto chosen = test::run_ipd("rank " + d.path() + " --ref real --class 0");
  EXPECT_EQ(chosen.exit_code, 0) << chosen.err;
  // The same provenance note as the table's for that class.
  const auto table_chosen = test::run_ipd("table " + d.path() + " --class 0");
  const std::string note = table_chosen.out.substr(table_chosen.out.rfind("Label files"));
  EXPECT_NE(chosen.out.find(note), std::string::npos) << chosen.out;
}

}  // namespace
}  // namespace ipd
