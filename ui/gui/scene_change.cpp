#include "ui/gui/scene_change.h"

#include "ui/gui/pane_zoom.h"

namespace ipd::ui {

void enter_scene(UiState& ui, int scene) {
  ui.scene = scene;
  ui.selected_left = ui.selected_right = -1;
  ui.replay = ReplayState{};
  ui.rerun_discarded = false;
  // A zoom fitted to one scene's rocks points at nothing in particular in the next one.
  const auto rule = ui.keep_zoom_across_scenes ? ZoomOnSceneChange::kKeep : ZoomOnSceneChange::kReset;
  ui.left_view = view_after_scene_change(ui.left_view, rule);
  ui.right_view = view_after_scene_change(ui.right_view, rule);
  // "suspect pair 3 in scene_00012" or a save's outcome read as if about the scene now shown.
  ui.status.clear();
}

void show_scene_of_edit(UiState& ui, int scene) {
  if (scene != ui.scene) return enter_scene(ui, scene);
  // "scene_00038 marked reviewed" is no longer true once that mark is undone.
  ui.status.clear();
}

}  // namespace ipd::ui
