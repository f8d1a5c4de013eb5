// The pairing rules once centres or boxes are aligned: the paper's mutual nearest neighbours within the gate,
// and the consensus / cpd assignment on aligned-box IoU above min_pair_iou.
#include <gtest/gtest.h>

#include "core/registration/pairing.h"
#include "core/registration/registration.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

using test::box;

// A centre 0.15 from its neighbour pairs within a gate of 0.2; one 0.25 away does not (not even as the
// nearest of each other: the gate is a hard limit).
TEST(Pairing, MutualNearestNeighboursPairOnlyWithinTheGate) {
  const std::vector<Eigen::Vector2d> a = {{0, 0}, {1, 0}};
  EXPECT_EQ(mutual_nearest_pairs(a, {{0.15, 0}, {1.25, 0}}, 0.2), (RockPairs{{0, 0}}));
  EXPECT_EQ(mutual_nearest_pairs(a, {{0.2, 0}, {1, 0.1999}}, 0.2), (RockPairs{{0, 0}, {1, 1}}));  // at the gate: in
  EXPECT_TRUE(mutual_nearest_pairs(a, {{0.25, 0}}, 0.2).empty());
}

// B's one rock at 0.12 is nearest to A's rock 1 (0.02 away), though A's rock 0 also has it as its nearest
// (0.12): only the mutual pair counts, one B rock is never paired twice.
TEST(Pairing, TheNearestNeighbourMustBeMutual) {
  EXPECT_EQ(mutual_nearest_pairs({{0, 0}, {0.1, 0}}, {{0.12, 0}}, 0.2), (RockPairs{{1, 0}}));
}

// Two boxes 0.1 wide, 0.09 apart: IoU 0.001 / 0.019 = 0.053, below min_pair_iou 0.1, so not a pair even
// though each is the other's only overlap. 0.05 apart: IoU 0.333, a pair.
TEST(Pairing, ALoneOverlapBelowTheMinimumIsNoPair) {
  const std::vector<Box> a = {box(0.5, 0.5, 0.1, 0.1)};
  EXPECT_TRUE(pair_by_aligned_iou(identity_affine(), a, {box(0.59, 0.5, 0.1, 0.1)}, 0.1).empty());
  EXPECT_EQ(pair_by_aligned_iou(identity_affine(), a, {box(0.55, 0.5, 0.1, 0.1)}, 0.1), (RockPairs{{0, 0}}));
  EXPECT_NEAR(iou(a[0], box(0.59, 0.5, 0.1, 0.1)), 0.001 / 0.019, 1e-12);
}

// The paper's method pairs mutual nearest neighbours within pair_gate (0.2) of the centres' spread (0.458 here,
// so 0.092 of the width). Eight rocks, B the same but rock 3 moved 0.12 to the right: the identity fits the
// other seven exactly and rock 3 is left unpaired (twice the gate would pair it), nor is it an inlier.
TEST(Pairing, ThePaperPairsWithinTheGateOfTheSpread) {
  const double spots[8][2] = {{0.1, 0.1},   {0.5, 0.15}, {0.9, 0.1},  {0.2, 0.5},
                              {0.75, 0.55}, {0.1, 0.9},  {0.5, 0.85}, {0.9, 0.9}};
  std::vector<Box> a;
  for (const auto& s : spots) a.push_back(box(s[0], s[1], 0.04, 0.04));
  std::vector<Box> b = a;
  b[3].cx += 0.12;
  RegistrationOptions o;
  o.method = RegistrationMethod::kPaper;
  const auto r = register_rocks(a, b, o);
  EXPECT_TRUE(r.affine.isApprox(identity_affine(), 1e-9)) << r.affine;
  EXPECT_EQ(r.pairs, (RockPairs{{0, 0}, {1, 1}, {2, 2}, {4, 4}, {5, 5}, {6, 6}, {7, 7}}));
  EXPECT_EQ(r.inliers, 7);
  b[3].cx = a[3].cx + 0.05;  // within the gate: paired
  EXPECT_EQ(register_rocks(a, b, o).pairs.size(), 8u);
}

}  // namespace
}  // namespace ipd
