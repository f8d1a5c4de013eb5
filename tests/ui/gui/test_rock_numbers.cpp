// Rock numbers of the picture panes (ui/gui/rock_numbers.h): no number under another, with hand-computed
// spots.
#include <gtest/gtest.h>

#include "ui/gui/rock_numbers.h"

namespace ipd::ui {
namespace {

TEST(RockNumbers, NeighboursNumbersDoNotCoverEachOther) {
  // Rock 26 at x 100..130 and rock 6 at x 110..140, both y 100..130, numbers 16 x 13 px. Above the left end
  // both would be at y 86..99, x 100..116 and 110..126: "26" over "6". The first takes it; the second's
  // first free spot is below its own box's left end: (110, 131), 1 px under the box.
  const std::vector<RockNumberTag> tags = {{{100, 100, 130, 130}, 16, 13}, {{110, 100, 140, 130}, 16, 13}};
  const LabelPlacement p = place_rock_numbers(tags, {0, 0, 400, 300});
  ASSERT_EQ(p.labels.size(), 2u);
  EXPECT_EQ(p.labels[0].position, LabelPosition::kAbove);
  EXPECT_DOUBLE_EQ(p.labels[0].box.x0, 100);
  EXPECT_DOUBLE_EQ(p.labels[0].box.y0, 86);  // 100 - 1 - 13
  EXPECT_EQ(p.labels[1].position, LabelPosition::kBelow);
  EXPECT_DOUBLE_EQ(p.labels[1].box.x0, 110);
  EXPECT_DOUBLE_EQ(p.labels[1].box.y0, 131);
  EXPECT_FALSE(overlaps(p.labels[0].box, p.labels[1].box));
  EXPECT_EQ(p.left_out, 0);
}

TEST(RockNumbers, ABoxAtThePaneTopGetsItsNumberBelow) {
  // Above would be at y -14: outside the pane, so below the box: y 41 (40 + 1).
  const LabelPlacement p = place_rock_numbers({{{10, 0, 40, 40}, 16, 13}}, {0, 0, 400, 300});
  EXPECT_EQ(p.labels[0].position, LabelPosition::kBelow);
  EXPECT_DOUBLE_EQ(p.labels[0].box.x0, 10);
  EXPECT_DOUBLE_EQ(p.labels[0].box.y0, 41);
}

// The panes ask again every frame and get the kept answer back, but only for the same request: the same box in
// a pane whose top is lower (the pane scrolled) has no room above any more, and the first pane's answer holds
// again when it comes back.
TEST(RockNumbers, AKeptPlacementIsOnlyReusedForTheSameRequest) {
  const std::vector<RockNumberTag> tags = {{{10, 20, 40, 60}, 16, 13}};
  for (int round = 0; round < 2; ++round) {
    EXPECT_EQ(place_rock_numbers(tags, {0, 0, 400, 300}).labels[0].position, LabelPosition::kAbove);
    EXPECT_EQ(place_rock_numbers(tags, {0, 15, 400, 300}).labels[0].position, LabelPosition::kBelow);
    std::vector<RockNumberTag> wider = tags;
    wider[0].height = 25;  // a larger font: 20 - 1 - 25 < 0, no room above in the first pane either
    EXPECT_EQ(place_rock_numbers(wider, {0, 0, 400, 300}).labels[0].position, LabelPosition::kBelow);
  }
}

// The same for confidences: a rock number placed where the confidence would go (`taken`) moves it, and the
// kept answer for the free pane holds again after.
TEST(RockNumbers, AKeptConfidencePlacementFollowsWhatIsTaken) {
  const std::vector<ConfidenceTag> tags = {{{100, 100, 130, 130}, 20, 10, -1}};
  const LabelRect pane{0, 0, 400, 300};
  const LabelRect above{100, 89, 120, 99};  // where "above" puts it: y 100 - 1 - 10
  for (int round = 0; round < 2; ++round) {
    const LabelPlacement free = place_confidences(tags, {}, {}, pane);
    EXPECT_EQ(free.labels[0].position, LabelPosition::kAbove);
    EXPECT_DOUBLE_EQ(free.labels[0].box.y0, 89);
    EXPECT_NE(place_confidences(tags, {}, {above}, pane).labels[0].position, LabelPosition::kAbove);
  }
}

TEST(RockNumbers, DenseSceneNeverStacksNumbers) {
  // 60 rocks of 20 x 20 px on a 10 x 6 grid 24 px apart: every shown number is clear of every other.
  std::vector<RockNumberTag> tags;
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 10; ++c) tags.push_back({{20.0 + 24 * c, 20.0 + 24 * r, 40.0 + 24 * c, 40.0 + 24 * r}, 16, 13});
  const LabelPlacement p = place_rock_numbers(tags, {0, 0, 300, 200});
  int shown = 0;
  for (size_t i = 0; i < p.labels.size(); ++i) {
    if (!p.labels[i].shown()) continue;
    ++shown;
    for (size_t j = i + 1; j < p.labels.size(); ++j) {
      if (!p.labels[j].shown()) continue;
      EXPECT_FALSE(overlaps(p.labels[i].box, p.labels[j].box)) << i << " and " << j;
    }
  }
  EXPECT_EQ(shown + p.left_out, 60);
  EXPECT_GT(shown, 0);
}

}  // namespace
}  // namespace ipd::ui
