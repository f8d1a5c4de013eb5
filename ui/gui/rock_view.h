// The linked rock view: every counted pair of the current cell (domain pair and model) as a point, x and y
// chosen among perf A, perf B, |diff|, size, position and confidence, over the filtered scene list or the
// current scene. Hover names the rock pair, a click goes to its scene with the pair selected, a drag box
// becomes a filter of the scene list ("selection: 37 pairs in 12 scenes", cleared from the list). Its second
// tab, the paired-rock gallery, lists the worst |diff| pairs first, A | B side by side with their boxes.
// The points come from rock_pair_points (core/session), gathered again only when the snapshot or the scene
// list changes; thousands of points are drawn once per screen pixel, on ImGui's draw list.
#pragma once

#include <vector>

#include "core/session/rock_pair_points.h"
#include "ui/gui/views.h"

namespace ipd::ui {

struct RockViewState {
  int x_axis = static_cast<int>(PairAxis::kPerfA), y_axis = static_cast<int>(PairAxis::kPerfB);
  bool current_scene = false;  // false: the scene list as filtered
  bool dragging = false;
  ImVec2 drag_from{0, 0};
  // The last drag box in data coordinates (its points are drawn highlighted), on axes (box_x, box_y).
  bool has_box = false;
  int box_x = 0, box_y = 0;
  double bx0 = 0, by0 = 0, bx1 = 0, by1 = 0;
  int gallery_sort = 0;  // 0: |diff|, 1: perf A, 2: perf B, 3: size; largest first
  int gallery_page = 0;
  // What the points were gathered from (recomputed when any of it changes).
  const Session* session = nullptr;
  std::vector<int> scenes;
  std::vector<RockPairPoint> points;
  std::vector<int> gallery;          // points in the gallery's order
  int gallery_sorted_by = -1;        // gallery_sort the order was made for
  std::vector<unsigned char> drawn;  // one flag per plot pixel: a point already drawn there
};

// The pairs the view shows: the scene list's scenes (ui.order, before a selection of this view narrowed it),
// or only ui.scene. Gathered again only when
// the snapshot, the scope or the list changed; true when it did.
bool refresh_rock_points(const Session& s, const UiState& ui, RockViewState& st);

// The gallery's order of st.points for sort key `sort` (see RockViewState::gallery_sort): largest first,
// ties in gallery_order's order (scene, then rocks).
std::vector<int> gallery_sorted(const std::vector<RockPairPoint>& points, int sort);

// The window (open while ui.show_rock_view).
void draw_rock_view(const StudyView& v, RockViewState& st, UiState& ui, UiCommands& out);

// Sets the scene list's selection filter from a drag box (nothing when it holds no pair).
void apply_pair_selection(const Session& s, const PairSelection& sel, UiState& ui);

}  // namespace ipd::ui
