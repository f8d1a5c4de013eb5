// IPD of a tiny hand-made study, worked out by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/ipd/ipd.h"
#include "core/report/table_format.h"
#include "core/session/session.h"
#include "core/util/atomic_file.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

// real rock 0 at (0.2, 0.2), rock 1 at (0.6, 0.6); synth lists them in the other order.
// det: real rock 0 found exactly (IoU 1), real rock 1 found shifted by half a width (IoU 1/3, conf 0.4);
//      synth rock 1 (= real 0) found shifted (IoU 1/3), synth rock 0 (= real 1) not found (0).
// Pairs (0,1) and (1,0): |1 - 1/3| = 2/3 and |1/3 - 0| = 1/3, so IPD = 1/2.
void write_tiny_study(const test::TempDir& d, const std::string& yaml = "") {
  test::write_text(d / "real/labels/s1.txt", "0 0.2 0.2 0.1 0.1\n0 0.6 0.6 0.1 0.1\n");
  test::write_text(d / "synth/labels/s1.txt", "0 0.6 0.6 0.1 0.1\n0 0.2 0.2 0.1 0.1\n");
  test::write_text(d / "real/predictions/det/s1.txt", "0 0.2 0.2 0.1 0.1 0.9\n0 0.65 0.6 0.1 0.1 0.4\n");
  test::write_text(d / "synth/predictions/det/s1.txt", "0 0.25 0.2 0.1 0.1 0.8\n");
  test::write_text(d / "real/labels/only_real.txt", "0 0.5 0.5 0.1 0.1\n");
  test::write_text(d / "study.yaml", yaml + "image_size: [1000, 1000]\n");  // square pictures, said so
}

CrossTable table_of(const std::string& root, RegistrationMethod method = RegistrationMethod::kConsensus) {
  TableOptions o;
  o.registration.method = method;
  return compute_cross_table(load_labels(open_study(root)), o);
}

TEST(Ipd, TinyStudyWorkedByHand) {
  test::TempDir d;
  write_tiny_study(d);
  for (auto method : {RegistrationMethod::kConsensus, RegistrationMethod::kPaper, RegistrationMethod::kCpd}) {
    const CrossTable t = table_of(d.path(), method);
    ASSERT_EQ(t.cells.size(), 1u);
    const TableCell& c = t.cells[0];
    EXPECT_EQ(c.a, "real");
    EXPECT_EQ(c.b, "synth");
    EXPECT_NEAR(c.ipd, 0.5, 1e-12) << to_string(method);
    EXPECT_EQ(c.pairs, 2);
    EXPECT_EQ(c.unpaired_a, 0);
    EXPECT_EQ(c.unpaired_b, 0);
    EXPECT_EQ(c.scenes, 1);
    ASSERT_EQ(c.per_scene.size(), 1u);
    EXPECT_NEAR(c.per_scene[0].perf_a[0], 1.0, 1e-12);
    EXPECT_NEAR(c.per_scene[0].perf_b[0], 1.0 / 3, 1e-12);
    ASSERT_EQ(t.warnings.size(), 1u);
    EXPECT_EQ(t.warnings[0], "1 scene(s) of 'real' have no counterpart in 'synth' and are skipped: only_real");
  }
}

// synth's prediction file of s2 is missing while its folder holds s1's: s2 reads as a picture without
// detections (real's exact hit on s2's rock against nothing: |1 - 0|), which YOLOv5 would write that way too, so
// the table counts it and says so, as the studio's Problems list does.
TEST(Ipd, AMissingPredictionFileIsSaidNotSilentlyReadAsNoDetections) {
  test::TempDir d;
  write_tiny_study(d);
  test::write_text(d / "real/labels/s2.txt", "0 0.4 0.4 0.1 0.1\n");
  test::write_text(d / "synth/labels/s2.txt", "0 0.4 0.4 0.1 0.1\n");
  test::write_text(d / "real/predictions/det/s2.txt", "0 0.4 0.4 0.1 0.1 0.9\n");
  const CrossTable t = table_of(d.path());
  ASSERT_EQ(t.cells.size(), 1u);
  EXPECT_NEAR(t.cells[0].ipd, (2.0 / 3 + 1.0 / 3 + 1) / 3, 1e-12);
  const std::string said = "model 'det' has no prediction file for 1 scene(s) of 'synth' (in " +
                           d / "synth/predictions/det" +
                           "/), each read as a picture without detections, as YOLOv5 writes no file for one: s2";
  ASSERT_EQ(t.warnings.size(), 2u);
  EXPECT_EQ(t.warnings[1], said);
  const Session s(load_labels(open_study(d.path())));
  const auto& problems = s.problems();
  EXPECT_EQ(std::count_if(problems.begin(), problems.end(), [&](const Problem& p) { return p.to_string() == said; }),
            1);
}

TEST(Ipd, ConfidenceThresholdDropsWeakPredictions) {
  test::TempDir d;
  write_tiny_study(d, "conf_threshold: 0.5\n");
  // real rock 1's only prediction (conf 0.4) is gone: diffs 2/3 and 0.
  EXPECT_NEAR(table_of(d.path()).cells[0].ipd, 1.0 / 3, 1e-12);
}

TEST(Ipd, FixedPairsReplaceRegistrationInEitherNameOrder) {
  test::TempDir d;
  write_tiny_study(d);
  // Written as synth__real: [synth 1, real 0], i.e. real 0 <-> synth 1 only.
  test::write_text(d / "pairs/synth__real/s1.json", R"({"pairs": [[1, 0]]})");
  const CrossTable t = table_of(d.path());
  EXPECT_NEAR(t.cells[0].ipd, 2.0 / 3, 1e-12);
  EXPECT_EQ(t.cells[0].pairs, 1);
  EXPECT_EQ(t.cells[0].unpaired_a, 1);
  EXPECT_EQ(t.cells[0].unpaired_b, 1);
  EXPECT_EQ(t.fixed_scenes, 1);
  EXPECT_EQ(t.registrations, 0);
}

TEST(Ipd, ExcludedRocksLeaveTheIpd) {
  test::TempDir d;
  write_tiny_study(d);
  test::write_text(d / "pairs/real__synth/s1.json", R"({"pairs": [[0, 1], [1, 0]], "excluded_a": [1]})");
  const CrossTable t = table_of(d.path());
  EXPECT_NEAR(t.cells[0].ipd, 2.0 / 3, 1e-12);
  EXPECT_EQ(t.cells[0].pairs, 1);
}

// The scene counts the GUI's header shows (Session::summary) and `ipd table` sums: hand-computed.
TEST(Ipd, SceneContributionCountsAnExcludedPairAsNeitherCountedNorUnpaired) {
  const std::vector<double> pa = {0.9, 0.5, 0.2}, pb = {0.8, 0.1, 0.4, 0.3};
  const RockPairs pairs = {{0, 0}, {1, 1}, {2, 2}};
  // B rock 2 (index 1) excluded: pair (1, 1) leaves the IPD; A rock 1 keeps its partner, so it is not unpaired.
  SceneIpd s = scene_contribution("s", pairs, {}, {1}, pa, pb);
  EXPECT_EQ(s.pairs, 2);
  EXPECT_NEAR(s.sum_abs_diff, 0.1 + 0.2, 1e-12);
  EXPECT_NEAR(s.ipd(), 0.15, 1e-12);
  EXPECT_EQ(s.unpaired_a, 0);
  EXPECT_EQ(s.unpaired_b, 1);  // B rock 4 only
  EXPECT_EQ(s.counted, (RockPairs{{0, 0}, {2, 2}}));
  // The same from the A side, plus an excluded rock that has no pair: not unpaired either.
  s = scene_contribution("s", pairs, {1}, {3}, pa, pb);
  EXPECT_EQ(s.pairs, 2);
  EXPECT_EQ(s.unpaired_a, 0);
  EXPECT_EQ(s.unpaired_b, 0);
  // No exclusions: B rock 4 is the one unpaired rock; a rock listed in two pairs counts once.
  s = scene_contribution("s", {{0, 0}, {0, 3}, {1, 1}}, {}, {}, pa, pb);
  EXPECT_EQ(s.pairs, 2);
  EXPECT_EQ(s.unpaired_a, 1);
  EXPECT_EQ(s.unpaired_b, 2);
}

TEST(Ipd, BadFixedPairsNameTheFile) {
  test::TempDir d;
  write_tiny_study(d);
  const std::string f = d / "pairs/real__synth/s1.json";
  test::write_text(f, R"({"pairs": [[0, 5]]})");
  try {
    table_of(d.path());
    FAIL() << "expected an error";
  } catch (const StudyError& e) {
    EXPECT_EQ(std::string(e.what()), f + ": pair 1 [0, 5] is out of range: the images have 2 and 2 rocks");
  }
  test::write_text(f, R"({"pairs": [[0, 1], [0, 0]]})");
  EXPECT_THROW(table_of(d.path()), StudyError);
  test::write_text(f, R"({"pairs": [[0, 1)");
  try {
    table_of(d.path());
    FAIL() << "expected an error";
  } catch (const StudyError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(f + ": invalid JSON at byte", 0), 0u) << e.what();
  }
}

TEST(Ipd, NoPairsGivesNanNotACrash) {
  SceneIpd s;
  EXPECT_TRUE(std::isnan(s.ipd()));
  ScenePairing p;
  const SceneIpd e = scene_ipd(p, {}, {}, {}, {}, Task::kDetect);
  EXPECT_EQ(e.pairs, 0);
  EXPECT_TRUE(std::isnan(e.ipd()));
}

TEST(Ipd, FixedPairsRoundTripAtomically) {
  test::TempDir d;
  write_tiny_study(d);
  const Study s = open_study(d.path());
  FixedPairs fp;
  fp.pairs = {{0, 1}, {1, 0}};
  fp.excluded_b = {0};
  const StudyLabels labels = load_labels(s);
  const auto& real = labels.gt_of("real", "s1").boxes;
  const auto& synth = labels.gt_of("synth", "s1").boxes;
  write_fixed_pairs(s, "real", "synth", "s1", fp, real, synth);
  EXPECT_EQ(read_file(d / "pairs/real__synth/s1.json"),
            "{\"excluded_b\":[0],\"pairs\":[[0,1],[1,0]],\"rocks_a\":[[0,0.2,0.2,0.1,0.1],[1,0.6,0.6,0.1,0.1]],"
            "\"rocks_b\":[[0,0.6,0.6,0.1,0.1],[1,0.2,0.2,0.1,0.1]]}\n");
  const auto back = read_fixed_pairs(s, "real", "synth", "s1", real, synth);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->pairs, fp.pairs);
  EXPECT_EQ(back->excluded_b, fp.excluded_b);
  // Read from the other side, indices swap.
  const auto swapped = read_fixed_pairs(s, "synth", "real", "s1", synth, real);
  EXPECT_EQ(swapped->pairs, (RockPairs{{0, 1}, {1, 0}}));
  EXPECT_EQ(swapped->excluded_a, (std::vector<int>{0}));
}

}  // namespace
}  // namespace ipd
