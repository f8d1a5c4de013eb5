// Outlines and mask IoU: the segment task's performance value, checked against areas worked out by hand.
#include <gtest/gtest.h>

#include "core/geometry/geometry.h"
#include "core/io/label_io.h"

namespace ipd {
namespace {

Outline outline_of(std::vector<Eigen::Vector2d> points) {
  Outline o;
  const std::string why = make_outline(std::move(points), &o);
  EXPECT_EQ(why, "");
  return o;
}

Outline square(double x, double y, double side) {
  return outline_of({{x, y}, {x + side, y}, {x + side, y + side}, {x, y + side}});
}

TEST(Outline, TwoSquaresOffsetByHalfTheirSideOverlapByAThird) {
  // Side 0.4, offset 0.2: intersection 0.2 x 0.4 = 0.08, union 0.16 + 0.16 - 0.08 = 0.24.
  EXPECT_NEAR(mask_iou(square(0.1, 0.1, 0.4), square(0.3, 0.1, 0.4)), 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(outline_intersection_area(square(0.1, 0.1, 0.4), square(0.3, 0.1, 0.4)), 0.08, 1e-12);
}

TEST(Outline, AnLShapeAgainstItsBoundingSquareIsThreeQuarters) {
  // The square [0, 0.4]^2 without its top-right quarter: area 0.16 - 0.04 = 0.12.
  const Outline l = outline_of({{0, 0}, {0.4, 0}, {0.4, 0.2}, {0.2, 0.2}, {0.2, 0.4}, {0, 0.4}});
  EXPECT_NEAR(l.area, 0.12, 1e-12);
  EXPECT_NEAR(mask_iou(l, square(0, 0, 0.4)), 0.75, 1e-12);
  // Centroid: (0.16 * 0.2 - 0.04 * 0.3) / 0.12 on both axes.
  EXPECT_NEAR(l.centroid.x(), 1.0 / 6.0, 1e-12);
  EXPECT_NEAR(l.centroid.y(), 1.0 / 6.0, 1e-12);
  EXPECT_DOUBLE_EQ(l.x1, 0.4);
}

TEST(Outline, ATriangleInsideASquareIsHalfOfIt) {
  const Outline t = outline_of({{0.1, 0.1}, {0.5, 0.1}, {0.1, 0.5}});
  EXPECT_NEAR(t.area, 0.08, 1e-12);
  EXPECT_NEAR(mask_iou(t, square(0.1, 0.1, 0.4)), 0.5, 1e-12);
  EXPECT_NEAR(mask_iou(square(0.1, 0.1, 0.4), t), 0.5, 1e-12);
}

TEST(Outline, AContourThatCrossesItselfFillsBothLobes) {
  // A bow tie: its shoelace sum is 0, the non-zero rule fills two triangles of 0.04 each.
  const Outline bow = outline_of({{0, 0}, {0.4, 0.4}, {0.4, 0}, {0, 0.4}});
  EXPECT_NEAR(bow.area, 0.08, 1e-12);
  EXPECT_NEAR(bow.centroid.x(), 0.2, 1e-12);
  EXPECT_NEAR(bow.centroid.y(), 0.2, 1e-12);
  EXPECT_NEAR(mask_iou(bow, square(0, 0, 0.4)), 0.5, 1e-12);
  // Drawn clockwise or anticlockwise, a polygon is the same mask.
  const Outline back = outline_of({{0, 0.4}, {0.4, 0.4}, {0.4, 0}, {0, 0}});
  EXPECT_NEAR(mask_iou(back, square(0, 0, 0.4)), 1.0, 1e-12);
}

TEST(Outline, OutlinesWhoseBoundsDoNotOverlapHaveNoIou) {
  EXPECT_EQ(mask_iou(square(0, 0, 0.2), square(0.2, 0, 0.2)), 0.0);  // touching edges: no area in common
  EXPECT_EQ(mask_iou(square(0, 0, 0.2), square(0.5, 0.5, 0.2)), 0.0);
}

TEST(Outline, APolygonWithoutAreaOrWithTooFewPointsIsRefused) {
  Outline o;
  EXPECT_EQ(make_outline({{0.1, 0.1}, {0.2, 0.2}}, &o), "expected an outline of at least 3 points, found 2");
  EXPECT_EQ(make_outline({{0.1, 0.1}, {0.2, 0.2}, {0.3, 0.3}}, &o),
            "expected an outline that encloses an area, found 3 points with none (on one line)");
  EXPECT_EQ(make_outline(std::vector<Eigen::Vector2d>(kMaxOutlinePoints + 1, Eigen::Vector2d(0.5, 0.5)), &o),
            "expected an outline of at most 10000 points, found 10001");
}

TEST(Outline, TheSegmentTaskScoresByMaskIouAndDetectByBoxIou) {
  const LabelFile gt = parse_labels("0 0 0 0.4 0 0.4 0.2 0.2 0.2 0.2 0.4 0 0.4\n", "a.txt", {LabelKind::kGroundTruth});
  const LabelFile pred = parse_labels("0 0 0 0.4 0 0.4 0.4 0 0.4 0.9\n", "p.txt", {LabelKind::kPrediction});
  ASSERT_TRUE(gt.errors.empty() && pred.errors.empty());
  EXPECT_NEAR(performance_values(gt.boxes, pred.boxes, Task::kSegment).value[0], 0.75, 1e-12);
  EXPECT_NEAR(performance_values(gt.boxes, pred.boxes, Task::kDetect).value[0], 1.0, 1e-12);
  // A box without an outline is the mask of its rectangle.
  Box plain;
  plain.cx = plain.cy = 0.2, plain.w = plain.h = 0.4;
  EXPECT_NEAR(instance_iou(gt.boxes[0], plain, Task::kSegment), 0.75, 1e-12);
}

TEST(LabelOutlines, AYoloSegLineIsAnOutlineAndItsBoundsAreTheBox) {
  const LabelFile f = parse_labels("1 0.1 0.2 0.5 0.2 0.3 0.6\n", "a.txt", {LabelKind::kGroundTruth});
  ASSERT_TRUE(f.errors.empty());
  ASSERT_EQ(f.boxes.size(), 1u);
  const Box& b = f.boxes[0];
  ASSERT_TRUE(b.outline);
  EXPECT_EQ(b.cls, 1);
  EXPECT_DOUBLE_EQ(b.cx, 0.3);
  EXPECT_DOUBLE_EQ(b.cy, 0.4);
  EXPECT_DOUBLE_EQ(b.w, 0.4);
  EXPECT_DOUBLE_EQ(b.h, 0.4);
  EXPECT_NEAR(b.outline->area, 0.08, 1e-12);
  const LabelFile p =
      parse_labels("0 0.1 0.2 0.5 0.2 0.3 0.6 0.75\n0 0.5 0.5 0.1 0.1 0.5\n", "p.txt", {LabelKind::kPrediction});
  ASSERT_TRUE(p.errors.empty());
  ASSERT_EQ(p.boxes.size(), 2u);
  EXPECT_DOUBLE_EQ(p.boxes[0].conf, 0.75);
  EXPECT_TRUE(p.boxes[0].outline);
  EXPECT_FALSE(p.boxes[1].outline);  // box and outline lines mix in one file
}

TEST(LabelOutlines, ABadOutlineLineNamesTheFileLineAndWhatWasExpected) {
  auto gt_error = [](const std::string& text) {
    const LabelFile f = parse_labels(text, "a.txt", {LabelKind::kGroundTruth});
    return f.errors.size() == 1 ? f.errors[0].to_string() : "";
  };
  EXPECT_EQ(gt_error("0 0.1 0.2 0.5 0.2 0.3 0.6 0.7\n"),
            "a.txt:1: expected an outline (class x1 y1 ... xn yn), found 8 columns: an odd number of coordinates");
  EXPECT_EQ(gt_error("0 0.1 0.2 0.5 0.2 1.3 0.6\n"), "a.txt:1: expected x3 in [0, 1] (normalised), found 1.3");
  EXPECT_EQ(gt_error("0 0.1 0.1 0.2 0.2 0.3 0.3\n"),
            "a.txt:1: expected an outline that encloses an area, found 3 points with none (on one line)");
  EXPECT_EQ(gt_error("0 0.1 0.2 0.5 x 0.3 0.6\n"), "a.txt:1: expected a number for y2 in column 5, found 'x'");
  const LabelFile p = parse_labels("0 0.1 0.2 0.5 0.2 0.3 0.6 0.7 0.8\n", "p.txt", {LabelKind::kPrediction});
  ASSERT_EQ(p.errors.size(), 1u);
  EXPECT_EQ(p.errors[0].to_string(),
            "p.txt:1: expected an outline with a confidence last (class x1 y1 ... xn yn conf), found 9 columns: an "
            "odd number of coordinates, or no confidence");
  const LabelFile c = parse_labels("0 0.1 0.2 0.5 0.2 0.3 0.6 1.5\n", "p.txt", {LabelKind::kPrediction});
  ASSERT_EQ(c.errors.size(), 1u);
  EXPECT_EQ(c.errors[0].to_string(), "p.txt:1: expected conf in [0, 1], found 1.5");
}

TEST(LabelOutlines, AnOutlineIsWrittenBackAsTheLineItWasReadFrom) {
  const std::string line = "2 0.125 0.25 0.5 0.25 0.375 0.625 0.875\n";
  const LabelFile p = parse_labels(line, "p.txt", {LabelKind::kPrediction});
  ASSERT_TRUE(p.errors.empty());
  EXPECT_EQ(labels_text(p.boxes, LabelKind::kPrediction, LabelDigits::kExact), line);
}

}  // namespace
}  // namespace ipd
