// Provenance: the hand-pair counts and the label fingerprint that travel with every table, so a reader can
// tell an automatic number from an edited one and which labels it came from.
#include "core/report/provenance.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/study/study.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

// Real rock 0 paired by hand with synth rock 1 (the same box), real rock 1 left out.
void write_hand_pairs(const test::TempDir& d) {
  test::write_text(d / "pairs/real__synth/s1.json", R"({"pairs": [[0, 1]], "excluded_a": [1],)"
                                                    R"( "rocks_a": [[0, 0.2, 0.2, 0.1, 0.1], [1, 0.6, 0.6, 0.1, 0.1]],)"
                                                    R"( "rocks_b": [[1, 0.2, 0.2, 0.1, 0.1]]})");
}

// The expected digests were computed outside the tool (Python's hashlib over the same bytes, path \0 size
// \0 contents, sorted by path).
TEST(Provenance, FingerprintCoversLabelNamesAndBytesOnly) {
  test::TempDir d;
  test::write_two_rock_study(d);
  EXPECT_EQ(label_set_fingerprint(open_study(d.path())), "d189a61c07b5");
  // Predictions and pairs files are not part of the label set.
  test::write_text(d / "real/predictions/det/s1.txt", "0 0.3 0.2 0.1 0.1 0.7\n");
  write_hand_pairs(d);
  EXPECT_EQ(label_set_fingerprint(open_study(d.path())), "d189a61c07b5");
  // One digit of one box is a different label set.
  test::write_text(d / "synth/labels/s1.txt", "0 0.6 0.6 0.1 0.1\n0 0.2 0.2 0.1 0.11\n");
  EXPECT_EQ(label_set_fingerprint(open_study(d.path())), "6225339ca70b");
}

TEST(Provenance, TableJsonCarriesHandPairCountsAndFingerprint) {
  test::TempDir d;
  test::write_two_rock_study(d);
  write_hand_pairs(d);
  const auto r = test::run_ipd("table " + d.path() + " --format json --no-cache");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json p = nlohmann::json::parse(r.out).at("provenance");
  EXPECT_EQ(p.at("label_fingerprint"), "d189a61c07b5");
  EXPECT_EQ(p.at("scenes_with_hand_pairs"), 1);
  EXPECT_EQ(p.at("pairs_set_by_hand"), 1);
  EXPECT_EQ(p.at("rocks_excluded"), 1);
  EXPECT_EQ(p.at("edited_scenes"), nlohmann::json::parse(R"([{"a": "real", "b": "synth", "stem": "s1"}])"));
  EXPECT_NE(
      r.err.find("note: Label files d189a61c07b5; hand pairs in 1 scene (1 pair set by hand, 1 rock excluded).\n"),
      std::string::npos)
      << r.err;
}

TEST(Provenance, TextTableFootnoteAndVerboseListOfEditedScenes) {
  test::TempDir d;
  test::write_two_rock_study(d);
  auto r = test::run_ipd("table " + d.path() + " --no-cache");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\nLabel files d189a61c07b5; no hand pairs (every pair from registration).\n"),
            std::string::npos)
      << r.out;
  write_hand_pairs(d);
  r = test::run_ipd("table " + d.path() + " --no-cache --verbose");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\nLabel files d189a61c07b5; hand pairs in 1 scene (1 pair set by hand, 1 rock excluded).\n"
                       "  real vs synth: s1: pairs set by hand\n"),
            std::string::npos)
      << r.out;
}

// Review marks travel with the table: a reviewed scene, and a checked pair that is still a pair (the second
// check names rocks that registration did not pair: it is not counted).
TEST(Provenance, ReviewFilesCountReviewedScenesAndCheckedPairs) {
  test::TempDir d;
  test::write_two_rock_study(d);
  test::write_text(d / "review/real__synth.json",
                   R"({"reviewed": ["s1"], "checked": [)"
                   R"({"scene": "s1", "rock_a": [0.2, 0.2, 0.1, 0.1], "rock_b": [0.2, 0.2, 0.1, 0.1]},)"
                   R"({"scene": "s1", "rock_a": [0.6, 0.6, 0.1, 0.1], "rock_b": [0.2, 0.2, 0.1, 0.1]}]})");
  const auto r = test::run_ipd("table " + d.path() + " --format json --no-cache");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json p = nlohmann::json::parse(r.out).at("provenance");
  EXPECT_EQ(p.at("scenes_reviewed"), 1);
  EXPECT_EQ(p.at("pairs_checked"), 1);
  EXPECT_NE(r.err.find("note: Label files d189a61c07b5; no hand pairs (every pair from registration); 1 scene "
                       "reviewed, 1 pair checked as correct.\n"),
            std::string::npos)
      << r.err;
  // A review file that is not JSON stops the table, naming the file.
  test::write_text(d / "review/real__synth.json", "{\"reviewed\": [\"s1\"]");
  const auto bad = test::run_ipd("table " + d.path() + " --no-cache");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find(d / "review/real__synth.json: invalid JSON"), std::string::npos) << bad.err;
}

TEST(Provenance, NoteCountsInPlural) {
  Provenance p;
  p.label_fingerprint = "0123456789ab";
  p.scenes_with_hand_pairs = 2;
  p.pairs_set_by_hand = 5;
  p.rocks_excluded = 0;
  EXPECT_EQ(provenance_note(p),
            "Label files 0123456789ab; hand pairs in 2 scenes (5 pairs set by hand, 0 rocks excluded).");
  p.scenes_reviewed = 412;
  EXPECT_EQ(provenance_note(p),
            "Label files 0123456789ab; hand pairs in 2 scenes (5 pairs set by hand, 0 rocks excluded); 412 scenes "
            "reviewed, 0 pairs checked as correct.");
}

}  // namespace
}  // namespace ipd
