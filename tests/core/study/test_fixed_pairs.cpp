// Hand pairs are bound to rocks, not to row numbers: a label file re-exported with its rows reordered, a
// row inserted or a paired rock removed never moves a hand pair onto another rock without a word.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "core/ipd/ipd.h"
#include "core/session/session.h"
#include "core/util/atomic_file.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

// real rock 0 at (0.2, 0.2) (perf 1), rock 1 at (0.6, 0.6) (perf 1/3); synth rock 0 at (0.6, 0.6) (perf 0),
// rock 1 at (0.2, 0.2) (perf 1/3). Hand pair real 0 <-> synth 1 only: IPD |1 - 1/3| = 2/3.
const char* kReal = "0 0.2 0.2 0.1 0.1\n0 0.6 0.6 0.1 0.1\n";
const char* kSynth = "0 0.6 0.6 0.1 0.1\n0 0.2 0.2 0.1 0.1\n";
const char* kHandPairs =
    R"({"pairs": [[0, 1]], "rocks_a": [[0, 0.2, 0.2, 0.1, 0.1]], "rocks_b": [[1, 0.2, 0.2, 0.1, 0.1]]})";

void write_study_fixed_pairs(const test::TempDir& d, const std::string& real, const std::string& synth) {
  test::write_text(d / "real/labels/s1.txt", real);
  test::write_text(d / "synth/labels/s1.txt", synth);
  test::write_text(d / "real/predictions/det/s1.txt", "0 0.2 0.2 0.1 0.1 0.9\n0 0.65 0.6 0.1 0.1 0.4\n");
  test::write_text(d / "synth/predictions/det/s1.txt", "0 0.25 0.2 0.1 0.1 0.8\n");
  test::write_text(d / "study.yaml", "image_size: [1000, 1000]\n");  // square pictures, said so
}

CrossTable table_of_fixed_pairs(const std::string& root) {
  return compute_cross_table(load_labels(open_study(root)), {});
}

TEST(FixedPairsBinding, RocksAtTheirRowsReadWithoutAWord) {
  test::TempDir d;
  write_study_fixed_pairs(d, kReal, kSynth);
  test::write_text(d / "pairs/real__synth/s1.json", kHandPairs);
  const CrossTable t = table_of_fixed_pairs(d.path());
  EXPECT_NEAR(t.cells[0].ipd, 2.0 / 3, 1e-12);
  EXPECT_EQ(t.fixed_scenes, 1);
  EXPECT_TRUE(t.pairs_problems.empty());
  EXPECT_TRUE(t.warnings.empty());
}

TEST(FixedPairsBinding, ReorderedRowsKeepThePairsOnTheirRocks) {
  test::TempDir d;
  // real re-exported with its two rows swapped: by row number the pair would be real (0.6, 0.6) <-> synth 1,
  // |1/3 - 1/3| = 0.
  write_study_fixed_pairs(d, "0 0.6 0.6 0.1 0.1\n0 0.2 0.2 0.1 0.1\n", kSynth);
  const std::string f = d / "pairs/real__synth/s1.json";
  test::write_text(f, kHandPairs);
  const CrossTable t = table_of_fixed_pairs(d.path());
  EXPECT_NEAR(t.cells[0].ipd, 2.0 / 3, 1e-12);
  ASSERT_EQ(t.cells[0].per_scene.size(), 1u);
  EXPECT_EQ(t.cells[0].per_scene[0].counted, (RockPairs{{1, 1}}));
  ASSERT_EQ(t.pairs_problems.size(), 1u);
  EXPECT_EQ(t.pairs_problems[0].file, f);
  EXPECT_EQ(t.pairs_problems[0].line, 0);
  EXPECT_FALSE(t.pairs_problems[0].unusable);
  const std::string message =
      "1 hand-paired rock(s) changed rows in their label files and were found again by their boxes: real rock 1 -> 2";
  EXPECT_EQ(t.pairs_problems[0].message, message);
  ASSERT_EQ(t.warnings.size(), 1u);
  EXPECT_EQ(t.warnings[0], f + ": " + message);
}

TEST(FixedPairsBinding, AnInsertedRowShiftsNoPair) {
  test::TempDir d;
  // A new synth rock at the top: the paired synth rock (0.2, 0.2) is row 2 now.
  write_study_fixed_pairs(d, kReal, "0 0.9 0.9 0.05 0.05\n" + std::string(kSynth));
  test::write_text(d / "pairs/real__synth/s1.json", kHandPairs);
  const CrossTable t = table_of_fixed_pairs(d.path());
  EXPECT_NEAR(t.cells[0].ipd, 2.0 / 3, 1e-12);
  EXPECT_EQ(t.cells[0].per_scene[0].counted, (RockPairs{{0, 2}}));
  EXPECT_EQ(t.cells[0].unpaired_a, 1);
  EXPECT_EQ(t.cells[0].unpaired_b, 2);
  ASSERT_EQ(t.pairs_problems.size(), 1u);
  EXPECT_EQ(
      t.pairs_problems[0].message,
      "1 hand-paired rock(s) changed rows in their label files and were found again by their boxes: synth rock 2 -> 3");
}

TEST(FixedPairsBinding, ExcludedRocksAndTheOtherNameOrderAreBoundToo) {
  test::TempDir d;
  write_study_fixed_pairs(d, "0 0.6 0.6 0.1 0.1\n0 0.2 0.2 0.1 0.1\n", kSynth);  // real rows swapped
  // Saved as synth__real: first index synth. Pairs synth 1 <-> real 0 and synth 0 <-> real 1; real 1 excluded.
  test::write_text(d / "pairs/synth__real/s1.json",
                   R"({"pairs": [[1, 0], [0, 1]], "excluded_b": [1],
                       "rocks_a": [[0, 0.6, 0.6, 0.1, 0.1], [1, 0.2, 0.2, 0.1, 0.1]],
                       "rocks_b": [[0, 0.2, 0.2, 0.1, 0.1], [1, 0.6, 0.6, 0.1, 0.1]]})");
  const CrossTable t = table_of_fixed_pairs(d.path());
  // real (0.6, 0.6) is excluded, so only real (0.2, 0.2) <-> synth (0.2, 0.2) counts: 2/3.
  EXPECT_NEAR(t.cells[0].ipd, 2.0 / 3, 1e-12);
  EXPECT_EQ(t.cells[0].per_scene[0].counted, (RockPairs{{1, 1}}));
  EXPECT_EQ(t.pairings[0][0].excluded_a, (std::vector<int>{0}));
  ASSERT_EQ(t.pairs_problems.size(), 1u);
  EXPECT_EQ(t.pairs_problems[0].message,
            "2 hand-paired rock(s) changed rows in their label files and were found again by their boxes: "
            "real rock 1 -> 2, 2 -> 1");
}

TEST(FixedPairsBinding, ARemovedRockMakesTheScenesHandPairsUnusable) {
  test::TempDir d;
  write_study_fixed_pairs(d, kReal, "0 0.6 0.6 0.1 0.1\n");  // the paired synth rock (0.2, 0.2) is gone
  const double registration_only = table_of_fixed_pairs(d.path()).cells[0].ipd;
  const std::string f = d / "pairs/real__synth/s1.json";
  test::write_text(f, kHandPairs);
  const CrossTable t = table_of_fixed_pairs(d.path());
  EXPECT_EQ(t.fixed_scenes, 0);
  EXPECT_EQ(t.registrations, 1);
  EXPECT_FALSE(t.pairings[0][0].fixed);
  // The registration's pairs, not the hand pairs (NaN when registration pairs nothing).
  EXPECT_TRUE(t.cells[0].ipd == registration_only || (std::isnan(t.cells[0].ipd) && std::isnan(registration_only)))
      << t.cells[0].ipd << " vs " << registration_only;
  EXPECT_EQ(t.pairings[0][0].pairs, t.pairings[0][0].registration.pairs);
  ASSERT_EQ(t.pairs_problems.size(), 1u);
  EXPECT_TRUE(t.pairs_problems[0].unusable);
  const std::string message =
      "hand pairs not used (registration counts instead): a stored box is no longer in its label file (moved or "
      "deleted): the box saved from line 2 "
      "(0.2 0.2 0.1 0.1) of 'synth' (" +
      d / "synth/labels/s1.txt" + ")";
  EXPECT_EQ(t.pairs_problems[0].message, message);
  EXPECT_TRUE(t.warnings.empty());  // an error, not a warning: the CLI decides
  // Callers without a problem list get the error itself.
  const StudyLabels labels = load_labels(open_study(d.path()));
  try {
    read_fixed_pairs(labels.study, "real", "synth", "s1", labels.gt_of("real", "s1").boxes,
                     labels.gt_of("synth", "s1").boxes);
    FAIL() << "expected an error";
  } catch (const StudyError& e) {
    EXPECT_EQ(std::string(e.what()), f + ": " + message);
  }
}

// A box that moved far below what a label can tell apart (a re-export rounding the last of its 6 decimals
// the other way) is the same rock: the hand pairs still count, without a word. Ten units of that decimal
// (kSameRockTolerance) is the bound; past it the rock is gone.
TEST(FixedPairsBinding, ABoxMovedFarBelowLabelPrecisionIsTheSameRock) {
  test::TempDir d;
  write_study_fixed_pairs(d, kReal, "0 0.6 0.6 0.1 0.1\n0 0.200001 0.2 0.1 0.1\n");
  test::write_text(d / "pairs/real__synth/s1.json", kHandPairs);
  const CrossTable t = table_of_fixed_pairs(d.path());
  EXPECT_EQ(t.fixed_scenes, 1);
  EXPECT_EQ(t.cells[0].per_scene[0].counted, (RockPairs{{0, 1}}));
  EXPECT_TRUE(t.pairs_problems.empty());
  // 9e-6 in w (within), then 1.1e-5 in h (beyond): unusable, naming the stored box.
  test::write_text(d / "synth/labels/s1.txt", "0 0.6 0.6 0.1 0.1\n0 0.2 0.2 0.100009 0.1\n");
  EXPECT_TRUE(table_of_fixed_pairs(d.path()).pairs_problems.empty());
  test::write_text(d / "synth/labels/s1.txt", "0 0.6 0.6 0.1 0.1\n0 0.2 0.2 0.1 0.100011\n");
  const CrossTable gone = table_of_fixed_pairs(d.path());
  ASSERT_EQ(gone.pairs_problems.size(), 1u);
  EXPECT_TRUE(gone.pairs_problems[0].unusable);
  EXPECT_EQ(gone.pairs_problems[0].why_unusable,
            "a stored box is no longer in its label file (moved or deleted): the box saved from line 2 (0.2 0.2 0.1 "
            "0.1) of 'synth' (" +
                d / "synth/labels/s1.txt" + ")");
}

// A rock no longer at its row is found at the free row whose box is nearest to the stored one, not at the
// first row within the tolerance.
TEST(FixedPairsBinding, AMovedRockIsFoundAtTheNearestBoxWithinTheTolerance) {
  test::TempDir d;
  write_study_fixed_pairs(d, kReal,
                          "0 0.6 0.6 0.1 0.1\n0 0.9 0.9 0.05 0.05\n0 0.200008 0.2 0.1 0.1\n0 0.200001 0.2 0.1 0.1\n");
  test::write_text(d / "pairs/real__synth/s1.json", kHandPairs);
  const CrossTable t = table_of_fixed_pairs(d.path());
  EXPECT_EQ(t.cells[0].per_scene[0].counted, (RockPairs{{0, 3}}));
  ASSERT_EQ(t.pairs_problems.size(), 1u);
  EXPECT_EQ(
      t.pairs_problems[0].message,
      "1 hand-paired rock(s) changed rows in their label files and were found again by their boxes: synth rock 2 -> 4");
}

TEST(FixedPairsBinding, TheCliExitsOneNamingTheFileUnlessSkipBadLines) {
  test::TempDir d;
  write_study_fixed_pairs(d, kReal, "0 0.6 0.6 0.1 0.1\n");
  const std::string f = d / "pairs/real__synth/s1.json";
  test::write_text(f, kHandPairs);
  const std::string line = f +
                           ": hand pairs not used (registration counts instead): a stored box is no longer in its "
                           "label file (moved or deleted): the box saved from line 2 (0.2 0.2 0.1 0.1) of 'synth' (" +
                           d / "synth/labels/s1.txt" + ")";
  const auto strict = test::run_ipd("table --no-cache --bootstrap 0 " + d.path());
  EXPECT_EQ(strict.exit_code, 1) << strict.err;
  EXPECT_NE(strict.err.find(line + "\n"), std::string::npos) << strict.err;
  EXPECT_NE(strict.err.find("error: the hand pairs of 1 scene(s) can't be used; pair those scenes again, or pass "
                            "--skip-bad-lines to use registration for them\n"),
            std::string::npos)
      << strict.err;
  EXPECT_TRUE(strict.out.empty());
  const auto lenient = test::run_ipd("table --no-cache --bootstrap 0 --skip-bad-lines " + d.path());
  EXPECT_EQ(lenient.exit_code, 0) << lenient.err;
  EXPECT_NE(lenient.err.find("warning: " + line + "\n"), std::string::npos) << lenient.err;
}

TEST(FixedPairsBinding, AFigureOfTheSceneSaysSoToo) {
  test::TempDir d;
  write_study_fixed_pairs(d, kReal, "0 0.6 0.6 0.1 0.1\n");
  const std::string f = d / "pairs/real__synth/s1.json";
  test::write_text(f, kHandPairs);
  const std::string out = d / "fig.svg";
  const auto strict = test::run_ipd("figure registration " + d.path() + " --scene s1 --out " + out);
  EXPECT_EQ(strict.exit_code, 1) << strict.err;
  EXPECT_NE(
      strict.err.find(f +
                      ": hand pairs not used (registration counts instead): a stored box is no longer in "
                      "its label file (moved or deleted): the box saved from line 2 (0.2 0.2 0.1 0.1) of 'synth' (" +
                      d / "synth/labels/s1.txt" + ") (pass --skip-bad-lines to draw registration's pairs)\n"),
      std::string::npos)
      << strict.err;
  const auto lenient = test::run_ipd("figure registration " + d.path() + " --scene s1 --skip-bad-lines --out " + out);
  EXPECT_EQ(lenient.exit_code, 0) << lenient.err;
  EXPECT_NE(lenient.err.find("warning: " + f + ": hand pairs not used"), std::string::npos) << lenient.err;
}

TEST(FixedPairsBinding, FilesWithoutBoxesLoadByIndexAndGainBoxesOnTheNextSave) {
  test::TempDir d;
  write_study_fixed_pairs(d, kReal, kSynth);
  const std::string f = d / "pairs/real__synth/s1.json";
  test::write_text(f, R"({"pairs": [[0, 1]]})");
  EXPECT_NEAR(table_of_fixed_pairs(d.path()).cells[0].ipd, 2.0 / 3, 1e-12);
  Session s = Session::open(d.path());
  EXPECT_NEAR(s.cell().ipd, 2.0 / 3, 1e-12);
  EXPECT_TRUE(s.pairs_problems().empty());
  run_save_job(s.apply(0, Edit::toggle_exclude(Side::kB, 0)));
  EXPECT_EQ(read_file(f),
            "{\"excluded_b\":[0],\"pairs\":[[0,1]],\"rocks_a\":[[0,0.2,0.2,0.1,0.1]],"
            "\"rocks_b\":[[0,0.6,0.6,0.1,0.1],[1,0.2,0.2,0.1,0.1]]}\n");
  // Now bound: reordering the synth rows keeps the pair on synth (0.2, 0.2).
  test::write_text(d / "synth/labels/s1.txt", "0 0.2 0.2 0.1 0.1\n0 0.6 0.6 0.1 0.1\n");
  const CrossTable t = table_of_fixed_pairs(d.path());
  EXPECT_NEAR(t.cells[0].ipd, 2.0 / 3, 1e-12);
  EXPECT_EQ(t.pairings[0][0].excluded_b, (std::vector<int>{1}));
}

TEST(FixedPairsBinding, TheSessionListsProblemsAndFlagsUnusableScenes) {
  test::TempDir d;
  write_study_fixed_pairs(d, kReal, "0 0.6 0.6 0.1 0.1\n");
  const std::string f = d / "pairs/real__synth/s1.json";
  test::write_text(f, kHandPairs);
  const Session s = Session::open(d.path());
  ASSERT_EQ(s.scenes().size(), 1u);
  EXPECT_TRUE(s.scenes()[0].pairs_unusable);
  EXPECT_FALSE(s.scenes()[0].edited);
  EXPECT_EQ(s.scenes()[0].current.pairs, s.scenes()[0].automatic.pairs);
  const std::vector<PairsProblem> problems = s.pairs_problems();
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0].file, f);
  EXPECT_TRUE(problems[0].unusable);
}

// An edit of a scene whose pairs file no longer applies would save registration's pairs plus the edit over
// the hand pairs: it is refused, naming the file and what no longer matches, and the file is untouched.
// "reset to automatic" is the explicit way to discard it.
TEST(FixedPairsBinding, AnEditOfAStaleSceneIsRefusedAndResetDiscardsTheFile) {
  test::TempDir d;
  write_study_fixed_pairs(d, kReal, "0 0.6 0.6 0.1 0.1\n");
  const std::string f = d / "pairs/real__synth/s1.json";
  test::write_text(f, kHandPairs);
  Session s = Session::open(d.path());
  const FixedPairs before = s.scenes()[0].current;
  for (const Edit& e : {Edit::pair(1, 0), Edit::unpair(Side::kA, 0), Edit::toggle_exclude(Side::kB, 0),
                        Edit::replace(RockPairs{{0, 0}})}) {
    try {
      s.apply(0, e);
      FAIL() << "expected the edit to be refused";
    } catch (const StudyError& err) {
      EXPECT_EQ(
          std::string(err.what()),
          f +
              ": edit refused: this file's hand pairs no longer match the label files (a stored box is no "
              "longer in its label file (moved or deleted): the box saved from line 2 (0.2 0.2 0.1 0.1) of 'synth' (" +
              d / "synth/labels/s1.txt" +
              ")), and saving the edit would overwrite them. To keep them, correct the label file and open "
              "the study again; to discard them and start from registration's pairs, use \"reset to "
              "automatic\" on scene \"s1\"");
    }
  }
  EXPECT_FALSE(s.can_undo());
  ASSERT_EQ(s.problems().size(), 1u);  // listed while the file is there
  EXPECT_EQ(s.problems()[0].file, f);
  EXPECT_EQ(s.scenes()[0].current.pairs, before.pairs);
  EXPECT_EQ(read_file(f), kHandPairs);
  // Reset removes the file (checked against what was read) and makes the scene editable again.
  const SaveJob discard = s.apply(0, Edit::reset());
  EXPECT_FALSE(discard.contents.has_value());
  EXPECT_EQ(discard.path, f);
  run_save_job(discard);
  EXPECT_FALSE(fs::exists(f));
  EXPECT_FALSE(s.scenes()[0].pairs_unusable);
  EXPECT_FALSE(s.can_undo());  // nothing to take back: the scene showed these pairs before, and the file is gone
  for (const Problem& p : s.problems()) EXPECT_NE(p.file, f) << p.to_string();  // no longer listed
  // Editable: an exclusion is saved (pairing 1 with 0 again would be registration's own pairs, saved as no file).
  const SaveJob edit = s.apply(0, Edit::toggle_exclude(Side::kA, 0));
  EXPECT_TRUE(edit.contents.has_value());
}

// Undo and redo write the scene's pairs as an edit does: once the file went stale (a reload after its rock left
// the label file) they are refused too, and the file stays as it is.
TEST(FixedPairsBinding, UndoAndRedoOfAStaleSceneAreRefusedAsEditsAre) {
  test::TempDir d;
  write_study_fixed_pairs(d, kReal, kSynth);
  const std::string f = d / "pairs/real__synth/s1.json";
  test::write_text(f, kHandPairs);
  Session s = Session::open(d.path());
  run_save_job(s.apply(0, Edit::toggle_exclude(Side::kB, 1)));
  // Another program writes the file with a synth rock at (0.3, 0.3), which the label file does not have.
  const std::string stale =
      R"({"pairs": [[0, 1]], "rocks_a": [[0, 0.2, 0.2, 0.1, 0.1]], "rocks_b": [[1, 0.3, 0.3, 0.1, 0.1]]})";
  test::write_text(f, stale);
  EXPECT_TRUE(s.problems().empty());
  s.reload_scene(0, "s1");
  ASSERT_TRUE(s.scenes()[0].pairs_unusable);
  // The Problems window lists the file that went stale after opening, as it lists one stale at opening.
  ASSERT_EQ(s.problems().size(), 1u);
  EXPECT_EQ(s.problems()[0].file, f);
  EXPECT_EQ(s.problems()[0].scene, "s1");
  EXPECT_TRUE(s.problems()[0].unusable_pairs);
  EXPECT_NE(s.problems()[0].message.find("no longer in its label file"), std::string::npos) << s.problems()[0].message;
  EXPECT_THROW(s.undo(), StudyError);
  EXPECT_TRUE(s.can_undo());
  EXPECT_EQ(read_file(f), stale);
}

TEST(FixedPairsBinding, MalformedStoredRocksNameTheFile) {
  test::TempDir d;
  write_study_fixed_pairs(d, kReal, kSynth);
  const std::string f = d / "pairs/real__synth/s1.json";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"pairs": [[0, 1]], "rocks_a": [[0, 0.2, 0.2, 0.1, 0.1]], "rocks_b": []})",
       "rock 1 of 'synth' is paired or excluded but has no box in \"rocks_b\""},
      {R"({"pairs": [[0, 1]], "rocks_a": [[0, 0.2, 0.2, 0.1]]})",
       "\"rocks_a\" holds [0,0.2,0.2,0.1], expected [rock index, cx, cy, w, h]"},
      {R"({"pairs": [[0, 1]], "rocks_a": [[0, 0.2, 0.2, 0.1, 0.1], [0, 0.2, 0.2, 0.1, 0.1]]})",
       "\"rocks_a\" gives rock 0 twice"},
      {R"({"pairs": [[0, 1]], "rocks_a": {"0": 1}})", "\"rocks_a\" must be an array of [index, cx, cy, w, h]"},
  };
  for (const auto& [text, why] : cases) {
    test::write_text(f, text);
    try {
      table_of_fixed_pairs(d.path());
      ADD_FAILURE() << "expected an error for " << text;
    } catch (const StudyError& e) {
      EXPECT_EQ(std::string(e.what()), f + ": " + why);
    }
  }
}

// A rock excluded twice read as "2 rocks excluded": an error naming the file, as a rock paired twice is.
TEST(FixedPairsBinding, ARockListedTwiceIsAnErrorAsARockPairedTwiceIs) {
  test::TempDir d;
  write_study_fixed_pairs(d, kReal, kSynth);
  const std::string f = d / "pairs/real__synth/s1.json";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"pairs": [], "excluded_a": [0, 0]})", "\"excluded_a\" lists rock 0 twice"},
      {R"({"pairs": [], "excluded_b": [1, 0, 1]})", "\"excluded_b\" lists rock 1 twice"},
      {R"({"pairs": [[0, 1], [0, 0]]})", "pair 2 [0, 0] uses a rock that is already paired"},
  };
  for (const auto& [text, why] : cases) {
    test::write_text(f, text);
    try {
      table_of_fixed_pairs(d.path());
      ADD_FAILURE() << "expected an error for " << text;
    } catch (const StudyError& e) {
      EXPECT_EQ(std::string(e.what()), f + ": " + why);
    }
  }
  test::write_text(f, R"({"pairs": [], "excluded_a": [1, 0]})");
  EXPECT_EQ(table_of_fixed_pairs(d.path()).pairings[0][0].excluded_a, (std::vector<int>{0, 1}));
}

}  // namespace
}  // namespace ipd
