// The fold benchmark's parts: terrains from file names, folds holding every terrain out once, size bands and
// the counts per band, the strict truth carried through a case.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "app/bench/fold_benchmark.h"

namespace ipd {
namespace {

Box box_px(double cx, double cy, double w, double h) {  // pixels of a 1936 x 1216 picture
  Box b;
  b.cx = cx / 1936, b.cy = cy / 1216, b.w = w / 1936, b.h = h / 1216;
  return b;
}

TEST(FoldBenchmark, TerrainFromTheFileName) {
  EXPECT_EQ(terrain_of("/data/labels/Terrain05/05_A_off_30_L_1024.txt"), 5);
  EXPECT_EQ(terrain_of("12_B_on_no_R_64.txt"), 12);
  EXPECT_EQ(terrain_of("Terrain05.txt"), -1);  // no leading number
  EXPECT_EQ(terrain_of("05.txt"), -1);         // a number, but not of the NN_ form
}

TEST(FoldBenchmark, EveryTerrainIsHeldOutExactlyOnce) {
  std::multiset<int> held_out;
  for (const auto& f : benchmark_folds()) held_out.insert(f.validation.begin(), f.validation.end());
  EXPECT_EQ(held_out, (std::multiset<int>{1, 2, 3, 4, 5, 7, 8}));
}

TEST(FoldBenchmark, PairsSplitByTheirTerrain) {
  LabelPair p1, p5;
  p1.file_a = "labels/Terrain01/01_A_off_30_L_1024.txt";
  p5.file_a = "labels/Terrain05/05_A_off_30_L_1024.txt";
  const Fold fold{"A", {5, 7, 8}};
  const auto validation = fold_pairs({p1, p5}, fold, true), tuning = fold_pairs({p1, p5}, fold, false);
  ASSERT_EQ(validation.size(), 1u);
  ASSERT_EQ(tuning.size(), 1u);
  EXPECT_EQ(validation[0].file_a, p5.file_a);
  EXPECT_EQ(tuning[0].file_a, p1.file_a);
}

TEST(FoldBenchmark, SizeBandsByTheGeometricMeanOfTheSides) {
  EXPECT_EQ(size_band(box_px(500, 500, 20, 40), 1936, 1216), 0);   // sqrt(800) = 28.3
  EXPECT_EQ(size_band(box_px(500, 500, 30, 30), 1936, 1216), 1);   // 30: the middle band starts there
  EXPECT_EQ(size_band(box_px(500, 500, 70, 70), 1936, 1216), 1);   // 70: still the middle band
  EXPECT_EQ(size_band(box_px(500, 500, 50, 120), 1936, 1216), 2);  // sqrt(6000) = 77.5
  EXPECT_STREQ(size_band_name(0), "< 30 px");
  EXPECT_STREQ(size_band_name(2), "> 70 px");
}

TEST(FoldBenchmark, CountsPerBandOfSideARock) {
  // A: rock 0 small (20 px), rock 1 medium (50 px), rock 2 large (100 px).
  const std::vector<Box> a = {box_px(100, 100, 20, 20), box_px(300, 300, 50, 50), box_px(600, 600, 100, 100)};
  const RockPairs truth = {{0, 0}, {1, 1}, {2, 2}};
  const RockPairs found = {{0, 1}, {1, 1}, {2, 2}};  // the small rock paired with the wrong partner
  BandCounts c;
  count_by_size_band(found, truth, a, 1936, 1216, &c);
  EXPECT_EQ(c.found[0], 1);
  EXPECT_EQ(c.truth[0], 1);
  EXPECT_EQ(c.common[0], 0);
  EXPECT_EQ(c.common[1], 1);
  EXPECT_EQ(c.common[2], 1);
  count_by_size_band(found, truth, a, 1936, 1216, &c);  // counts add up over cases
  EXPECT_EQ(c.truth[2], 2);
}

TEST(FoldBenchmark, StrictTruthFollowsTheCaseRows) {
  // Rock 0 overlaps its partner by IoU 0.6 (strict pair), rock 1 only by 0.2 (paired, but not strictly).
  LabelPair p;
  p.file_a = "01_A_off_30_L_1.txt";
  p.file_b = "01_A_off_180_L_1.txt";
  p.a = {box_px(300, 300, 100, 100), box_px(1200, 800, 100, 100)};
  p.b = {box_px(300, 325, 100, 100), box_px(1200, 866.67, 100, 100)};
  p.truth = {{0, 0}, {1, 1}};
  p.strict_truth = {{0, 0}};
  MisalignmentRange none = small_misalignment();
  none.hidden = 0, none.noise = 0;
  const auto c = make_case(p, none, 3);
  ASSERT_EQ(c.truth.size(), 2u);
  ASSERT_EQ(c.strict_truth.size(), 1u);
  // B's rows are shuffled: the strict pair is the one whose B box is A's first rock's partner.
  const int b0 = c.strict_truth[0].second;
  EXPECT_EQ(c.strict_truth[0].first, 0);
  EXPECT_TRUE(std::find(c.truth.begin(), c.truth.end(), std::make_pair(0, b0)) != c.truth.end());
}

}  // namespace
}  // namespace ipd
