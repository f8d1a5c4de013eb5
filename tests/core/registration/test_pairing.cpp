// The pairing rules once centres or boxes are aligned: the paper's mutual nearest neighbours within the gate,
// and the consensus / cpd assignment on aligned-box IoU above min_pair_iou.
#include <gtest/gtest.h>

#include "core/registration/pairing.h"
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

}  // namespace
}  // namespace ipd
