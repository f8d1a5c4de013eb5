#include "core/session/pair_density.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace ipd {
namespace {

RockPairPoint point(double perf_a, double perf_b, double size = 0) {
  RockPairPoint p;
  p.perf_a = perf_a;
  p.perf_b = perf_b;
  p.abs_diff = std::abs(perf_a - perf_b);
  p.size = size;
  return p;
}

// A 4 x 2 grid over [0, 1] x [0, 1]: columns 0.25 wide, rows 0.5 high.
TEST(PairDensity, PointsFallInTheirCellsOnceEach) {
  const std::vector<RockPairPoint> points = {point(0.1, 0.1), point(0.2, 0.4), point(0.9, 0.9), point(1.0, 1.0),
                                             point(0.3, 0.6)};
  const PairDensity d = bin_pair_points(points, PairAxis::kPerfA, PairAxis::kPerfB, {}, 4, 2, nullptr);
  EXPECT_EQ(d.cells_x, 4);
  EXPECT_EQ(d.shown, 5);
  ASSERT_EQ(d.cells.size(), 3u);  // (0, 0) twice, (3, 1) twice (the upper end is the last cell), (1, 1) once
  EXPECT_EQ(d.cells[0].cx, 0);
  EXPECT_EQ(d.cells[0].cy, 0);
  EXPECT_EQ(d.cells[0].count, 2);
  EXPECT_EQ(d.cells[0].first, 0);
  EXPECT_EQ(d.cells[1].cx, 3);
  EXPECT_EQ(d.cells[1].cy, 1);
  EXPECT_EQ(d.cells[1].count, 2);
  EXPECT_EQ(d.cells[1].first, 2);
  EXPECT_EQ(d.cells[2].cx, 1);
  EXPECT_EQ(d.cells[2].cy, 1);
  EXPECT_EQ(d.cells[2].count, 1);
  EXPECT_EQ(d.max_count, 2);
}

// Points are told apart by scene and rocks, as the Rock pairs window's selection keeps them.
RockPairPoint pair_point(int scene, int rock, double perf_a, double perf_b, double size) {
  RockPairPoint p = point(perf_a, perf_b, size);
  p.scene = scene, p.rock_a = rock, p.rock_b = rock + 1;
  return p;
}

TEST(PairDensity, TheDragBoxCountsItsPointsPerCell) {
  const std::vector<RockPairPoint> points = {pair_point(0, 0, 0.1, 0.1, 10), pair_point(0, 1, 0.2, 0.4, 20),
                                             pair_point(1, 0, 0.9, 0.9, 30)};
  // Corners in either order: x 0 .. 0.15, y 0.3 .. 0.5.
  const PairSelection none = select_in_box(points, PairAxis::kPerfA, PairAxis::kPerfB, 0.15, 0.5, 0.0, 0.3);
  const std::vector<char> none_marked = marked_pairs(points, none.pairs);
  const PairDensity d = bin_pair_points(points, PairAxis::kPerfA, PairAxis::kPerfB, {}, 4, 2, &none_marked);
  ASSERT_EQ(d.cells.size(), 2u);
  EXPECT_EQ(d.cells[0].count, 2);
  EXPECT_EQ(d.cells[0].selected, 0);  // (0.1, 0.1) is below the box, (0.2, 0.4) right of it
  // Edges included.
  const PairSelection wide = select_in_box(points, PairAxis::kPerfA, PairAxis::kPerfB, 0, 0, 0.2, 0.4);
  EXPECT_EQ(wide.label(), "selection: 2 pairs in 1 scene");
  const std::vector<char> marked = marked_pairs(points, wide.pairs);
  const PairDensity e = bin_pair_points(points, PairAxis::kPerfA, PairAxis::kPerfB, {}, 4, 2, &marked);
  EXPECT_EQ(e.cells[0].selected, 2);
  EXPECT_EQ(e.cells[1].selected, 0);
}

// A selection keeps its pairs highlighted on other axes, where its box means nothing: it marks pairs, not a
// region. On size x |diff| the two selected pairs fall in two cells, the third pair in neither.
TEST(PairDensity, ASelectionStaysHighlightedOnOtherAxes) {
  const std::vector<RockPairPoint> points = {pair_point(0, 0, 0.1, 0.1, 10), pair_point(0, 1, 0.2, 0.4, 90),
                                             pair_point(1, 0, 0.9, 0.9, 50)};
  const PairSelection sel = select_in_box(points, PairAxis::kPerfA, PairAxis::kPerfB, 0, 0, 0.2, 0.4);
  // The points gathered again, in another order: the same pairs are marked.
  const std::vector<RockPairPoint> again = {points[2], points[1], points[0]};
  const std::vector<char> marked = marked_pairs(again, sel.pairs);
  EXPECT_EQ(marked, (std::vector<char>{0, 1, 1}));
  const PairDensity d = bin_pair_points(again, PairAxis::kSize, PairAxis::kAbsDiff, {0, 100, 0, 1}, 4, 2, &marked);
  ASSERT_EQ(d.cells.size(), 3u);  // size 50 | 90 | 10: columns 2, 3 and 0
  EXPECT_EQ(d.cells[0].selected, 0);
  EXPECT_EQ(d.cells[1].selected, 1);
  EXPECT_EQ(d.cells[2].selected, 1);
}

TEST(PairDensity, APointWithoutAValueOnAnAxisHasNoCell) {
  RockPairPoint p = point(0.5, 0.5);
  p.conf_a = std::numeric_limits<double>::quiet_NaN();
  const PairDensity d = bin_pair_points({p}, PairAxis::kConfA, PairAxis::kPerfB, {}, 10, 10, nullptr);
  EXPECT_EQ(d.shown, 0);
  EXPECT_TRUE(d.cells.empty());
}

TEST(PairDensity, SizeAndDiffAxesEndOnARoundNumber) {
  EXPECT_DOUBLE_EQ(round_up_nicely(3817.4), 5000);
  EXPECT_DOUBLE_EQ(round_up_nicely(2000), 2000);
  EXPECT_DOUBLE_EQ(round_up_nicely(2001), 2500);
  EXPECT_DOUBLE_EQ(round_up_nicely(0.41), 0.5);
  EXPECT_DOUBLE_EQ(round_up_nicely(0.83), 1);
  EXPECT_DOUBLE_EQ(round_up_nicely(0), 1);
  const std::vector<RockPairPoint> points = {point(0.9, 0.5, 120.5), point(0.1, 0.3, 1733)};
  EXPECT_EQ(scatter_axis_range(points, PairAxis::kSize), std::make_pair(0.0, 2000.0));
  EXPECT_EQ(scatter_axis_range(points, PairAxis::kAbsDiff), std::make_pair(0.0, 0.5));
  EXPECT_EQ(scatter_axis_range(points, PairAxis::kPerfA), std::make_pair(0.0, 1.0));
  EXPECT_EQ(scatter_axis_range({}, PairAxis::kSize), std::make_pair(0.0, 1.0));
}

}  // namespace
}  // namespace ipd
