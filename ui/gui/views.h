// The panels of ipd-studio. They read an immutable snapshot of the study (the worker's Session and the
// per-scene summaries) and the UI's own view state, and return what the user asked for as commands; the
// app applies them in one place (study changes go to the worker, view changes stay here).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/session/rock_pair_points.h"
#include "core/session/scene_filter.h"
#include "core/session/session.h"
#include "core/session/session_statistics.h"
#include "ui/gui/blink_view.h"
#include "ui/gui/pane_zoom.h"
#include "ui/gui/scene_canvas.h"

namespace ipd::ui {

// An IPD as the views print it: 4 decimals, "n/a" for NaN.
std::string fmt_ipd(double v);

// A table column sized from text, not pixels: wide enough for its header (with the sort arrow) and for
// `widest`, the longest value it shows. `tooltip` explains a short header when it is hovered.
struct TextColumn {
  const char* header;
  const char* widest;
  const char* tooltip = nullptr;
  ImGuiTableColumnFlags flags = 0;
};
// `sortable`: room for the sort arrow beside the header (ImGui keeps it beside every sortable column's header; an
// unsortable table's headers need none).
float text_column_width(const TextColumn& c, bool sortable = true);
// TableSetupColumn for each (fixed width from text, or stretched when `widest` is null), then the header
// row, with the tooltips.
void setup_text_columns(const std::vector<TextColumn>& columns, bool sortable = true);
// The width fixed-width columns take at the current font, their cell padding included.
float text_columns_width(const std::vector<TextColumn>& columns, bool sortable = true);
// A table never cuts columns silently: the largest font scale (1, 0.95, ... down to kMinTableFontScale) at which
// the columns fit in `avail`, `needed(scale)` being their width at that scale (text shrinks with the font, cell
// padding does not); a table still wider scrolls sideways at the smallest. Set with ImGui::SetWindowFontScale
// around the table, whose ID names the scale (scaled_table_id): a table sets its columns' widths once, so each
// scale is a table of its own.
inline constexpr float kMinTableFontScale = 0.8f;  // 12 px of the studio's 15
float table_font_scale(const std::function<float(float scale)>& needed, float avail);
// The same for columns drawn in the current window: measured with ImGui at each scale.
float table_font_scale(const std::vector<TextColumn>& columns, bool sortable, float extra, float avail);
std::string scaled_table_id(const char* name, float scale);  // "scenes##85" at 0.85

struct Picture {
  ImTextureID texture = nullptr;
  int width = 0, height = 0;
  std::string placeholder;  // "loading…" or why it can't be shown
};

// What the views read this frame: never modified by them.
struct StudyView {
  const Session* session = nullptr;
  // A domain's picture of a scene, loaded in the background when not yet in (the gallery's crops); empty: none.
  std::function<Picture(const std::string& domain, const std::string& stem)> picture_of;
  const std::vector<SceneSummary>* summaries = nullptr;  // per scene, computed by the worker once per change
  const RegistrationReport* rerun = nullptr;             // a re-run (with its trace) of the current scene
  bool rerun_is_automatic = false;                       // the re-run repeats the study's own registration
  // Status bar inputs.
  int pending_saves = 0;
  std::vector<std::string> failed_saves;
  int unsaved_edits = 0;  // edits of a read-only study made since it was last saved elsewhere ('save as')
  // Saves refused because someone else changed the file (the conflict dialog shows the first).
  struct Conflict {
    std::string key;           // the save's file (UiCommands::keep_mine / keep_theirs)
    std::string message;       // "FILE: changed on disk since ..."
    std::string mine, theirs;  // both versions, summarised ("3 pairs, 1 excluded rock: {...}")
  };
  std::vector<Conflict> conflicts;
  bool busy = false;                         // the worker is computing
  std::string loading;                       // a first look is shown while the study loads: how far it got
  const SessionStatistics* stats = nullptr;  // intervals etc. (stats_panels.h), computed off the UI thread
  // Every problem found in the study's data (the session's, then pictures that could not be read).
  const std::vector<Problem>* problems = nullptr;
};

// The replay of a registration's search (the trace), as a position on its timeline.
struct ReplayState {
  bool playing = false;
  float position = 0;  // 0 .. steps (hypotheses/iterations) + 1 (the final raw -> aligned motion)
  float speed = 20;    // steps per second
};

// What the scene list sorts by (UiState::sort_column); each of its columns sorts by one of these.
enum SceneSortKey : int { kByStem, kByIpd, kByPairs, kByUnpaired, kBySuspects, kByEdited, kByAmbiguous, kByReviewed };

// What the views remember between frames (never study data).
struct UiState {
  int scene = 0;
  CanvasView left_view, right_view;
  bool sync_views = true;
  SideLayers layers;
  int selected_left = -1, selected_right = -1;  // a click on one side waits for one on the other
  int hover_left = -1, hover_right = -1;
  int sort_column = kByIpd;     // browser: a SceneSortKey
  bool sort_descending = true;  // worst first: the audit order
  std::string list_table_id;    // the scene list's table last frame (a new font scale: a new table)
  char filter[128] = "";
  ReplayState replay;
  int rerun_method = 0, rerun_seed = 0;  // rerun_method: index into registration_methods()
  // The re-run's time budget in ms: < 0 until edited (then study.yaml's registration.budget_ms is used), 0: none.
  float rerun_budget_ms = -1;
  bool rerun_discarded = false;
  double conf_threshold = 0.0;  // as the slider shows it (conf_slider_value)
  char save_as_dir[512] = "";
  std::string status;
  std::vector<int> order;  // browser_order(), recomputed by the app only when its inputs change
  // The scene the list last scrolled into view: a scene shown by N, a name, a histogram bar or the gallery
  // may sit thousands of rows away from the list's scroll position.
  int list_scrolled_to = -1;
  // With a rock-view selection: the list the filter alone gives, so the scatter keeps every pair it was drawn
  // on (a second box then selects among all of them, not within the first); empty without a selection.
  std::vector<int> order_without_selection;
  std::string filter_error;
  // Chrome: menus and dialogs.
  bool show_help = false, show_goto = false, show_open = false, show_quit = false;
  // A text field outside the dialogs to take the keyboard on the next frame (Ctrl+F: the scene list's filter).
  enum class Field { kNone, kSearch, kSaveAs };
  Field focus_field = Field::kNone;
  ImVec2 picture_px[2] = {};  // the pictures' parts on screen, left and right (--frame-stats' picture_px)
  // The key index of F1 (the window's backend maps it: ImGui 1.86 names no F keys); -1: only '?' opens the help.
  int help_key = -1;
  char goto_text[128] = "";
  std::string browse_dir;                      // the Open study… browser's directory
  std::vector<std::string> browse_dirs;        // its subdirectories (listed by the app when browse_dir changes)
  bool browse_is_study = false;                // browse_dir has a study.yaml or domain folders
  char open_path[1024] = "";                   // the Open dialog's path field (typed or pasted)
  std::string open_error;                      // why the typed path was not opened (shown under the field)
  std::vector<std::string> recent;             // recent studies, newest first
  float pictures_height = -1;                  // height of the pictures pane; -1: fit the pictures' aspect
  float browser_width = -1, stats_width = -1;  // side columns as dragged; -1: from their content
  bool quit_confirmed = false;
  bool show_problems = false;            // the Problems window
  bool focus = false;                    // focus view: the pictures fill the window, the side columns are strips (Z)
  bool keep_zoom_across_scenes = false;  // else a scene change fits both pictures again
  bool show_rock_view = false;           // the linked rock view and gallery (rock_view.h)
  // The rock view's drag box as a filter of the scene list: the scenes (ascending) it holds pairs in, for the
  // domain pair and model it was drawn on (another one clears it); empty: no selection.
  std::vector<int> selection_scenes;
  std::string selection_label;  // "selection: 37 pairs in 12 scenes"
  // The selected pairs themselves (ascending), highlighted in the Rock pairs window on whatever axes it shows.
  std::shared_ptr<const std::vector<RockPairKey>> selection_pairs;
  int selection_pair = -1;
  std::string selection_model;
  BlinkState blink;                     // the blink view (B) in place of the two panes
  BlinkDrawn blink_drawn;               // what it drew last frame
  bool show_rank = false;               // the Rank window: the renderer settings ranked against the left domain
  bool show_registration_tab = false;   // the next frame brings the registration tab forward (a rerun's replay)
  bool registration_tab_shown = false;  // the registration tab was the one drawn last frame
};

struct UiCommands {
  std::vector<Edit> edits;
  bool undo = false, redo = false;
  int goto_scene = -1;
  std::string left_domain, right_domain, model;
  double conf_threshold = -1;
  bool rerun_registration = false;
  bool save_as = false;
  bool export_figures = false;  // Fig. 1 and Fig. 2 of the current view, through `ipd figure`
  bool export_dialog = false;   // File > Export figure… (the figure dialog hook)
  std::string open_study;       // File > Open study… / Recent
  std::string class_word;       // the class menu: the study opened again showing this class
  std::string open_typed_path;  // Enter in the Open dialog's path field: opened when it is a study
  bool retry_saves = false;
  std::string keep_mine, keep_theirs;     // a conflict's key: the version the user keeps
  bool quit = false;                      // confirmed (or nothing unsaved)
  bool next_suspect = false;              // `N`: the next suspect pair anywhere in the study
  bool toggle_reviewed = false;           // `R`: the scene in view marked reviewed (again: not)
  int check_left = -1, check_right = -1;  // `C`: this pair (view indices) checked as correct (again: not)
  int goto_problem = -1;                  // a row of the Problems window (index into StudyView::problems): its scene
  // A pair of the rock view: its scene, with the pair (view indices) selected and in view.
  int goto_pair_scene = -1, goto_pair_left = -1, goto_pair_right = -1;
};

// The scene order of the browser (sorted and filtered as the user asked); sets ui.filter_error.
std::vector<int> browser_order(const std::vector<SceneSummary>& summaries, UiState& ui);
// Sets ui.order, and ui.order_without_selection when a selection filters the list.
void update_browser_order(const std::vector<SceneSummary>& summaries, UiState& ui);

// The scene list's columns, left to right: header (sized from text) and what a click on it sorts by, which is
// also what its cells show.
struct BrowserColumn {
  TextColumn text;
  SceneSortKey sort_key;
};
const std::vector<BrowserColumn>& browser_columns();

// The study browser's width: the longest scene name and the numeric columns, within [min_w, max_w].
float browser_width(const StudyView& v, float min_w, float max_w);
// What a rock's number is: its box IoU, or its mask IoU in the segment task (the words every view uses).
const char* iou_word(const Session& s);
void draw_menu_bar(const StudyView& v, UiState& ui, UiCommands& out);
void draw_status_bar(const StudyView& v, UiState& ui, UiCommands& out);
void draw_dialogs(const StudyView& v, UiState& ui, UiCommands& out);  // help, go to scene, open study, quit
// The Problems window (views_problems.cpp), open while ui.show_problems; "1 problem", "3 problems".
void draw_problems_window(const StudyView& v, UiState& ui, UiCommands& out);
std::string problems_label(size_t count);
void draw_study_browser(const StudyView& v, UiState& ui, UiCommands& out);
float scene_toolbar_width();  // the pictures' toolbar on one line
void draw_side_by_side(const StudyView& v, UiState& ui, const Picture& left, const Picture& right, UiCommands& out);
// The blink view (blink_view.h) in the space the two panes would take (views_blink.cpp).
void draw_blink_view(const StudyView& v, UiState& ui, const Picture& left, const Picture& right, UiCommands& out);
// The blink view's legend: each domain's GT and predictions with their colour and line style.
std::string blink_legend(const Session& s);
void draw_registration(const StudyView& v, UiState& ui, UiCommands& out);
void draw_pair_table(const StudyView& v, UiState& ui, UiCommands& out);
void draw_ipd_panel(const StudyView& v, UiState& ui, UiCommands& out);
// The three columns (browser, pictures + registration + pair table, IPD + `draw_stats`) in `h` pixels,
// laid out by studio_columns() for the window's width.
void draw_main_columns(const StudyView& v, UiState& ui, const Picture& left, const Picture& right, float h,
                       const std::function<void()>& draw_stats, UiCommands& out);
// Text wrapped to the available width at spaces only (wrap_at_spaces): numbers are never split.
void text_wrapped_at_spaces(const std::string& text);
void text_disabled_wrapped_at_spaces(const std::string& text);
void text_coloured_wrapped_at_spaces(const ImVec4& colour, const std::string& text);
// SameLine() when an item `width` wide still fits on this line, else nothing (it goes on the next line).
void same_line_if_fits(float width);
float button_width(const char* label);

// The registration panel's words: its summary line ("real -> hapke: consensus, 1 trial, 5,982 hypotheses,
// ..."), the replayed step ("step 350 of 5,000 (hypothesis): score ..."), and what a capped trace holds.
std::string registration_summary(const std::string& a, const std::string& b, const RegistrationReport& r);
// One replayed step in words; its fit is in the method's measure (fit_measure_of).
std::string replay_step_line(const TraceStep& step, FitMeasure measure, int k, int steps);
std::string trace_cap_note(int steps, int hypotheses);
// "stopped: REASON; NOTE". When the time budget ended the registration the reason says so once: the note's
// sentences then say only where it ran out and what was left out ("while setting up the search: identity
// used"), not "time budget spent" again.
std::string registration_stop_line(const RegistrationReport& r);
// The warning of an ambiguous registration ("ambiguous: REASON; check the pairs"); when the time budget ended
// it, the budget may be why: a larger one may settle it.
std::string ambiguity_line(const RegistrationReport& r);
// Under the scrubber when the registration recorded no step: why (a budget spent before the search began, a
// method that records none) or, for the study's own registration, that its search is still being recorded.
std::string no_steps_line(const RegistrationReport& r, bool rerun);
// The time budget the registration panel shows for a re-run: ui.rerun_budget_ms once edited, else the study's
// registration.budget_ms (0: none).
float rerun_budget_ms(const UiState& ui, const RegistrationOptions& study);
// The budget a re-run is given: the one shown, unset when that is 0.
std::optional<double> rerun_time_budget(const UiState& ui, const RegistrationOptions& study);
// The registration canvas at `p0` of `size`: the plot's clip rect (all of the canvas above the three legend
// lines), the picture's box inside it (10 px margins) and the legend's top.
struct RegistrationCanvas {
  ImVec2 plot_min, plot_max, box_min, box_size;
  float legend_top = 0;
};
RegistrationCanvas registration_canvas(ImVec2 p0, ImVec2 size, float line_h);
// The selected rock's pair (left, right in view indices), or {-1, -1} when the selected rock is unpaired.
std::pair<int, int> selected_pair(const Session& s, const UiState& ui);
// "412 of 2,000 scenes reviewed, 37 suspect pairs left" (the domain pair in view).
std::string review_progress_line(const Session::ReviewProgress& p);
// Keyboard shortcuts that act on the whole window.
void handle_shortcuts(const StudyView& v, UiState& ui, UiCommands& out);
// Shortcuts act only when the keyboard is nobody else's: no text field is active and no dialog (modal or
// popup) is open. A letter typed into a dialog, even one whose field lost focus, never edits the study.
bool shortcuts_may_act();
// After a single-line text field drawn with ImGuiInputTextFlags_EnterReturnsTrue, given what it returned:
// Enter (which ends the edit) gives the keyboard straight back to the field, so the letters typed after a
// rejected entry go into it, not to the shortcuts. Esc or a click elsewhere still leaves it.
void keep_keyboard_after_enter(bool entered);
// Before a text field: it takes the keyboard when `ui.focus_field` asks for `field`.
void take_keyboard_if_asked(UiState& ui, UiState::Field field);
// Every shortcut, for the help window (and docs/gui.md).
const std::vector<std::pair<const char*, const char*>>& shortcut_list();

// Per-rock inputs of the canvas for one side of the current scene.
SideInput side_input(const Session& s, const UiState& ui, Side side, const Picture& picture);

// From the picture of view side k (0 left) to its partner's, through scene `scene`'s registration affine (which
// maps A onto B): sync zoom keeps a rock's partner under the cursor, and the blink view lays the right picture
// over the left one through towards_partner(s, scene, 1).
PaneAffine towards_partner(const Session& s, int scene, int k);

// The trace step shown at a replay position (clamped), -1 when the trace is empty.
int replay_step(const RegistrationReport& r, float position);

}  // namespace ipd::ui
