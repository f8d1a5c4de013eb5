#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/geometry/geometry.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

using test::box;

TEST(Iou, HandComputedValues) {
  // Shifted by half a width: intersection 0.1 x 0.2 = 0.02, union 0.04 + 0.04 - 0.02 = 0.06.
  EXPECT_NEAR(iou(box(0.5, 0.5, 0.2, 0.2), box(0.6, 0.5, 0.2, 0.2)), 1.0 / 3.0, 1e-12);
  // Contained: 0.04 / 0.16.
  EXPECT_NEAR(iou(box(0.5, 0.5, 0.4, 0.4), box(0.5, 0.5, 0.2, 0.2)), 0.25, 1e-12);
  // Corner overlap: intersection 0.05 x 0.05 = 0.0025, union 0.01 + 0.01 - 0.0025 = 0.0175.
  EXPECT_NEAR(iou(box(0.2, 0.2, 0.1, 0.1), box(0.25, 0.25, 0.1, 0.1)), 0.0025 / 0.0175, 1e-12);
  EXPECT_DOUBLE_EQ(iou(box(0.3, 0.3, 0.1, 0.2), box(0.3, 0.3, 0.1, 0.2)), 1.0);
}

TEST(Iou, EdgeCasesGiveZeroNotNan) {
  EXPECT_EQ(iou(box(0.2, 0.2, 0.1, 0.1), box(0.8, 0.8, 0.1, 0.1)), 0.0);   // disjoint
  EXPECT_EQ(iou(box(0.2, 0.2, 0.2, 0.2), box(0.4, 0.2, 0.2, 0.2)), 0.0);   // touching edges
  EXPECT_EQ(iou(box(0.5, 0.5, 0.0, 0.2), box(0.5, 0.5, 0.2, 0.2)), 0.0);   // zero width
  EXPECT_EQ(iou(box(0.5, 0.5, -0.1, 0.2), box(0.5, 0.5, 0.2, 0.2)), 0.0);  // negative width
  EXPECT_EQ(iou(box(0.5, 0.5, 0.0, 0.0), box(0.5, 0.5, 0.0, 0.0)), 0.0);   // two points
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(iou(box(nan, 0.5, 0.1, 0.1), box(0.5, 0.5, 0.1, 0.1)), 0.0);
  EXPECT_EQ(iou(box(0.5, 0.5, INFINITY, 0.1), box(0.5, 0.5, 0.1, 0.1)), 0.0);
}

TEST(Iou, TableAndPerformanceValues) {
  const std::vector<Box> gt = {box(0.5, 0.5, 0.2, 0.2), box(0.1, 0.1, 0.1, 0.1), box(0.9, 0.9, 0.1, 0.1)};
  const std::vector<Box> pred = {box(0.6, 0.5, 0.2, 0.2, 0.9), box(0.5, 0.5, 0.4, 0.4, 0.8),
                                 box(0.1, 0.1, 0.1, 0.1, 0.3)};
  const IouTable t = iou_table(gt, pred);
  ASSERT_EQ(t.rows, 3);
  ASSERT_EQ(t.cols, 3);
  EXPECT_NEAR(t.at(0, 0), 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(t.at(0, 1), 0.25, 1e-12);
  EXPECT_EQ(t.at(2, 0), 0.0);
  const PerformanceValues pv = performance_values(gt, pred);
  EXPECT_NEAR(pv.value[0], 1.0 / 3.0, 1e-12);  // the best of 1/3 and 1/4
  EXPECT_EQ(pv.best_prediction[0], 0);
  EXPECT_DOUBLE_EQ(pv.value[1], 1.0);
  EXPECT_EQ(pv.best_prediction[1], 2);
  EXPECT_EQ(pv.value[2], 0.0);  // nothing overlaps
  EXPECT_EQ(pv.best_prediction[2], -1);
  const PerformanceValues none = performance_values(gt, {});
  EXPECT_EQ(none.value, std::vector<double>(3, 0.0));
}

// The performance value is the best IoU over all predictions, wherever the best one stands in the list: a
// prediction that overlaps first but less must not set the value.
TEST(PerformanceValue, LaterBetterPredictionWinsOverFirstOverlapping) {
  const std::vector<Box> gt = {box(0.5, 0.5, 0.2, 0.2)};
  // IoUs in list order: 0 (far away), 1/4 (contains the rock), 1 (exact), 1/3 (shifted by half a width).
  const std::vector<Box> pred = {box(0.9, 0.9, 0.05, 0.05, 0.99), box(0.5, 0.5, 0.4, 0.4, 0.95),
                                 box(0.5, 0.5, 0.2, 0.2, 0.5), box(0.6, 0.5, 0.2, 0.2, 0.9)};
  const PerformanceValues pv = performance_values(gt, pred);
  EXPECT_NEAR(pv.value[0], 1.0, 1e-12);
  EXPECT_EQ(pv.best_prediction[0], 2);  // neither the first overlapping (1) nor the last (3)
  // The same predictions in another order give the same value: the order of a predictions file is no rule.
  const std::vector<Box> reversed(pred.rbegin(), pred.rend());
  const PerformanceValues rv = performance_values(gt, reversed);
  EXPECT_NEAR(rv.value[0], 1.0, 1e-12);
  EXPECT_EQ(rv.best_prediction[0], 1);
}

// Each GT rock takes its own best, over all predictions: one prediction may overlap both rocks and be the best
// of neither (rock 1) or of one (rock 0).
TEST(PerformanceValue, EachRockTakesItsOwnBestPrediction) {
  const std::vector<Box> gt = {box(0.3, 0.5, 0.2, 0.2), box(0.5, 0.5, 0.2, 0.2)};  // x 0.2..0.4 and 0.4..0.6
  // pred 0 (x 0.1..0.3): rock 0 intersection 0.1 x 0.2 = 0.02, union 0.06 -> 1/3; rock 1 disjoint -> 0.
  // pred 1 (x 0.2..0.6, area 0.08) contains each rock: 0.04 / 0.08 -> 1/2 for both.
  // pred 2 is rock 1 exactly -> 1 (rock 0: touching edges, 0).
  const std::vector<Box> pred = {box(0.2, 0.5, 0.2, 0.2), box(0.4, 0.5, 0.4, 0.2), box(0.5, 0.5, 0.2, 0.2)};
  const PerformanceValues pv = performance_values(gt, pred);
  EXPECT_NEAR(pv.value[0], 0.5, 1e-12);  // not the first overlapping prediction's 1/3
  EXPECT_EQ(pv.best_prediction[0], 1);
  EXPECT_NEAR(pv.value[1], 1.0, 1e-12);  // not the first overlapping prediction's 1/2
  EXPECT_EQ(pv.best_prediction[1], 2);
}

// Ties: two predictions with the same IoU (a duplicate detection) -- the value is that IoU, and the earlier
// index is kept (a later prediction replaces the best only when it is strictly better), whatever the
// confidences.
TEST(PerformanceValue, TieKeepsTheEarlierPredictionWhateverTheConfidence) {
  const std::vector<Box> gt = {box(0.5, 0.5, 0.2, 0.2)};
  const std::vector<Box> pred = {box(0.1, 0.1, 0.05, 0.05, 0.99), box(0.6, 0.5, 0.2, 0.2, 0.3),
                                 box(0.6, 0.5, 0.2, 0.2, 0.9)};
  const PerformanceValues pv = performance_values(gt, pred);
  EXPECT_NEAR(pv.value[0], 1.0 / 3.0, 1e-12);
  EXPECT_EQ(pv.best_prediction[0], 1);
}

TEST(Affine, ComposeInvertInterpolate) {
  Affine2 m;
  m << 1.1, 0.2, 0.05, -0.1, 0.9, -0.02;
  Affine2 inv;
  ASSERT_TRUE(invert(m, &inv));
  const Affine2 id = compose(inv, m);
  EXPECT_TRUE(id.isApprox(identity_affine(), 1e-12));
  const Eigen::Vector2d p(0.3, 0.7);
  EXPECT_TRUE(apply(m, p).isApprox(Eigen::Vector2d(1.1 * 0.3 + 0.2 * 0.7 + 0.05, -0.1 * 0.3 + 0.9 * 0.7 - 0.02)));
  EXPECT_TRUE(interpolate_from_identity(m, 0).isApprox(identity_affine()));
  EXPECT_TRUE(interpolate_from_identity(m, 1).isApprox(m));
  Affine2 singular;
  singular << 1, 2, 0, 2, 4, 0;
  EXPECT_FALSE(invert(singular, &inv));
}

TEST(Affine, TransformBoxTakesBoundsOfCorners) {
  Affine2 rot90;  // (x, y) -> (-y, x) about the origin, then shift by (1, 0)
  rot90 << 0, -1, 1, 1, 0, 0;
  const Box b = transform_box(rot90, box(0.2, 0.3, 0.2, 0.1));
  EXPECT_NEAR(b.cx, 0.7, 1e-12);
  EXPECT_NEAR(b.cy, 0.2, 1e-12);
  EXPECT_NEAR(b.w, 0.1, 1e-12);
  EXPECT_NEAR(b.h, 0.2, 1e-12);
}

}  // namespace
}  // namespace ipd
