#include "core/session/rock_pair_points.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/support/test_support.h"

namespace ipd {
namespace {

// write_two_rock_study: real rocks r0 (0.2, 0.2), r1 (0.6, 0.6); synth lists them the other way round.
// real's prediction sits on r0 (IoU 1, conf 0.9); synth's is shifted by half a width off s1 (IoU 1/3, conf 0.8).
// Pairs (r0, s1): perf 1 vs 1/3, |diff| 2/3; (r1, s0): 0 vs 0. Areas 0.1 x 0.1 of an image of unknown size: 10^4.
TEST(RockPairPoints, EveryCountedPairWithItsValues) {
  test::TempDir d;
  test::write_two_rock_study(d);
  const Session s = Session::open(d.path());
  ASSERT_EQ(s.left_domain(), "real");
  const auto points = rock_pair_points(s);
  ASSERT_EQ(points.size(), 2u);
  const RockPairPoint& p = points[0].rock_a == 0 ? points[0] : points[1];
  const RockPairPoint& q = points[0].rock_a == 0 ? points[1] : points[0];
  EXPECT_EQ(p.scene, 0);
  EXPECT_EQ(p.rock_b, 1);
  EXPECT_NEAR(p.perf_a, 1.0, 1e-12);
  EXPECT_NEAR(p.perf_b, 1.0 / 3, 1e-12);
  EXPECT_NEAR(p.abs_diff, 2.0 / 3, 1e-12);
  EXPECT_DOUBLE_EQ(p.size, 1e4);
  EXPECT_DOUBLE_EQ(p.x, 0.2);
  EXPECT_DOUBLE_EQ(p.y, 0.2);
  EXPECT_DOUBLE_EQ(p.conf_a, 0.9);
  EXPECT_DOUBLE_EQ(p.conf_b, 0.8);
  EXPECT_EQ(q.rock_a, 1);
  EXPECT_EQ(q.rock_b, 0);
  EXPECT_EQ(q.perf_a, 0);
  EXPECT_EQ(q.perf_b, 0);
  EXPECT_DOUBLE_EQ(q.x, 0.6);
  // Nothing overlaps these rocks: no confidence, rather than a made-up 0.
  EXPECT_TRUE(std::isnan(q.conf_a));
  EXPECT_TRUE(std::isnan(q.conf_b));
  // The gallery starts with the pair the renderer gets most wrong.
  EXPECT_EQ(points[gallery_order(points)[0]].rock_a, 0);
}

TEST(RockPairPoints, ASwappedViewTurnsEveryPairAround) {
  test::TempDir d;
  test::write_two_rock_study(d);
  Session s = Session::open(d.path());
  ASSERT_TRUE(s.select_domains("synth", "real"));
  ASSERT_TRUE(s.swapped());
  const auto points = rock_pair_points(s);
  ASSERT_EQ(points.size(), 2u);
  const RockPairPoint& p = points[0].rock_a == 1 ? points[0] : points[1];
  EXPECT_EQ(p.rock_a, 1);  // synth's s1 is on the left now
  EXPECT_EQ(p.rock_b, 0);
  EXPECT_NEAR(p.perf_a, 1.0 / 3, 1e-12);
  EXPECT_NEAR(p.perf_b, 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(p.conf_a, 0.8);
  EXPECT_DOUBLE_EQ(p.conf_b, 0.9);
  EXPECT_DOUBLE_EQ(p.x, 0.2);
}

TEST(RockPairPoints, OnlyTheScenesAskedFor) {
  test::TempDir d;
  test::write_two_rock_study(d);
  const Session s = Session::open(d.path());
  EXPECT_EQ(rock_pair_points(s, {0}).size(), 2u);
  EXPECT_TRUE(rock_pair_points(s, {5}).empty());  // a scene index the cell doesn't have adds nothing
}

RockPairPoint pair_point(int scene, int a, int b, double diff) {
  RockPairPoint p;
  p.scene = scene;
  p.rock_a = a;
  p.rock_b = b;
  p.perf_a = diff;
  p.abs_diff = diff;
  return p;
}

TEST(RockPairPoints, GalleryIsWorstFirstAndTiesGoBySceneThenRocks) {
  const std::vector<RockPairPoint> points = {pair_point(2, 0, 0, 0.5), pair_point(1, 3, 1, 0.5),
                                             pair_point(1, 2, 4, 0.5), pair_point(0, 0, 0, 0.1),
                                             pair_point(3, 0, 0, 0.9), pair_point(1, 2, 0, 0.5)};
  EXPECT_EQ(gallery_order(points), (std::vector<int>{4, 5, 2, 1, 0, 3}));
}

TEST(RockPairPoints, ABoxSelectsThePointsInsideAndNamesTheirScenes) {
  std::vector<RockPairPoint> points = {pair_point(0, 0, 0, 0.6), pair_point(0, 1, 1, 0.2), pair_point(4, 0, 0, 0.7),
                                       pair_point(2, 0, 0, 0.9)};
  points[1].conf_a = std::nan("");
  // Corners in either order; edges count.
  const PairSelection sel = select_in_box(points, PairAxis::kPerfA, PairAxis::kAbsDiff, 0.7, 0.7, 0.2, 0.2);
  EXPECT_EQ(sel.points, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(sel.scenes, (std::vector<int>{0, 4}));
  EXPECT_EQ(sel.label(), "selection: 3 pairs in 2 scenes");
  // A pair without a confidence is on no confidence axis.
  const PairSelection conf = select_in_box(points, PairAxis::kConfA, PairAxis::kPerfA, -1, 0, 1, 1);
  EXPECT_EQ(conf.points, (std::vector<int>{0, 2, 3}));
  const PairSelection one = select_in_box(points, PairAxis::kPerfA, PairAxis::kPerfA, 0.9, 0.9, 0.9, 0.9);
  EXPECT_EQ(one.label(), "selection: 1 pair in 1 scene");
}

}  // namespace
}  // namespace ipd
