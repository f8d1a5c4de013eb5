// Around the panels: menu bar, status bar, shortcuts and their help, Go to scene, Open study (a directory
// browser drawn in ImGui) and the quit warning.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <tuple>

#include "core/report/table_format.h"
#include "ui/gui/stats_panels.h"
#include "ui/gui/studio_layout.h"
#include "ui/gui/table_layout.h"
#include "ui/gui/views.h"

namespace ipd::ui {

float text_column_width(const TextColumn& c, bool sortable) {
  // The sort arrow takes about a line's height beside a sortable header.
  const float header = ImGui::CalcTextSize(c.header).x + (sortable ? ImGui::GetTextLineHeight() : 0.0f);
  return std::max(header, c.widest ? ImGui::CalcTextSize(c.widest).x : 0.0f);
}

float text_columns_width(const std::vector<TextColumn>& columns, bool sortable) {
  float w = 0;
  for (const auto& c : columns)
    if (c.widest) w += text_column_width(c, sortable) + 2 * ImGui::GetStyle().CellPadding.x;
  return w;
}

float table_font_scale(const std::function<float(float scale)>& needed, float avail) {
  const int lowest = static_cast<int>(std::lround(kMinTableFontScale * 20));
  for (int k = 20; k > lowest; --k)
    if (needed(k / 20.0f) <= avail) return k / 20.0f;
  return kMinTableFontScale;
}

float table_font_scale(const std::vector<TextColumn>& columns, bool sortable, float extra, float avail) {
  const float scale = table_font_scale(
      [&](float s) {
        ImGui::SetWindowFontScale(s);
        return text_columns_width(columns, sortable) + extra;
      },
      avail);
  ImGui::SetWindowFontScale(1.0f);
  return scale;
}

std::string scaled_table_id(const char* name, float scale) {
  return std::string(name) + "##" + std::to_string(std::lround(scale * 100));
}

void setup_text_columns(const std::vector<TextColumn>& columns, bool sortable) {
  for (const auto& c : columns)
    ImGui::TableSetupColumn(c.header, c.flags | (c.widest ? ImGuiTableColumnFlags_WidthFixed : 0),
                            c.widest ? text_column_width(c, sortable) : 0.0f);
  ImGui::TableNextRow(ImGuiTableRowFlags_Headers);
  for (int k = 0; k < static_cast<int>(columns.size()); ++k) {
    if (!ImGui::TableSetColumnIndex(k)) continue;
    ImGui::TableHeader(ImGui::TableGetColumnName(k));
    if (columns[k].tooltip && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", columns[k].tooltip);
  }
}

std::string fmt_ipd(double v) {
  if (std::isnan(v)) return "n/a";
  char b[32];
  std::snprintf(b, sizeof b, "%.4f", v);
  return b;
}

namespace {
void wrapped_lines(const std::string& text, const ImVec4* colour) {
  const float width = std::max(40.0f, ImGui::GetContentRegionAvail().x);
  if (colour) ImGui::PushStyleColor(ImGuiCol_Text, *colour);
  for (const std::string& line :
       wrap_at_spaces(text, width, [](const std::string& t) { return ImGui::CalcTextSize(t.c_str()).x; }))
    ImGui::TextUnformatted(line.c_str());
  if (colour) ImGui::PopStyleColor();
}
}  // namespace

void text_wrapped_at_spaces(const std::string& text) { wrapped_lines(text, nullptr); }
void text_disabled_wrapped_at_spaces(const std::string& text) {
  wrapped_lines(text, &ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
}
void text_coloured_wrapped_at_spaces(const ImVec4& colour, const std::string& text) { wrapped_lines(text, &colour); }

float button_width(const char* label) { return ImGui::CalcTextSize(label).x + 2 * ImGui::GetStyle().FramePadding.x; }

void same_line_if_fits(float width) {
  const float right = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
  if (ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x + width <= right) ImGui::SameLine();
}

namespace {

bool pressed(int key) { return ImGui::IsKeyPressed(key, true); }

bool unsaved(const StudyView& v) {
  if (v.pending_saves > 0 || !v.failed_saves.empty()) return true;
  // A read-only study's edits are lost on quitting unless 'save as' wrote them since (the scenes stay
  // edited after it, so they can't tell).
  return v.session && v.session->read_only() && v.unsaved_edits > 0;
}

}  // namespace

const std::vector<std::pair<const char*, const char*>>& shortcut_list() {
  static const std::vector<std::pair<const char*, const char*>> list = {
      {"click left rock, then right rock", "pair them (old partners are released)"},
      {"U", "unpair the selected rock"},
      {"X", "exclude the selected rock from the IPD (again: include)"},
      {"Esc", "clear the selection"},
      {"Ctrl+Z / Ctrl+Y", "undo / redo (every edit, any scene)"},
      {"Right / J, Left / K", "next / previous scene in the list's order"},
      {"N", "next suspect pair anywhere in the study (pairs checked as correct are skipped)"},
      {"C", "the selected pair is checked, correct: no longer suspect (again: unchecked)"},
      {"R", "the scene is reviewed (again: not reviewed)"},
      {"Ctrl+G", "go to a scene by name"},
      {"Ctrl+O", "open another study"},
      {"Ctrl+F", "type in the scene list's filter (Esc leaves it)"},
      {"wheel", "zoom at the cursor"},
      {"drag", "pan (both pictures when sync zoom is on)"},
      {"F", "fit the picture to its pane"},
      {"Z", "focus view: the pictures fill the window (again: the panels come back)"},
      {"1", "1:1 (one picture pixel per screen pixel)"},
      {"B", "blink view: the right picture over the left one through the registration (again: the two pictures)"},
      {"V", "blink view: show the other picture"},
      {"Space", "play / pause the registration replay"},
      {"F1 or ?", "this list"},
      {"filter box", "text, ipd>0.1, ipd<=0.05, suspect, edited, ambiguous, reviewed, unreviewed (all must match)"},
  };
  return list;
}

void draw_menu_bar(const StudyView& v, UiState& ui, UiCommands& out) {
  if (!ImGui::BeginMenuBar()) return;
  if (ImGui::BeginMenu("File")) {
    if (ImGui::MenuItem("Open study...", "Ctrl+O")) ui.show_open = true;
    if (ImGui::BeginMenu("Recent studies", !ui.recent.empty())) {
      for (const auto& r : ui.recent)
        if (ImGui::MenuItem(r.c_str())) out.open_study = r;
      ImGui::EndMenu();
    }
    ImGui::Separator();
    if (ImGui::MenuItem("Export figure...", nullptr, false, v.session != nullptr)) out.export_dialog = true;
    if (ImGui::MenuItem("Retry failed saves", nullptr, false, !v.failed_saves.empty())) out.retry_saves = true;
    ImGui::Separator();
    if (ImGui::MenuItem("Quit", "Ctrl+Q")) ui.show_quit = true;
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("View")) {
    ImGui::MenuItem("GT boxes", nullptr, &ui.layers.gt);
    ImGui::MenuItem("Predictions", nullptr, &ui.layers.predictions);
    ImGui::MenuItem("Pair numbers", nullptr, &ui.layers.indices);
    ImGui::MenuItem("Confidences", nullptr, &ui.layers.confidences);
    ImGui::MenuItem("Sync zoom", nullptr, &ui.sync_views);
    if (ImGui::MenuItem("Fit pictures", "F")) ui.left_view = ui.right_view = CanvasView{};
    ImGui::MenuItem("Focus pictures", "Z", &ui.focus);
    ImGui::MenuItem("Keep zoom across scenes", nullptr, &ui.keep_zoom_across_scenes);
    if (ImGui::MenuItem("Go to scene...", "Ctrl+G")) ui.show_goto = true;
    if (ImGui::MenuItem("Next suspect pair", "N")) out.next_suspect = true;
    ImGui::MenuItem("Blink view", "B", &ui.blink.on);
    ImGui::MenuItem("Rock pairs (scatter, gallery)", nullptr, &ui.show_rock_view);
    ImGui::MenuItem("Rank renderer settings", nullptr, &ui.show_rank);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Review", v.session != nullptr && !v.session->scenes().empty())) {
    const Session& s = *v.session;
    if (ImGui::MenuItem("Scene reviewed", "R", s.reviewed(ui.scene))) out.toggle_reviewed = true;
    const auto [l, r] = selected_pair(s, ui);
    if (ImGui::MenuItem("Selected pair checked, correct", "C", l >= 0 && s.checked(ui.scene, l, r), l >= 0))
      out.check_left = l, out.check_right = r;
    if (ImGui::MenuItem("Next suspect pair", "N")) out.next_suspect = true;
    if (ImGui::MenuItem("Unreviewed scenes only", nullptr, std::string(ui.filter) == "unreviewed"))
      std::snprintf(ui.filter, sizeof ui.filter, "%s", std::string(ui.filter) == "unreviewed" ? "" : "unreviewed");
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Help")) {
    if (ImGui::MenuItem("Shortcuts", "F1")) ui.show_help = true;
    if (ImGui::MenuItem("Problems in the data", nullptr, ui.show_problems, v.problems != nullptr))
      ui.show_problems = !ui.show_problems;
    ImGui::EndMenu();
  }
  if (!v.failed_saves.empty()) {
    // A banner on the always-visible menu bar: hand edits that are not on disk must not go unnoticed.
    ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(0.75f, 0.1f, 0.1f, 1));
    ImGui::PushStyleColor(ImGuiCol_ButtonHovered, ImVec4(0.9f, 0.2f, 0.2f, 1));
    const std::string banner = thousands(static_cast<long long>(v.failed_saves.size())) +
                               " hand edit(s) NOT SAVED: " + v.failed_saves.front() + "  [Retry]";
    if (ImGui::Button(banner.c_str())) out.retry_saves = true;
    ImGui::PopStyleColor(2);
  }
  ImGui::EndMenuBar();
}

void draw_status_bar(const StudyView& v, UiState& ui, UiCommands& out) {
  if (v.session) {
    const Session& s = *v.session;
    // The study's folder name alone when its whole path does not fit the window (the browser shows the path).
    const std::string rest = "  |  " + counted(s.scenes().size(), "scene") + "  |  " + s.left_domain() + " vs " +
                             s.right_domain() + "  |  " + (s.model().empty() ? "no predictions" : s.model());
    std::string line = s.study().root + rest;
    if (ImGui::CalcTextSize(line.c_str()).x > ImGui::GetContentRegionAvail().x) {
      std::filesystem::path root(s.study().root);
      if (root.filename().empty()) root = root.parent_path();  // "…/study/"
      line = root.filename().string() + rest;
    }
    ImGui::TextUnformatted(line.c_str());
    ImGui::SameLine();
  }
  if (v.problems && !v.problems->empty()) {
    // Never silent: skipped label lines and scenes left out change what the IPD is computed over.
    ImGui::TextUnformatted("|");
    ImGui::SameLine();
    ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(0.7f, 0.35f, 0.05f, 1));
    if (ImGui::SmallButton(problems_label(v.problems->size()).c_str())) ui.show_problems = !ui.show_problems;
    ImGui::PopStyleColor();
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", v.problems->front().to_string().c_str());
    ImGui::SameLine();
  }
  if (!v.loading.empty()) {
    ImGui::TextColored({0.6f, 0.8f, 1, 1}, "|  %s", v.loading.c_str());
    ImGui::SameLine();
  } else if (v.busy) {
    ImGui::TextColored({0.6f, 0.8f, 1, 1}, "|  computing...");
    ImGui::SameLine();
  }
  if (v.pending_saves > 0) {
    ImGui::Text("|  saving %d file(s)", v.pending_saves);
    ImGui::SameLine();
  }
  if (!v.failed_saves.empty()) {
    ImGui::TextColored({1, 0.35f, 0.3f, 1}, "|  %zu save(s) FAILED: %s", v.failed_saves.size(),
                       v.failed_saves.front().c_str());
    ImGui::SameLine();
    if (ImGui::SmallButton("Retry")) out.retry_saves = true;
    ImGui::SameLine();
  }
  if (!ui.status.empty()) {
    ImGui::TextUnformatted(("|  " + ui.status).c_str());
    // A long message (an edit refused, with its way out) runs past the window's edge: hovering shows it whole.
    if (ImGui::IsItemHovered()) {
      ImGui::BeginTooltip();
      ImGui::PushTextWrapPos(ImGui::GetFontSize() * 40);
      ImGui::TextUnformatted(ui.status.c_str());
      ImGui::PopTextWrapPos();
      ImGui::EndTooltip();
    }
  } else
    ImGui::NewLine();
}

namespace {
// A save that would have overwritten someone else's change: both versions, and the user keeps one.
void draw_conflict_dialog(const StudyView& v, UiCommands& out) {
  const char* title = "Hand pairs changed on disk";
  if (!v.conflicts.empty() && !ImGui::IsPopupOpen(title)) ImGui::OpenPopup(title);
  if (!ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
  if (v.conflicts.empty()) {
    ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
    return;
  }
  const StudyView::Conflict& c = v.conflicts.front();
  ImGui::PushTextWrapPos(ImGui::GetFontSize() * 40);
  ImGui::TextColored({1, 0.6f, 0.2f, 1}, "%s", c.message.c_str());
  ImGui::TextUnformatted("Nothing was overwritten; this window's edit is kept in memory.");
  ImGui::Separator();
  ImGui::TextUnformatted("This window:");
  ImGui::TextWrapped("%s", c.mine.c_str());
  ImGui::TextUnformatted("On disk now:");
  ImGui::TextWrapped("%s", c.theirs.c_str());
  ImGui::PopTextWrapPos();
  if (ImGui::Button("Keep this window's")) out.keep_mine = c.key;
  ImGui::SameLine();
  if (ImGui::Button("Keep the file on disk")) out.keep_theirs = c.key;
  if (v.conflicts.size() > 1) ImGui::Text("%zu more conflict(s) after this one", v.conflicts.size() - 1);
  ImGui::EndPopup();
}
}  // namespace

void draw_dialogs(const StudyView& v, UiState& ui, UiCommands& out) {
  draw_conflict_dialog(v, out);
  if (ui.show_help) ImGui::OpenPopup("Shortcuts");
  if (ImGui::BeginPopupModal("Shortcuts", &ui.show_help, ImGuiWindowFlags_AlwaysAutoResize)) {
    if (ImGui::BeginTable("keys", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV)) {
      for (const auto& [k, what] : shortcut_list()) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextColored({1, 0.85f, 0.4f, 1}, "%s", k);
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(what);
      }
      ImGui::EndTable();
    }
    ImGui::TextDisabled("Colours: pink GT pair, grey unpaired (x<rock>), orange suspect pair, red predictions.");
    if (ImGui::Button("Close") || pressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) ui.show_help = false;
    ImGui::EndPopup();
  }
  if (ui.show_goto) ImGui::OpenPopup("Go to scene");
  if (ImGui::BeginPopupModal("Go to scene", &ui.show_goto, ImGuiWindowFlags_AlwaysAutoResize)) {
    if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
    const bool enter = ImGui::InputTextWithHint("##goto", "scene name (or part of it)", ui.goto_text,
                                                sizeof ui.goto_text, ImGuiInputTextFlags_EnterReturnsTrue);
    keep_keyboard_after_enter(enter);  // a name that matches nothing stays in the field, to be corrected
    int first = -1, shown = 0;
    if (v.session && ui.goto_text[0]) {
      const auto& scenes = v.session->scenes();
      for (int k = 0; k < static_cast<int>(scenes.size()) && shown < 12; ++k) {
        if (scenes[k].stem.find(ui.goto_text) == std::string::npos) continue;
        if (first < 0 || scenes[k].stem == ui.goto_text) first = k;
        if (ImGui::Selectable(scenes[k].stem.c_str())) out.goto_scene = k, ui.show_goto = false;
        ++shown;
      }
      if (shown == 0) ImGui::TextDisabled("no scene matches");
    }
    if (enter && first >= 0) out.goto_scene = first, ui.show_goto = false;
    if (pressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) ui.show_goto = false;
    ImGui::EndPopup();
  }
  if (ui.show_open) ImGui::OpenPopup("Open study");
  ImGui::SetNextWindowSize({640, 420}, ImGuiCond_Appearing);
  if (ImGui::BeginPopupModal("Open study", &ui.show_open)) {
    if (ImGui::IsWindowAppearing()) {
      std::snprintf(ui.open_path, sizeof ui.open_path, "%s", ui.browse_dir.c_str());
      ui.open_error.clear();
      ImGui::SetKeyboardFocusHere();
    }
    ImGui::SetNextItemWidth(-FLT_MIN);
    const bool entered =
        ImGui::InputTextWithHint("##openpath", "type or paste a study folder's path; Enter opens it", ui.open_path,
                                 sizeof ui.open_path, ImGuiInputTextFlags_EnterReturnsTrue);
    if (entered) out.open_typed_path = ui.open_path;
    keep_keyboard_after_enter(entered);  // a path that is not a study stays in the field, to be corrected
    if (!ui.open_error.empty()) {
      ImGui::PushStyleColor(ImGuiCol_Text, ImVec4{1, 0.4f, 0.3f, 1});
      text_wrapped_at_spaces(ui.open_error);
      ImGui::PopStyleColor();
    }
    ImGui::TextDisabled("or browse:");
    ImGui::SameLine();
    ImGui::TextWrapped("%s", ui.browse_dir.c_str());
    const std::string browsed = ui.browse_dir;
    if (ImGui::Button("Up")) ui.browse_dir = std::filesystem::path(ui.browse_dir).parent_path().string();
    ImGui::SameLine();
    ImGui::BeginDisabled(!ui.browse_is_study);
    if (ImGui::Button("Open this study")) out.open_study = ui.browse_dir, ui.show_open = false;
    ImGui::EndDisabled();
    if (!ui.browse_is_study) {
      ImGui::SameLine();
      ImGui::TextDisabled("(not a study: no study.yaml or <domain>/labels/)");
    }
    ImGui::BeginChild("dirs", {0, -ImGui::GetFrameHeightWithSpacing()}, true);
    for (const auto& d : ui.browse_dirs)
      if (ImGui::Selectable((d + "/").c_str(), false, ImGuiSelectableFlags_AllowDoubleClick))
        ui.browse_dir = (std::filesystem::path(ui.browse_dir) / d).string();
    ImGui::EndChild();
    if (ui.browse_dir != browsed) {  // the field follows the browser
      std::snprintf(ui.open_path, sizeof ui.open_path, "%s", ui.browse_dir.c_str());
      ui.open_error.clear();
    }
    if (ImGui::Button("Cancel") || pressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) ui.show_open = false;
    ImGui::EndPopup();
  }
  if (ui.show_quit) {
    if (!unsaved(v)) {
      out.quit = true;
      ui.show_quit = false;
    } else {
      ImGui::OpenPopup("Unsaved edits");
    }
  }
  if (ImGui::BeginPopupModal("Unsaved edits", &ui.show_quit, ImGuiWindowFlags_AlwaysAutoResize)) {
    if (v.pending_saves > 0) ImGui::Text("%d edit(s) are still being written.", v.pending_saves);
    if (!v.failed_saves.empty())
      ImGui::TextColored({1, 0.4f, 0.3f, 1}, "%zu save(s) failed: %s", v.failed_saves.size(),
                         v.failed_saves.front().c_str());
    if (v.session && v.session->read_only())
      ImGui::TextWrapped("This study is read-only: hand edits live only in memory until saved elsewhere.");
    if (!v.failed_saves.empty() && ImGui::Button("Retry saves")) out.retry_saves = true;
    ImGui::SameLine();
    if (ImGui::Button("Quit anyway")) out.quit = true, ui.show_quit = false;
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) ui.show_quit = false;
    ImGui::EndPopup();
  }
}

std::pair<int, int> selected_pair(const Session& s, const UiState& ui) {
  if (s.scenes().empty() || (ui.selected_left < 0 && ui.selected_right < 0)) return {-1, -1};
  for (const auto& p : s.view_pairs(ui.scene))
    if (ui.selected_left >= 0 ? p.first == ui.selected_left : p.second == ui.selected_right) return p;
  return {-1, -1};
}

std::string review_progress_line(const Session::ReviewProgress& p) {
  return thousands(p.reviewed) + " of " + counted(p.scenes, "scene") + " reviewed, " +
         counted(p.suspects_left, "suspect pair") + " left";
}

bool shortcuts_may_act() {
  return !ImGui::GetIO().WantTextInput &&
         !ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId | ImGuiPopupFlags_AnyPopupLevel);
}

void keep_keyboard_after_enter(bool entered) {
  if (entered) ImGui::SetKeyboardFocusHere(-1);
}

void take_keyboard_if_asked(UiState& ui, UiState::Field field) {
  if (ui.focus_field != field) return;
  ImGui::SetKeyboardFocusHere();
  ui.focus_field = UiState::Field::kNone;
}

void handle_shortcuts(const StudyView& v, UiState& ui, UiCommands& out) {
  ImGuiIO& io = ImGui::GetIO();
  if (!shortcuts_may_act()) return;
  const bool ctrl = io.KeyCtrl;
  if ((ui.help_key >= 0 && pressed(ui.help_key)) || (!ctrl && io.InputQueueCharacters.contains('?')))
    ui.show_help = true;
  if (ctrl && pressed('O')) ui.show_open = true;
  if (ctrl && pressed('Q')) ui.show_quit = true;
  if (!v.session || v.session->scenes().empty()) return;
  if (ctrl && pressed('Z')) out.undo = true;
  if (ctrl && pressed('Y')) out.redo = true;
  if (ctrl && pressed('G')) ui.show_goto = true, ui.goto_text[0] = 0;
  if (ctrl && pressed('F')) ui.focus_field = UiState::Field::kSearch;
  if (ctrl) return;
  const std::vector<int>& order = ui.order;
  const auto pos = std::find(order.begin(), order.end(), ui.scene);
  const int at = pos == order.end() ? -1 : static_cast<int>(pos - order.begin());
  if ((pressed(ImGui::GetKeyIndex(ImGuiKey_RightArrow)) || pressed('J')) && !order.empty())
    out.goto_scene = order[std::min<int>(at + 1, order.size() - 1)];
  if ((pressed(ImGui::GetKeyIndex(ImGuiKey_LeftArrow)) || pressed('K')) && !order.empty())
    out.goto_scene = order[std::max(at - 1, 0)];
  if (pressed('N')) out.next_suspect = true;
  if (pressed('R')) out.toggle_reviewed = true;
  if (pressed('C')) std::tie(out.check_left, out.check_right) = selected_pair(*v.session, ui);
  if (pressed('Z')) ui.focus = !ui.focus;
  if (pressed('B')) ui.blink.on = !ui.blink.on;
  if (pressed('V') && ui.blink.on && !ui.blink.overlay)
    ui.blink.manual_right = !ui.blink.manual_right, ui.blink.flips_per_second = 0;
  if (pressed(ImGui::GetKeyIndex(ImGuiKey_Space))) {
    ui.replay.playing = !ui.replay.playing;
  }
  if (pressed('U') && ui.selected_left >= 0) out.edits.push_back(Edit::unpair(Side::kA, ui.selected_left));
  if (pressed('U') && ui.selected_left < 0 && ui.selected_right >= 0)
    out.edits.push_back(Edit::unpair(Side::kB, ui.selected_right));
  if (pressed('X') && (ui.selected_left >= 0 || ui.selected_right >= 0))
    out.edits.push_back(Edit::toggle_exclude(ui.selected_left >= 0 ? Side::kA : Side::kB,
                                             ui.selected_left >= 0 ? ui.selected_left : ui.selected_right));
  if (pressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) ui.selected_left = ui.selected_right = -1;
}

}  // namespace ipd::ui
