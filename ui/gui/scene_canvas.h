// Drawing one side of an image pair (picture, GT boxes with rock numbers, predictions with confidences)
// into any ImDrawList: the GUI's window and the headless figure renderer share it.
#pragma once

#include <imgui.h>

#include <string>
#include <vector>

#include "core/geometry/geometry.h"
#include "core/registration/registration.h"
#include "core/session/audit.h"

namespace ipd::ui {

// Colours of the paper's Fig. 1: GT pink, predictions red.
constexpr ImU32 kPink = IM_COL32(255, 105, 200, 255);
constexpr ImU32 kRed = IM_COL32(235, 40, 40, 255);
constexpr ImU32 kGreyUnpaired = IM_COL32(160, 160, 160, 255);
constexpr ImU32 kHighlight = IM_COL32(255, 230, 40, 255);
constexpr ImU32 kSelected = IM_COL32(60, 200, 255, 255);
constexpr ImU32 kSuspect = IM_COL32(255, 140, 0, 255);  // audit: a pair that looks wrong
constexpr ImU32 kTriple = IM_COL32(80, 255, 120, 255);  // replay: the hypothesis' sample rocks

// Zoom about the picture centre and pan in picture-normalised units; shared by both sides when synced.
struct CanvasView {
  float zoom = 1.0f;
  ImVec2 pan{0, 0};
};

struct SideLayers {
  bool gt = true, predictions = true, indices = true, confidences = true;
};

struct SideInput {
  ImTextureID texture = nullptr;  // null: draw a placeholder
  int image_w = 0, image_h = 0;   // for the aspect ratio (placeholder too)
  std::string placeholder;        // why there is no picture
  const std::vector<Box>* gt = nullptr;
  const std::vector<Box>* predictions = nullptr;
  std::vector<int> best_prediction;   // per GT rock, its best-IoU prediction (-1 none)
  std::vector<int> number;            // per GT rock: its pair's number (> 0) or 0 when unpaired
  std::vector<char> excluded;         // per GT rock
  int highlight = -1, selected = -1;  // GT rocks to emphasise
  std::vector<char> suspect;          // per GT rock: its pair is suspect (drawn in kSuspect)
  std::vector<int> sample;            // GT rocks of the replayed hypothesis' sample (drawn in kTriple)
  std::string caption;
  bool fill_background = true;  // the GUI paints its background once, with the GL clear
  // Confidences of predicted boxes narrower than this on screen are left out (they would overlap and
  // can't be read; zooming in brings them back). 0: always shown, as figures do.
  float min_box_px_for_confidence = 0;
};

// Per GT rock of one side, the number its pair is shown with (stable: the left rock's 1-based index), 0 when
// unpaired. GL-free, in core: the GUI and figures share it.
using ipd::pair_numbers;

// The picture's rectangle inside `area` (fit, keep aspect, then zoom and pan).
struct Placement {
  ImVec2 origin, size;  // of the whole (zoomed) picture
  ImVec2 to_screen(double x, double y) const { return {origin.x + float(x) * size.x, origin.y + float(y) * size.y}; }
};
Placement place(ImVec2 area_min, ImVec2 area_size, int image_w, int image_h, const CanvasView& view);

// A closed path on screen: solid (ground truth) or dashed, 6 px dashes and 4 px gaps running on round the
// corners (predictions), as the panes, the blink view and the print figures draw them.
void draw_closed_path(ImDrawList* dl, const std::vector<ImVec2>& points, ImU32 colour, float thickness, bool dashed);

// Draws one side; returns the GT rock under `mouse` (-1 none). `text_scale` scales labels (figures).
int draw_side(ImDrawList* dl, ImVec2 area_min, ImVec2 area_size, const CanvasView& view, const SideInput& in,
              const SideLayers& layers, ImVec2 mouse, float text_scale = 1.0f);

}  // namespace ipd::ui
