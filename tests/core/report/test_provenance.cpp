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

// Every format of `ipd table` carries the provenance: CSV as the same columns on every row (any CSV reader
// keeps them), Markdown and LaTeX as a footnote line under the table.
TEST(Provenance, TableCsvMarkdownAndLatexCarryIt) {
  test::TempDir d;
  test::write_two_rock_study(d);
  write_hand_pairs(d);
  auto r = test::run_ipd("table " + d.path() + " --format csv --no-cache --bootstrap 0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(
      r.out,
      "model,trained_on,a,b,ipd,pairs,unpaired_a,unpaired_b,scenes,involves_training_domain,ci_low,ci_high,se,"
      "reason,label_fingerprint,scenes_with_hand_pairs,pairs_set_by_hand,rocks_excluded,scenes_reviewed,pairs_checked,"
      "scenes_with_stale_hand_pairs\n"
      "det,,real,synth,0.666667,1,0,1,1,true,,,,,d189a61c07b5,1,1,1,0,0,0\n");
  r = test::run_ipd("table " + d.path() + " --format markdown --no-cache --bootstrap 0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string note = "Label files d189a61c07b5; hand pairs in 1 scene (1 pair set by hand, 1 rock excluded).";
  EXPECT_EQ(r.out.substr(r.out.size() - note.size() - 2), "\n" + note + "\n") << r.out;
  r = test::run_ipd("table " + d.path() + " --format latex --no-cache --bootstrap 0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.substr(r.out.size() - note.size() - 25), "\\par{\\footnotesize " + note + "\\par}\n") << r.out;
}

// `ipd compare` prints the note after its sentence and its JSON carries the object; `ipd breakdown` the same
// in text, as CSV columns and as a JSON object.
TEST(Provenance, CompareAndBreakdownCarryIt) {
  test::TempDir d;
  test::write_two_rock_study(d);
  test::write_text(d / "other/labels/s1.txt", "0 0.6 0.6 0.1 0.1\n0 0.2 0.2 0.1 0.1\n");
  test::write_text(d / "other/predictions/det/s1.txt", "0 0.2 0.2 0.1 0.1 0.9\n");
  write_hand_pairs(d);
  const std::string note = "Label files c46076aa055d; hand pairs in 1 scene (1 pair set by hand, 1 rock excluded).\n";
  auto r = test::run_ipd("compare " + d.path() + " --ref real --a synth --b other --no-cache");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_GE(r.out.size(), note.size());
  EXPECT_EQ(r.out.substr(r.out.size() - note.size()), note) << r.out;
  r = test::run_ipd("compare " + d.path() + " --ref real --a synth --b other --no-cache --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json p = nlohmann::json::parse(r.out).at("provenance");
  EXPECT_EQ(p.at("pairs_set_by_hand"), 1);
  EXPECT_EQ(p.at("label_fingerprint"), "c46076aa055d");
  r = test::run_ipd("breakdown " + d.path() + " --domains real,synth --bins 1 --bootstrap 0 --no-cache");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.substr(r.out.size() - note.size()), note) << r.out;  // the fingerprint covers every domain
  r = test::run_ipd("breakdown " + d.path() + " --domains real,synth --bins 1 --bootstrap 0 --no-cache --format csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.substr(0, r.out.find('\n')),
            "model,trained_on,a,b,bin,low,high,ipd,ci_low,ci_high,pairs,scenes,label_fingerprint,"
            "scenes_with_hand_pairs,pairs_set_by_hand,rocks_excluded,scenes_reviewed,pairs_checked,"
            "scenes_with_stale_hand_pairs");
  EXPECT_NE(r.out.find(",c46076aa055d,1,1,1,0,0,0\n"), std::string::npos) << r.out;
  r = test::run_ipd("breakdown " + d.path() + " --domains real,synth --bins 1 --bootstrap 0 --no-cache --format json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out).at("provenance").at("rocks_excluded"), 1);
}

// The rock export: each row says whether its pair was set by hand (source) and whether its rock was left
// out on purpose (excluded), and ends with the provenance columns (CSV) or keys (JSON).
//   real rock 0 <-> synth rock 1 by hand: perf 1 (exact prediction) and 1/3 (shifted by half its width).
//   real rock 1: excluded; its perf 0 (no prediction overlaps it). synth rock 0: unpaired, perf 0.
TEST(Provenance, RockExportRowsSayHandAndExcluded) {
  test::TempDir d;
  test::write_two_rock_study(d);
  write_hand_pairs(d);
  auto r = test::run_ipd("export rocks " + d.path() + " --unpaired --no-cache");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out,
            "model,trained_on,a,b,scene,class,index_a,index_b,perf_a,perf_b,diff,cx_a,cy_a,w_a,h_a,cx_b,cy_b,w_b,h_b,"
            "residual_px,source,excluded,mask_area_a,mask_area_b,label_fingerprint,scenes_with_hand_pairs,"
            "pairs_set_by_hand,rocks_excluded,scenes_reviewed,pairs_checked,scenes_with_stale_hand_pairs\n"
            "det,,real,synth,s1,0,0,1,1,0.333333333333,0.666666666667,0.2,0.2,0.1,0.1,0.2,0.2,0.1,0.1,,hand,false,,,"
            "d189a61c07b5,1,1,1,0,0,0\n"
            "det,,real,synth,s1,0,1,,0,,,0.6,0.6,0.1,0.1,,,,,,hand,true,,,d189a61c07b5,1,1,1,0,0,0\n"
            "det,,real,synth,s1,0,,0,,0,,,,,,0.6,0.6,0.1,0.1,,hand,false,,,d189a61c07b5,1,1,1,0,0,0\n");
  r = test::run_ipd("export rocks " + d.path() + " --unpaired --no-cache --format json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json rows = nlohmann::json::parse(r.out);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[1].at("excluded"), true);
  EXPECT_EQ(rows[0].at("excluded"), false);
  EXPECT_EQ(rows[2].at("label_fingerprint"), "d189a61c07b5");
  EXPECT_EQ(rows[2].at("pairs_set_by_hand"), 1);
}

// The machine-readable fields and which provenance counts as edited.
TEST(Provenance, CsvFieldsFollowTheJsonAndEditedMeansAHandPairOrAnExcludedRock) {
  Provenance p = scene_provenance(false, 4, 0, "0123456789ab");
  EXPECT_FALSE(provenance_edited(p));
  EXPECT_EQ(p.pairs_set_by_hand, 0);
  using Fields = std::vector<std::pair<std::string, std::string>>;
  EXPECT_EQ(provenance_csv_fields(p), (Fields{{"label_fingerprint", "0123456789ab"},
                                              {"scenes_with_hand_pairs", "0"},
                                              {"pairs_set_by_hand", "0"},
                                              {"rocks_excluded", "0"},
                                              {"scenes_reviewed", "0"},
                                              {"pairs_checked", "0"},
                                              {"scenes_with_stale_hand_pairs", "0"}}));
  p = scene_provenance(true, 4, 1, "0123456789ab");
  EXPECT_TRUE(provenance_edited(p));
  EXPECT_EQ(provenance_note(p),
            "Label files 0123456789ab; hand pairs in 1 scene (4 pairs set by hand, 1 rock excluded).");
  EXPECT_TRUE(provenance_edited(scene_provenance(false, 4, 1, "")));  // an excluded rock alone is an edit
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

// A pairs file whose stored rock left its label file is set aside (`--skip-bad-lines`: registration counts
// there); the note says so, so "no hand pairs" never hides an edit that was dropped, and figures print it.
TEST(Provenance, StaleHandPairsSetAsideAreCounted) {
  test::TempDir d;
  test::write_two_rock_study(d);
  write_hand_pairs(d);
  test::write_text(d / "synth/labels/s1.txt", "0 0.6 0.6 0.1 0.1\n0 0.3 0.2 0.1 0.1\n");  // rock 1 moved
  const auto r = test::run_ipd("table " + d.path() + " --format json --no-cache --skip-bad-lines");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json p = nlohmann::json::parse(r.out).at("provenance");
  EXPECT_EQ(p.at("scenes_with_hand_pairs"), 0);
  EXPECT_EQ(p.at("scenes_with_stale_hand_pairs"), 1);
  EXPECT_NE(r.err.find("; no hand pairs (every pair from registration); stale hand pairs not used in 1 scene "
                       "(registration counts there).\n"),
            std::string::npos)
      << r.err;
  // The studio counts the same, until "reset to automatic" discards the file.
  Session session = Session::open(d.path());
  EXPECT_EQ(session_provenance(session).scenes_with_stale_hand_pairs, 1);
  EXPECT_EQ(session_provenance(session).scenes_with_hand_pairs, 0);
  session.apply(0, Edit::reset());
  EXPECT_EQ(session_provenance(session).scenes_with_stale_hand_pairs, 0);
  Provenance q;
  q.scenes_with_stale_hand_pairs = 2;
  EXPECT_TRUE(provenance_edited(q));
  EXPECT_EQ(provenance_note(q),
            "Label files ; no hand pairs (every pair from registration); stale hand pairs not used in 2 scenes "
            "(registration counts there).");
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
