// `ipd rank` run again on a study that gained or changed variants: only the new or changed candidates are read
// and computed (core/rank/rank_cache.h), and what it prints is, byte for byte, what a run that reads the whole
// study prints (`--no-cache`).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

test::CommandResult rank(const test::TempDir& d, const std::string& extra = "") {
  return test::run_ipd("rank " + d.path() + " --ref real --model det-real --format json" + extra);
}

// stderr without the note that says which candidates were taken as kept.
std::string without_reuse_note(const std::string& err) {
  std::string out;
  size_t at = 0;
  while (at < err.size()) {
    const size_t end = err.find('\n', at);
    const std::string line = err.substr(at, end == std::string::npos ? std::string::npos : end - at + 1);
    if (line.find("as the last ranking left") == std::string::npos) out += line;
    at = end == std::string::npos ? err.size() : end + 1;
  }
  return out;
}

// The run's output and stderr are a whole run's; returns the run's stderr.
std::string expect_whole_runs_output(const test::TempDir& d, const std::string& extra = "") {
  const auto again = rank(d, extra);
  const auto whole = rank(d, extra + " --no-cache");
  EXPECT_EQ(again.exit_code, whole.exit_code) << again.err;
  EXPECT_EQ(again.out, whole.out);
  EXPECT_EQ(without_reuse_note(again.err), whole.err);
  return again.err;
}

void write_variants(const test::TempDir& d) {
  ASSERT_EQ(test::run_ipd("demo " + d.path() + " --variants 3 --scenes 6").exit_code, 0);
}

// The variants demo, ranked once (what it keeps is there for the next run).
void write_ranked_variants(const test::TempDir& d) {
  write_variants(d);
  const auto first = rank(d);
  ASSERT_EQ(first.exit_code, 0) << first.err;
}

// study.yaml without its line starting with `key`.
void drop_study_yaml_line(const test::TempDir& d, const std::string& key) {
  std::ifstream in(d / "study.yaml");
  std::string yaml, line;
  while (std::getline(in, line))
    if (line.rfind(key, 0) != 0) yaml += line + "\n";
  in.close();
  test::write_text(d / "study.yaml", yaml);
}

TEST(RankReuse, ANewVariantIsTheOnlyCandidateReadAndComputed) {
  test::TempDir d;
  write_variants(d);
  const auto first = rank(d);
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_EQ(first.err.find("as the last ranking left"), std::string::npos) << first.err;
  // A fourth setting rendered into the study: ambient-100's labels with ambient-000's detections.
  fs::copy(d / "ambient-100", d / "ambient-125", fs::copy_options::recursive);
  for (const auto& e : fs::directory_iterator(d / "ambient-000/predictions/det-real"))
    fs::copy_file(e.path(), d / ("ambient-125/predictions/det-real/" + e.path().filename().string()),
                  fs::copy_options::overwrite_existing);
  const std::string err = expect_whole_runs_output(d);
  EXPECT_NE(err.find("note: 3 candidates as the last ranking left them (their label and prediction files "
                     "unchanged); 1 read and computed: ambient-125\n"),
            std::string::npos)
      << err;
  const auto third = rank(d);
  EXPECT_NE(third.err.find("note: all 4 candidates as the last ranking left them (their label and prediction files "
                           "unchanged)\n"),
            std::string::npos)
      << third.err;
}

TEST(RankReuse, AnEditedPredictionFileMakesItsCandidateComputedAgain) {
  test::TempDir d;
  write_ranked_variants(d);
  // One detection fewer in one scene of ambient-050 (its first line dropped).
  const std::string file = d / "ambient-050/predictions/det-real/scene_00003.txt";
  std::ifstream in(file);
  std::string first_line, rest, line;
  std::getline(in, first_line);
  while (std::getline(in, line)) rest += line + "\n";
  in.close();
  test::write_text(file, rest);
  const std::string err = expect_whole_runs_output(d);
  EXPECT_NE(err.find("note: 2 candidates as the last ranking left them (their label and prediction files "
                     "unchanged); 1 read and computed: ambient-050\n"),
            std::string::npos)
      << err;
}

TEST(RankReuse, AHandPairsFolderMakesItsPairComputedAgain) {
  test::TempDir d;
  write_ranked_variants(d);
  fs::create_directories(d / "pairs/real__ambient-100");
  const std::string err = expect_whole_runs_output(d);
  EXPECT_NE(err.find("1 read and computed: ambient-100\n"), std::string::npos) << err;
}

TEST(RankReuse, OtherSettingsComputeEveryCandidate) {
  test::TempDir d;
  write_ranked_variants(d);
  for (const std::string extra : {" --conf 0.3", " --seed 7", " --bootstrap 500", " --class all"}) {
    const auto other = rank(d, extra);
    EXPECT_EQ(other.err.find("as the last ranking left"), std::string::npos) << extra << "\n" << other.err;
    const std::string err = expect_whole_runs_output(d, extra);
    EXPECT_NE(err.find("note: all 3 candidates as the last ranking left them"), std::string::npos) << extra << err;
  }
}

TEST(RankReuse, AStudyWithWarningsIsReadWholeAndSaysThemEveryTime) {
  test::TempDir d;
  write_variants(d);
  fs::remove(d / "ambient-000/predictions/det-real/scene_00002.txt");
  for (int run = 0; run < 2; ++run) {
    const auto r = rank(d);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("warning: model 'det-real' has no prediction file for 1 scene(s) of 'ambient-000'"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(r.err.find("as the last ranking left"), std::string::npos) << r.err;
  }
}

TEST(RankReuse, ANewVariantWithAnotherClassIsRefusedAsAWholeRunRefusesIt) {
  test::TempDir d;
  write_variants(d);
  // No class asked for: the one class of the labels is the class.
  drop_study_yaml_line(d, "rock_class:");
  ASSERT_EQ(rank(d).exit_code, 0);
  fs::copy(d / "ambient-100", d / "shadows", fs::copy_options::recursive);
  test::write_text(d / "shadows/labels/scene_00001.txt", "1 0.5 0.5 0.1 0.1\n");
  const auto r = rank(d);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("the labels hold 2 classes"), std::string::npos) << r.err;
}

TEST(RankReuse, AnUnreadableKeptFileIsComputedAgain) {
  test::TempDir d;
  write_ranked_variants(d);
  // Every kept file with one byte changed: none verifies, and the run reads the whole study.
  for (const auto& e : fs::directory_iterator(d / ".ipd-cache/rank")) {
    std::fstream f(e.path(), std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(40);
    f.put('\x5a');
  }
  fs::copy(d / "ambient-100", d / "ambient-125", fs::copy_options::recursive);
  const auto r = rank(d);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("as the last ranking left"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, rank(d, " --no-cache").out);
}

TEST(RankReuse, AKeptCellWhoseScenesFileIsGoneIsNotUsedForAComparison) {
  test::TempDir d;
  write_ranked_variants(d);
  // The scenes of every kept cell gone, the index left: a new variant needs the best's scenes to be compared.
  for (const auto& e : fs::directory_iterator(d / ".ipd-cache/rank"))
    if (e.path().filename() != "index.bin") fs::remove(e.path());
  fs::copy(d / "ambient-100", d / "ambient-125", fs::copy_options::recursive);
  const std::string err = expect_whole_runs_output(d);
  EXPECT_EQ(err.find("as the last ranking left"), std::string::npos) << err;
}

TEST(RankReuse, ANewBestComparesEveryCandidateAgain) {
  test::TempDir d;
  write_ranked_variants(d);
  // A setting that renders the reference exactly: IPD 0, the new best, so every kept comparison was with another.
  fs::create_directories(d / "exact");
  fs::copy(d / "real/labels", d / "exact/labels", fs::copy_options::recursive);
  fs::copy(d / "real/predictions", d / "exact/predictions", fs::copy_options::recursive);
  const std::string err = expect_whole_runs_output(d);
  EXPECT_NE(err.find("1 read and computed: exact\n"), std::string::npos) << err;
  EXPECT_NE(rank(d).out.find("\"best\": \"exact\""), std::string::npos);
}

TEST(RankReuse, OtherPermutationsCompareTheKeptCellsAgain) {
  test::TempDir d;
  write_ranked_variants(d);
  const std::string err = expect_whole_runs_output(d, " --permutations 50");
  EXPECT_NE(err.find("note: all 3 candidates as the last ranking left them"), std::string::npos) << err;
}

TEST(RankReuse, AnEditedLabelFileChangesTheFingerprintAsAWholeRunDoes) {
  test::TempDir d;
  write_ranked_variants(d);
  // ambient-000 comes first in the fingerprint's order: every domain after it is hashed again.
  std::ifstream in(d / "ambient-000/labels/scene_00004.txt");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  test::write_text(d / "ambient-000/labels/scene_00004.txt", text + "0 0.9 0.9 0.02 0.02\n");
  const std::string err = expect_whole_runs_output(d);
  EXPECT_NE(err.find("1 read and computed: ambient-000\n"), std::string::npos) << err;
}

TEST(RankReuse, AChangedDomainOutsideTheRankingIsReadForWhatItSays) {
  test::TempDir d;
  write_variants(d);
  const std::string two = " --candidates ambient-000,ambient-050";
  ASSERT_EQ(rank(d, two).exit_code, 0);
  // A malformed line in a domain the ranking does not rank: a whole run reads every domain and refuses it.
  test::write_text(d / "ambient-100/labels/scene_00001.txt", "0 0.5 0.5 0.1\n");
  const auto r = rank(d, two);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("ambient-100/labels/scene_00001.txt:1"), std::string::npos) << r.err;
  expect_whole_runs_output(d, two);
}

// What pairing says of the whole study (hand files no pair reads, square pictures) is said by a run that pairs
// nothing new too.
TEST(RankReuse, WhatPairingSaysOfTheWholeStudyIsSaidWhenNothingIsNew) {
  test::TempDir d;
  write_ranked_variants(d);
  test::write_text(d / "pairs/real__gone/scene_00001.json", "{}\n");
  std::string err = expect_whole_runs_output(d);
  EXPECT_NE(err.find("pairs/real__gone"), std::string::npos) << err;
  fs::remove_all(d / "pairs");

  // No image_size, and a picture in one domain: the aspect is the pictures'. Without the picture, every scene is
  // registered as a square picture, which a whole run says.
  drop_study_yaml_line(d, "image_size:");
  test::write_text(d / "ambient-000/images/scene_00001.png", "");
  ASSERT_EQ(rank(d).exit_code, 0);
  fs::remove_all(d / "ambient-000/images");
  err = expect_whole_runs_output(d);
  EXPECT_NE(err.find("no image_size and no pictures"), std::string::npos) << err;
}

}  // namespace
}  // namespace ipd
