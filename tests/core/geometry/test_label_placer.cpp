// The label placer: preferred positions in order, leaders when crowded, left-out counts, never an overlap.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/geometry/label_placer.h"

namespace ipd {
namespace {

LabelPlacementOptions page(double w, double h) {
  LabelPlacementOptions o;
  o.bounds = {0, 0, w, h};
  o.gap = 1;
  o.max_leader = 3;
  return o;
}

TEST(LabelPlacer, AboveTheBoxWhenThereIsRoom) {
  const auto p = place_labels({{{50, 50, 70, 60}, 10, 8}}, page(200, 200));
  ASSERT_EQ(p.labels.size(), 1u);
  EXPECT_EQ(p.labels[0].position, LabelPosition::kAbove);
  // Left-aligned with the box, its bottom one gap above the box's top.
  EXPECT_DOUBLE_EQ(p.labels[0].box.x0, 50);
  EXPECT_DOUBLE_EQ(p.labels[0].box.y1, 49);
  EXPECT_DOUBLE_EQ(p.labels[0].box.y0, 41);
  EXPECT_EQ(p.left_out, 0);
}

TEST(LabelPlacer, BelowWhenAboveLeavesThePage) {
  const auto p = place_labels({{{50, 3, 70, 20}, 10, 8}}, page(200, 200));
  EXPECT_EQ(p.labels[0].position, LabelPosition::kBelow);
  EXPECT_DOUBLE_EQ(p.labels[0].box.y0, 21);
}

TEST(LabelPlacer, SecondLabelOfTwoTouchingBoxesMovesAside) {
  // Two boxes side by side: both "above, left-aligned" spots would overlap (10 wide label, boxes 6 apart).
  const auto p = place_labels({{{50, 50, 56, 70}, 10, 8}, {{56, 50, 62, 70}, 10, 8}}, page(200, 200));
  EXPECT_EQ(p.labels[0].position, LabelPosition::kAbove);
  EXPECT_EQ(p.labels[1].position, LabelPosition::kBelow);  // its own "above" spots are the first label's
  EXPECT_FALSE(overlaps(p.labels[0].box, p.labels[1].box));
}

TEST(LabelPlacer, TakenRegionsAreAvoided) {
  auto o = page(200, 200);
  o.taken = {{40, 30, 100, 49.5}};  // a caption right above the box
  const auto p = place_labels({{{50, 50, 70, 60}, 10, 8}}, o);
  EXPECT_EQ(p.labels[0].position, LabelPosition::kBelow);
}

TEST(LabelPlacer, InsideCornerWhenAboveAndBelowAreTaken) {
  auto o = page(200, 200);
  o.taken = {{0, 0, 200, 49.5}, {0, 80.5, 200, 200}, {0, 0, 49.5, 200}, {90.5, 0, 200, 200}};
  const auto p = place_labels({{{50, 50, 90, 80}, 10, 8}}, o);
  EXPECT_EQ(p.labels[0].position, LabelPosition::kInsideTopLeft);
  EXPECT_DOUBLE_EQ(p.labels[0].box.x0, 51);
  EXPECT_DOUBLE_EQ(p.labels[0].box.y0, 51);
}

TEST(LabelPlacer, LeaderWhenEveryAdjacentSpotIsTaken) {
  auto o = page(200, 200);
  // Blocks right above, below, left and right of a small box (too small for a label inside).
  o.taken = {{55, 40, 65, 54.5}, {55, 65.5, 65, 80}, {40, 55, 54.5, 65}, {65.5, 55, 80, 65}};
  const auto p = place_labels({{{55, 55, 65, 65}, 10, 8}}, o);
  ASSERT_EQ(p.labels[0].position, LabelPosition::kLeader);
  EXPECT_EQ(p.with_leader, 1);
  for (const auto& t : o.taken) EXPECT_FALSE(overlaps(p.labels[0].box, t));
  // The leader starts on the box's edge and ends on the label.
  const auto& l = p.labels[0];
  EXPECT_TRUE(l.leader_x0 >= 55 && l.leader_x0 <= 65 && l.leader_y0 >= 55 && l.leader_y0 <= 65);
  EXPECT_TRUE(l.leader_x1 >= l.box.x0 && l.leader_x1 <= l.box.x1 && l.leader_y1 >= l.box.y0 && l.leader_y1 <= l.box.y1);
}

TEST(LabelPlacer, LeftOutAndCountedWhenNothingFits) {
  auto o = page(30, 30);
  const auto p = place_labels({{{10, 10, 20, 20}, 10, 8}, {{10, 10, 20, 20}, 10, 8}, {{10, 10, 20, 20}, 25, 8}}, o);
  EXPECT_TRUE(p.labels[0].shown());
  EXPECT_EQ(p.labels[2].position, LabelPosition::kLeftOut);  // 25 + gaps can't sit anywhere on a 30 pt page
  EXPECT_GE(p.left_out, 1);
}

// A's label would sit above A's left corner, 1.5 pt from B's corner: which box it names is unclear. As an
// exclusive label it keeps 2 pt from B (hypot(1.5, 0.5) = 1.58 < 2 above-left and below-left) and takes
// the next spot, above A's right corner.
TEST(LabelPlacer, ExclusiveLabelKeepsClearOfTheOtherExclusiveTargets) {
  auto o = page(200, 200);
  o.gap = 0.5;
  o.exclusive_clearance = 2;
  const LabelRect a{110, 110, 130, 130}, b{98, 110, 108.5, 130};
  auto p = place_labels({{a, 10, 5}, {b, 10, 5}}, o);
  EXPECT_EQ(p.labels[0].position, LabelPosition::kAbove);
  EXPECT_DOUBLE_EQ(p.labels[0].box.x0, 110);  // plain labels: the first spot, next to B
  p = place_labels({{a, 10, 5, true}, {b, 10, 5, true}}, o);
  EXPECT_EQ(p.labels[0].position, LabelPosition::kAbove);
  EXPECT_DOUBLE_EQ(p.labels[0].box.x0, 120);
  EXPECT_DOUBLE_EQ(p.labels[0].box.y1, 109.5);
  EXPECT_EQ(p.left_out_exclusive, 0);
}

// A box inside another of the same kind: every spot beside the inner one lies in the outer one, and any
// leader out crosses its edge, so the inner label is left out (and counted) instead of read as the outer's.
TEST(LabelPlacer, ExclusiveLabelIsLeftOutWhenNoSpotIsUnambiguous) {
  auto o = page(40, 40);
  o.gap = 0.5;
  o.exclusive_clearance = 2;
  const LabelRect outer{0, 0, 40, 40}, inner{10, 10, 30, 30};
  auto p = place_labels({{outer, 8, 5, true}, {inner, 8, 5, true}}, o);
  EXPECT_TRUE(p.labels[0].shown());
  EXPECT_EQ(p.labels[1].position, LabelPosition::kLeftOut);
  EXPECT_EQ(p.left_out, 1);
  EXPECT_EQ(p.left_out_exclusive, 1);
  p = place_labels({{outer, 8, 5}, {inner, 8, 5}}, o);  // plain labels: both placed
  EXPECT_TRUE(p.labels[1].shown());
  EXPECT_EQ(p.left_out_exclusive, 0);
  // A plain target overlapping the inner box is the same rock: it does not block the inner label.
  o.bounds = {-50, -50, 90, 90};
  p = place_labels({{inner, 8, 5, true}, {{12, 12, 32, 32}, 8, 5}}, o);
  EXPECT_EQ(p.labels[0].position, LabelPosition::kAbove);
}

// Exclusive labels of different groups (rock numbers, confidences) do not keep the clearance from each
// other's targets: the same setup as above, with B in group 1, gives A the first spot, next to B.
TEST(LabelPlacer, ClearanceIsKeptOnlyWithinAGroup) {
  auto o = page(200, 200);
  o.gap = 0.5;
  o.exclusive_clearance = 2;
  const LabelRect a{110, 110, 130, 130}, b{98, 110, 108.5, 130};
  LabelRequest ra{a, 10, 5, true, 0}, rb{b, 10, 5, true, 1};
  auto p = place_labels({ra, rb}, o);
  EXPECT_DOUBLE_EQ(p.labels[0].box.x0, 110);
  rb.group = 0;
  p = place_labels({ra, rb}, o);
  EXPECT_DOUBLE_EQ(p.labels[0].box.x0, 120);
}

// keep_off: the above-left spot {100, 94.5, 110, 99.5} overlaps K = [95, 108] x [90, 99.8] and the page
// ends at y = 125 (no room below), so the label goes above-right {110, 94.5, 120, 99.5}, 2 pt right of K.
// With keep_off_clearance 3 that is too near, and so are the top inside corners (0.7 pt below K): it
// goes to the bottom-left inside corner {100.5, 114.5}.
TEST(LabelPlacer, KeepOffRectsAreAvoidedWithTheirClearance) {
  auto o = page(200, 125);
  o.gap = 0.5;
  LabelRequest r{{100, 100, 120, 120}, 10, 5};
  EXPECT_DOUBLE_EQ(place_labels({r}, o).labels[0].box.x0, 100);
  r.exclusive = true;
  r.keep_off = {{95, 90, 108, 99.8}};
  auto p = place_labels({r}, o);
  EXPECT_EQ(p.labels[0].position, LabelPosition::kAbove);
  EXPECT_DOUBLE_EQ(p.labels[0].box.x0, 110);
  r.keep_off_clearance = 3;
  p = place_labels({r}, o);
  EXPECT_EQ(p.labels[0].position, LabelPosition::kInsideBottomLeft);
  EXPECT_DOUBLE_EQ(p.labels[0].box.x0, 100.5);
  EXPECT_DOUBLE_EQ(p.labels[0].box.y0, 114.5);
  // Walled in by keep_off rects on both sides and the page above and below: no spot and no leader (it
  // would cross a wall), so left out and counted.
  o.bounds = {0, 100, 200, 120};
  r = {{100, 100, 104, 120}, 10, 5, true};
  r.keep_off = {{90, 100, 100, 120}, {104, 100, 114, 120}};
  p = place_labels({r}, o);
  EXPECT_EQ(p.labels[0].position, LabelPosition::kLeftOut);
  EXPECT_EQ(p.left_out_exclusive, 1);
}

// Box 15 right below box 1, 10 pt apart: 15's label above it (7 pt high, a 1 pt gap) would end 2 pt below
// box 1, which keeps the 2 pt clearance but reads as box 1's as much as box 15's. Beside its box a label
// must be nearer its own box by half its height (3.5 pt): 1 pt from 15 needs 4.5 pt from box 1, so it goes
// below box 15 instead (1 pt from it, 18 pt from box 1).
TEST(LabelPlacer, ANumberBesideItsBoxIsClearlyNearerItThanTheNextBox) {
  auto o = page(200, 200);
  o.exclusive_clearance = 2;
  const LabelRect one{50, 40, 70, 50}, fifteen{50, 60, 70, 70};
  LabelRequest r1{one, 10, 7, true}, r15{fifteen, 10, 7, true};
  EXPECT_EQ(place_labels({r1, r15}, o).labels[1].position, LabelPosition::kAbove);  // the plain clearance only
  r1.nearest_own = r15.nearest_own = true;
  const auto p = place_labels({r1, r15}, o);
  EXPECT_EQ(p.labels[0].position, LabelPosition::kAbove);
  EXPECT_EQ(p.labels[1].position, LabelPosition::kBelow);
  EXPECT_DOUBLE_EQ(p.labels[1].box.y0, 71);
  // 4.5 pt apart from box 1 is enough: with the boxes 12.5 pt apart it stays above box 15.
  r15.target = {50, 62.5, 70, 72.5};
  const auto q = place_labels({r1, r15}, o);
  EXPECT_EQ(q.labels[1].position, LabelPosition::kAbove);
  EXPECT_DOUBLE_EQ(q.labels[1].box.y1, 61.5);
}

// The rule holds for every number placed beside its box in a dense crowd of exclusive labels.
TEST(LabelPlacer, InACrowdEveryNumberBesideItsBoxIsNearestItsOwn) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 240);
  std::vector<LabelRequest> req;
  for (int k = 0; k < 60; ++k) {
    const double x = u(rng), y = u(rng) * 0.6;
    req.push_back({{x, y, x + 6 + u(rng) / 20, y + 6 + u(rng) / 20}, 8, 7, true});
    req.back().nearest_own = true;
  }
  auto o = page(252, 160);
  o.exclusive_clearance = 2;
  const auto p = place_labels(req, o);
  const auto gap = [](const LabelRect& a, const LabelRect& b) {
    const double dx = std::max({0.0, a.x0 - b.x1, b.x0 - a.x1}), dy = std::max({0.0, a.y0 - b.y1, b.y0 - a.y1});
    return std::hypot(dx, dy);
  };
  int beside = 0;
  for (size_t i = 0; i < req.size(); ++i) {
    const PlacedLabel& l = p.labels[i];
    if (!l.shown() || l.position == LabelPosition::kLeader) continue;
    ++beside;
    for (size_t j = 0; j < req.size(); ++j) {
      if (j != i) EXPECT_GE(gap(l.box, req[j].target), gap(l.box, req[i].target) + 3.5 - 1e-9) << i << " " << j;
    }
  }
  EXPECT_GT(beside, 20);
}

TEST(LabelPlacer, NoTwoLabelsOverlapInACrowd) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 240);
  std::vector<LabelRequest> req;
  for (int k = 0; k < 80; ++k) {
    const double x = u(rng), y = u(rng) * 0.6;
    req.push_back({{x, y, x + 4 + u(rng) / 20, y + 4 + u(rng) / 20}, 9, 9.3});
  }
  const auto p = place_labels(req, page(252, 160));
  int shown = 0;
  for (size_t i = 0; i < p.labels.size(); ++i) {
    if (!p.labels[i].shown()) continue;
    ++shown;
    const auto& b = p.labels[i].box;
    EXPECT_TRUE(b.x0 >= 0 && b.y0 >= 0 && b.x1 <= 252 && b.y1 <= 160);
    for (size_t j = 0; j < i; ++j)
      if (p.labels[j].shown()) {
        EXPECT_FALSE(overlaps(b, p.labels[j].box)) << i << " " << j;
      }
  }
  EXPECT_EQ(shown + p.left_out, 80);
  EXPECT_GT(shown, 40);
}

TEST(LabelPlacer, BadOptionsAreRejected) {
  LabelPlacementOptions o;
  EXPECT_THROW(place_labels({}, o), std::invalid_argument);  // empty bounds
  o = page(10, 10);
  o.gap = -1;
  EXPECT_THROW(place_labels({}, o), std::invalid_argument);
}

// Each check names its field; check() throws the sentence behind the "label placement: " prefix.
TEST(LabelPlacer, ValidateNamesTheBadField) {
  LabelPlacementOptions o = page(10, 10);
  EXPECT_EQ(o.validate(), "");
  o.max_leader = -0.5;
  EXPECT_EQ(o.validate(), "max_leader must be >= 0");
  o.max_leader = 3;
  o.exclusive_clearance = -1;
  EXPECT_EQ(o.validate(), "exclusive_clearance must be >= 0");
  o.exclusive_clearance = 1;
  o.gap = -1;
  EXPECT_EQ(o.validate(), "gap must be >= 0");
  try {
    o.check();
    FAIL() << "check() accepted a negative gap";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "label placement: gap must be >= 0");
  }
  EXPECT_EQ(LabelPlacementOptions{}.validate(), "the bounds are empty");
}

}  // namespace
}  // namespace ipd
