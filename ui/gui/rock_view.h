// The linked rock view: every counted pair of the current cell (domain pair and model) as a point, x and y
// chosen among each side's performance, |diff|, size, position and each side's confidence, over the filtered
// scene list or the current scene. Hover names the rock pair, a click goes to its scene with the pair
// selected, a drag box becomes a filter of the scene list ("selection: 37 pairs in 12 scenes", cleared from
// the list). Its second tab, the paired-rock gallery, lists the worst |diff| pairs first, left | right side
// by side with their boxes.
// The points are gathered off the UI thread (app/studio/studio_points.h) and binned into small cells
// (core/session/pair_density.h) when they, the axes, the plot's size or the drag box change: a frame draws
// the occupied cells, shaded by how many pairs each holds, never the 300,000 pairs of a 10,000-scene study.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/session/pair_density.h"
#include "core/session/rock_pair_points.h"
#include "ui/gui/views.h"

namespace ipd::ui {

struct RockViewState {
  int x_axis = static_cast<int>(PairAxis::kPerfA), y_axis = static_cast<int>(PairAxis::kPerfB);
  bool current_scene = false;  // false: the scene list as filtered
  bool dragging = false;
  ImVec2 drag_from{0, 0};
  GallerySort gallery_sort = GallerySort::kDiff;  // largest first
  int gallery_page = 0;
  int select_tab = -1;  // 0: scatter, 1: gallery, shown on the next frame (a script's `gallery`); -1: as is
  // The points in use (from the Rock pairs job) and what was derived from them.
  std::shared_ptr<const RockPointSet> points;
  std::vector<int> gallery;                      // points in the gallery's order
  std::optional<GallerySort> gallery_sorted_by;  // gallery_sort the order was made for
  // The binned scatter and what it was binned for.
  PairDensity density;
  ScatterRange range;
  const RockPointSet* binned_points = nullptr;
  int binned_x = -1, binned_y = -1, binned_w = 0, binned_h = 0;
  std::shared_ptr<const std::vector<RockPairKey>> binned_selection;  // the selection highlighted (UiState's)
};

// The scenes whose pairs the view shows, ascending: the scene list's scenes (ui.order, before a selection
// of this view narrowed it), or only ui.scene.
std::vector<int> rock_view_scenes(const UiState& ui, const RockViewState& st);

// Takes `points` for the view when they belong to the session's current cell (domain pair, its order and
// model): older points of the same cell are shown while newer ones are gathered. True when they changed.
bool adopt_rock_points(const Session& s, const std::shared_ptr<const RockPointSet>& points, RockViewState& st);

// An axis as the view names it: the domain's name, not A or B ("perf real", "conf synthetic", "|diff|").
std::string pair_axis_label(PairAxis axis, const std::string& left, const std::string& right);

// The window (open while ui.show_rock_view); `points`: the latest gathered (may be null or stale).
void draw_rock_view(const StudyView& v, const std::shared_ptr<const RockPointSet>& points, bool gathering,
                    RockViewState& st, UiState& ui, UiCommands& out);

// Sets the scene list's selection filter from a drag box (nothing when it holds no pair).
void apply_pair_selection(const Session& s, const PairSelection& sel, UiState& ui);
// A drag box on the scatter's current axes, in data coordinates (corners in either order): its pairs become the
// scene list's selection. The mouse and scripts (`select`) both end here.
void select_pairs_in_box(const Session& s, const RockViewState& st, double x0, double y0, double x1, double y1,
                         UiState& ui);
// Pairs highlighted on the scatter as last binned (the selection's pairs among the points shown).
int highlighted_pairs(const RockViewState& st);

}  // namespace ipd::ui
