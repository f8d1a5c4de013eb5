// The blink view (B): one pane with the right picture laid over the left one through the scene's registration,
// shown in turn (a key or a rate, as an astronomer's blink comparator) or blended (an opacity slider), with both
// domains' GT and predicted boxes (or outlines) in the same frame, each domain in its own colour, GT solid and
// predictions dashed. Pairs set by hand and the selected rock with its partner stay highlighted.
#pragma once

#include <imgui.h>

#include "ui/gui/scene_canvas.h"

namespace ipd::ui {

// Each domain's colour in the blink view: the left one's as the panes draw it (GT pink, predictions red), the
// right one's green (GT) and blue (predictions), so the two sets never read as one.
constexpr ImU32 kRightGt = IM_COL32(90, 230, 120, 255);
constexpr ImU32 kRightPrediction = IM_COL32(60, 150, 255, 255);
constexpr ImU32 kHandPair = IM_COL32(255, 230, 40, 255);  // a pair set by hand: both rocks and the line joining them

struct BlinkState {
  bool on = false;
  bool overlay = false;        // false: one picture at a time; true: the right one over the left at `opacity`
  float opacity = 0.5f;        // overlay: the right picture's opacity
  float flips_per_second = 0;  // blink: alternate at this rate; 0: the key (V) flips
  bool manual_right = false;   // blink without a rate: the right picture is shown
  double rate_started = 0;     // ImGui time when the rate was set (the alternation counts from it)
  CanvasView view;             // zoom and pan of the pane, in the left picture's terms
};

// What the blink view drew in the last frame: for --frame-stats and the replay's state dump.
struct BlinkDrawn {
  bool drawn = false;
  bool pictures = false;    // false: a labels-only scene, boxes only
  float right_opacity = 0;  // 0: the left picture alone, 1: the right one alone (blink), between: overlay
  int gt_left = 0, gt_right = 0, predictions_left = 0, predictions_right = 0;
  int hand_pairs = 0;                // pairs set by hand, highlighted
  ImVec2 pane{0, 0}, picture{0, 0};  // the pane, and the left picture's part of it on screen
};

}  // namespace ipd::ui
