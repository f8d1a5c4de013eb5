// What the views forget when another scene comes into view (GL-free, so tests check it without a window):
// the selection, the replay, the zoom (unless the user keeps it) and the status line, whose messages are
// about the scene or study they were posted in.
#pragma once

#include "ui/gui/views.h"

namespace ipd::ui {

void enter_scene(UiState& ui, int scene);
// Where an undo or redo took effect: that scene, entered as above when another one is in view; on the scene in
// view only the status line, about the action undone, is cleared (undoing a review mark keeps the selected pair,
// the zoom and the replay).
void show_scene_of_edit(UiState& ui, int scene);
// What the status line says when an edit of `scene` is sent, before the session applies it: the line about
// the last action (a refused edit's reason, say) no longer applies. A refusal replaces it when it comes back.
std::string edit_status(const Session& s, int scene, const Edit& edit);
// Why `edit` would change nothing in `scene` ("... are a pair already", "... has the automatic pairs already"),
// or "" when it changes something. Sending it anyway would write a pairs file of the same pairs, and the
// scene would count as edited by hand in every provenance note.
std::string unchanged_by_edit(const Session& s, int scene, const Edit& edit);

}  // namespace ipd::ui
