#include "ui/gui/scene_change.h"

#include <fmt/format.h>

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

namespace {

// The partner of a rock of the view's `side` among the view's (left, right) pairs, or -1.
int view_partner(const RockPairs& pairs, Side side, int rock) {
  for (const auto& [l, r] : pairs)
    if ((side == Side::kA ? l : r) == rock) return side == Side::kA ? r : l;
  return -1;
}

std::string rock_name(const Session& s, Side side, int rock) {
  return fmt::format("{} rock {}", side == Side::kA ? s.left_domain() : s.right_domain(), rock + 1);
}

}  // namespace

std::string unchanged_by_edit(const Session& s, int scene, const Edit& edit) {
  if (scene < 0 || scene >= static_cast<int>(s.scenes().size())) return "";
  const SceneState& sc = s.scenes()[scene];
  const RockPairs pairs = s.view_pairs(scene);
  if (edit.kind == Edit::Kind::kPair && view_partner(pairs, Side::kA, edit.a) == edit.b &&
      !s.excluded(Side::kA, scene, edit.a) && !s.excluded(Side::kB, scene, edit.b))
    return fmt::format("{} and {} are a pair already in {}: nothing changed", rock_name(s, Side::kA, edit.a),
                       rock_name(s, Side::kB, edit.b), sc.stem);
  if (edit.kind == Edit::Kind::kUnpair && view_partner(pairs, edit.side, edit.a) < 0)
    return fmt::format("{} is in no pair in {}: nothing changed", rock_name(s, edit.side, edit.a), sc.stem);
  if (edit.kind == Edit::Kind::kResetToAutomatic && !sc.edited && !sc.pairs_unusable)
    return sc.stem + " has the automatic pairs already: nothing changed";
  return "";
}

std::string edit_status(const Session& s, int scene, const Edit& edit) {
  if (scene < 0 || scene >= static_cast<int>(s.scenes().size())) return "";
  const std::string& stem = s.scenes()[scene].stem;
  const RockPairs pairs = s.view_pairs(scene);  // (left, right); a pair is shown numbered by its left rock
  auto partner = [&](Side side, int index) { return view_partner(pairs, side, index); };
  auto name = [&](Side side, int index) { return rock_name(s, side, index); };
  // A rock as the pictures show it: its number, and for a right rock in a pair, the pair's number it carries.
  auto rock = [&](Side side, int index) {
    const int other = side == Side::kB ? partner(side, index) : -1;
    return other >= 0 ? fmt::format("{} (pair {})", name(side, index), other + 1) : name(side, index);
  };
  switch (edit.kind) {
    case Edit::Kind::kPair: {
      // The rocks' old partners are left unpaired: said, as the pictures show them as "x" rocks now.
      std::string released;
      if (const int r = partner(Side::kA, edit.a); r >= 0 && r != edit.b) released = name(Side::kB, r);
      if (const int l = partner(Side::kB, edit.b); l >= 0 && l != edit.a)
        released += (released.empty() ? "" : " and ") + name(Side::kA, l);
      return fmt::format("pair {} is now {} | {} in {}{}", edit.a + 1, name(Side::kA, edit.a), name(Side::kB, edit.b),
                         stem, released.empty() ? "" : "; " + released + " unpaired");
    }
    case Edit::Kind::kUnpair: {
      const int other = partner(edit.side, edit.a);
      if (other < 0) return fmt::format("{} is in no pair in {}", name(edit.side, edit.a), stem);
      const int left = edit.side == Side::kA ? edit.a : other, right = edit.side == Side::kA ? other : edit.a;
      return fmt::format("pair {} unpaired in {} ({} | {})", left + 1, stem, name(Side::kA, left),
                         name(Side::kB, right));
    }
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
