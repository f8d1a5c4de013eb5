// Where the picture panes put rock numbers: the figures' label placer (core/geometry/label_placer.h) with
// the panes' rules, so on a dense scene no number sits under another ("26" over "6") and none covers a
// rock when a free spot exists. GL-free, so tests check the spots with hand-computed numbers.
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

}  // namespace ipd::ui
