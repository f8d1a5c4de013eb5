// The panels of ipd-studio. They read the session and the UI's own view state, and return what the user
// asked for as commands; the app applies them (edits to the session, saves to the saver thread).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "ipd/session.h"
#include "scene_canvas.h"

namespace ipd::ui {

struct Picture {
  ImTextureID texture = nullptr;
  int width = 0, height = 0;
  std::string placeholder;  // "loading…" or why it can't be shown
};

// What the views remember between frames (never study data).
struct UiState {
  int scene = 0;
  CanvasView left_view, right_view;
  bool sync_views = true;
  SideLayers layers;
  int selected_left = -1, selected_right = -1;  // a click on one side waits for one on the other
  int hover_left = -1, hover_right = -1;
  int sort_column = 1;                           // browser: 0 stem, 1 IPD, 2 pairs, 3 unpaired, 4 edited
  bool sort_descending = true;                   // worst first: the audit order
  char filter[64] = "";
  float anim_t = 1.0f;
  bool playing = false;
  int rerun_method = 0, rerun_seed = 0;
  std::optional<RegistrationReport> rerun;       // shown instead of the automatic one until applied
  float conf_threshold = 0.0f;
  char save_as_dir[512] = "";
  std::string status;
  std::vector<int> order;  // browser_order() of this frame, computed once by the app and shared by the views
};

struct UiCommands {
  std::vector<Edit> edits;
  bool undo = false, redo = false;
  int goto_scene = -1;
  std::string left_domain, right_domain, model;
  float conf_threshold = -1;
  bool rerun_registration = false;
  bool save_as = false;
  bool export_figures = false;  // Fig. 1 and Fig. 2 of the current view, through `ipd figure`
};

// The scene order of the browser (sorted and filtered as the user asked).
std::vector<int> browser_order(const Session& s, const UiState& ui);

void draw_study_browser(const Session& s, UiState& ui, UiCommands& out);
void draw_side_by_side(const Session& s, UiState& ui, const Picture& left, const Picture& right, UiCommands& out);
void draw_registration(const Session& s, UiState& ui, UiCommands& out);
void draw_pair_table(const Session& s, UiState& ui, UiCommands& out);
void draw_ipd_panel(const Session& s, UiState& ui, UiCommands& out);
// Keyboard shortcuts that act on the whole window.
void handle_shortcuts(const Session& s, UiState& ui, UiCommands& out);

// Per-rock inputs of the canvas for one side of the current scene.
SideInput side_input(const Session& s, const UiState& ui, Side side, const Picture& picture);

}  // namespace ipd::ui
