// Where the picture panes put rock numbers and confidences: the figures' label placer (core/geometry/label_placer.h)
// with the panes' rules, so on a dense scene no number sits under another ("26" over "6") and none covers a rock when a
// free spot exists. GL-free, so tests check the spots with hand-computed numbers.
#pragma once

#include <vector>

#include "core/geometry/label_placer.h"

namespace ipd::ui {

struct RockNumberTag {
  LabelRect rock;                // the rock's box on screen
  double width = 0, height = 0;  // its number's text, backdrop included
};

// One placed label per tag, same order: above the box's left end first, then below, the other end, inside,
// beside, then a short leader; left out (hover still names the rock) only when nothing is free in `pane`.
LabelPlacement place_rock_numbers(const std::vector<RockNumberTag>& tags, const LabelRect& pane);

// A prediction's confidence on a picture pane: its box on screen, the text's size, and the GT box it
// matches (its highest IoU; -1: none), the only GT box the label may lie on.
struct ConfidenceTag {
  LabelRect prediction;
  double width = 0, height = 0;
  int matched_gt = -1;
};

// One placed label per tag, same order, as the figures place confidences: clear of the placed rock numbers
// (`taken`), of every other prediction's box and of every GT box but its match (`gt`, screen rectangles), so
// a confidence never reads as a neighbour's; left out when no spot in `pane` is free.
LabelPlacement place_confidences(const std::vector<ConfidenceTag>& tags, const std::vector<LabelRect>& gt,
                                 const std::vector<LabelRect>& taken, const LabelRect& pane);

}  // namespace ipd::ui
