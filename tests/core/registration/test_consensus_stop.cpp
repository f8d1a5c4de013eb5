// The consensus search's stop rules as pure functions of counts: when a best can't (or won't) be beaten, when a
// consensus is beyond chance, and how confirmations are counted per anchor rock.
#include <gtest/gtest.h>

#include <cmath>

#include "core/registration/consensus/consensus_scorer.h"  // core/src: internal
#include "core/registration/consensus/consensus_stop.h"    // core/src: internal

namespace ipd {
namespace {

detail::ConsensusCounts counts(int best, int max, int confirmations, int scored, bool beyond_chance = false) {
  detail::ConsensusCounts c;
  c.best_inliers = best;
  c.max_inliers = max;
  c.confirmations = confirmations;
  c.scored = scored;
  c.hypothesis_budget = 1000;
  c.beyond_chance = beyond_chance;
  return c;
}

TEST(ConsensusStop, EveryRockOfTheSmallerSidePairedEndsTheSearch) {
  EXPECT_TRUE(detail::consensus_cannot_be_beaten(counts(10, 10, 0, 1)));
  EXPECT_FALSE(detail::consensus_cannot_be_beaten(counts(9, 10, 0, 1)));
}

// 5 of 20 rocks: COLMAP's trials for an inlier ratio of 1/4, triples, 99%: log(0.01) / log(1 - 1/64) = 292.4,
// so 293 hypotheses must have been scored before two confirmations are believed.
TEST(ConsensusStop, TwoConfirmationsWaitForColmapsNumberOfTrials) {
  EXPECT_FALSE(detail::consensus_cannot_be_beaten(counts(5, 20, 2, 292)));
  EXPECT_TRUE(detail::consensus_cannot_be_beaten(counts(5, 20, 2, 293)));
  EXPECT_FALSE(detail::consensus_cannot_be_beaten(counts(5, 20, 1, 293)));   // one confirmation is not enough
  EXPECT_FALSE(detail::consensus_cannot_be_beaten(counts(4, 20, 3, 1000)));  // nor are 4 rocks
  // 10 of 20: log(0.01) / log(1 - 1/8) = 34.5, so 35.
  EXPECT_FALSE(detail::consensus_cannot_be_beaten(counts(10, 20, 2, 34)));
  EXPECT_TRUE(detail::consensus_cannot_be_beaten(counts(10, 20, 2, 35)));
}

TEST(ConsensusStop, BeyondChanceEndsTheSearchOnceItHoldsHalfTheSmallerSide) {
  EXPECT_TRUE(detail::consensus_cannot_be_beaten(counts(10, 20, 0, 1, true)));
  EXPECT_FALSE(detail::consensus_cannot_be_beaten(counts(9, 20, 0, 1, true)));
  EXPECT_FALSE(detail::consensus_cannot_be_beaten(counts(10, 20, 0, 1, false)));
}

// Four B rocks on the unit square's corners, gate^2 = 0.01: 4 discs of area 0.01 pi over an area of 1.
TEST(ConsensusStop, ChanceOfAgreementIsTheGateDiscsOverTheAreaBSpans) {
  const std::vector<Eigen::Vector2d> b = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  EXPECT_NEAR(detail::chance_of_agreement(b, 0.01), 0.04 * M_PI, 1e-12);
  EXPECT_EQ(detail::chance_of_agreement(b, 0.1), 0.5);              // 0.4 pi, capped
  EXPECT_EQ(detail::chance_of_agreement({{0.3, 0.3}}, 0.01), 0.5);  // one rock spans no area
}

// 6 inliers of 6 rocks at chance 0.1: the three of the hypothesis don't count, P(3 of 3) = 0.001, times the
// hypothesis budget against 0.05.
TEST(ConsensusStop, BeyondChanceWeighsTheTailByTheHypothesisBudget) {
  EXPECT_TRUE(detail::consensus_beyond_chance(6, 6, 0.1, 1));     // 0.001
  EXPECT_TRUE(detail::consensus_beyond_chance(6, 6, 0.1, 10));    // 0.01
  EXPECT_FALSE(detail::consensus_beyond_chance(6, 6, 0.1, 100));  // 0.1
  EXPECT_FALSE(detail::consensus_beyond_chance(5, 5, 0.01, 1));   // fewer than 6 rocks never are
}

TEST(Confirmations, EachOtherAnchorCountsOnce) {
  const std::vector<Eigen::Vector2d> a = {{0, 0}, {1, 0}, {0, 1}};
  detail::Confirmations c(a, 0.01);
  EXPECT_FALSE(c.has_best());
  c.set_best(identity_affine(), 7);
  EXPECT_TRUE(c.has_best());
  c.confirm(7);  // the anchor that found the best does not confirm it
  EXPECT_EQ(c.count(), 0);
  c.confirm(3);
  c.confirm(3);
  c.confirm(-1);
  EXPECT_EQ(c.count(), 2);
  c.restart();
  EXPECT_EQ(c.count(), 0);
  c.confirm(7);  // after a restart every anchor counts again
  EXPECT_EQ(c.count(), 1);
}

TEST(Confirmations, AgreementIsMostRocksWithinAGateOfTheBest) {
  const std::vector<Eigen::Vector2d> a = {{0, 0}, {1, 0}, {0, 1}};
  detail::Confirmations c(a, 0.01);
  c.set_best(identity_affine(), 0);
  Affine2 near = identity_affine();
  near.col(2) = Eigen::Vector2d(0.09, 0);  // every rock 0.09 away: within the gate of 0.1
  EXPECT_TRUE(c.agrees_with_best(near));
  Affine2 turned = identity_affine();
  turned.leftCols<2>() << 0, -1, 1, 0;  // a quarter turn keeps only (0, 0) in place: 1 of 3
  EXPECT_FALSE(c.agrees_with_best(turned));
  Affine2 broken = identity_affine();
  broken(0, 0) = NAN;
  EXPECT_FALSE(c.agrees_with_best(broken));
}

}  // namespace
}  // namespace ipd
