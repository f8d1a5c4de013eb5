#include "ui/gui/scene_change.h"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

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

std::string unchanged_by_edit(const Session& s, int scene, const Edit& edit) {
  if (scene < 0 || scene >= static_cast<int>(s.scenes().size())) return "";
  const SceneState& sc = s.scenes()[scene];
  if (edit.kind == Edit::Kind::kPair) {
    const RockPairs pairs = s.view_pairs(scene);
    if (std::binary_search(pairs.begin(), pairs.end(), std::make_pair(edit.a, edit.b)) &&
        !s.excluded(Side::kA, scene, edit.a) && !s.excluded(Side::kB, scene, edit.b))
      return fmt::format("{} rock {} and {} rock {} are a pair already in {}: nothing changed", s.left_domain(),
                         edit.a + 1, s.right_domain(), edit.b + 1, sc.stem);
  }
  if (edit.kind == Edit::Kind::kResetToAutomatic && !sc.edited && !sc.pairs_unusable)
    return sc.stem + " has the automatic pairs already: nothing changed";
  return "";
}

std::string edit_status(const Session& s, int scene, const Edit& edit) {
  if (scene < 0 || scene >= static_cast<int>(s.scenes().size())) return "";
  const std::string& stem = s.scenes()[scene].stem;
  // Rocks are numbered from 1 and named by their domain, as the pictures and the pair table show them.
  auto rock = [&](Side side, int index) {
    return fmt::format("{} rock {}", side == Side::kA ? s.left_domain() : s.right_domain(), index + 1);
  };
  switch (edit.kind) {
    case Edit::Kind::kPair:
      return fmt::format("paired {} with {} in {}", rock(Side::kA, edit.a), rock(Side::kB, edit.b), stem);
    case Edit::Kind::kUnpair:
      return fmt::format("unpaired {} in {}", rock(edit.side, edit.a), stem);
    case Edit::Kind::kToggleExclude:
      return fmt::format("{} {} in {}", rock(edit.side, edit.a),
                         s.excluded(edit.side, scene, edit.a) ? "counted again" : "excluded from the IPD", stem);
    case Edit::Kind::kResetToAutomatic:
      return stem + " reset to the automatic pairs";
    case Edit::Kind::kReplacePairs:
      return fmt::format("{} paired as the re-run registration pairs it", stem);
  }
  return "";
}

}  // namespace ipd::ui
