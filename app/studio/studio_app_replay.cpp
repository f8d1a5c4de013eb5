// StudioApp's replay (--replay, studio_replay.h): one scripted action per frame, the rock view's verbs,
// and what a finished replay left undone.
#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>

#include "app/studio/studio_app.h"
#include "core/util/atomic_file.h"

#include <nlohmann/json.hpp>

namespace ipd::studio {

void StudioApp::replay_rock_axes(const std::string& x, const std::string& y) {
  PairAxis ax, ay;  // both checked by parse_replay
  parse_pair_axis(x, &ax);
  parse_pair_axis(y, &ay);
  ui_.show_rock_view = true;
  rock_view_.x_axis = static_cast<int>(ax);
  rock_view_.select_tab = 0;  // the scatter, whichever tab was shown
  rock_view_.y_axis = static_cast<int>(ay);
}

void StudioApp::replay_select(double x0, double y0, double x1, double y1) {
  const Session& s = *snap_->session;
  ui::adopt_rock_points(s, rock_points_.result(), rock_view_);  // current: replay_step waited for them
  ui::select_pairs_in_box(s, rock_view_, x0, y0, x1, y1, ui_);
}

void StudioApp::replay_gallery(const std::vector<std::string>& args) {
  ui_.show_rock_view = true;
  rock_view_.select_tab = 1;
  for (size_t k = 0; k + 1 < args.size(); k += 2) {  // checked by parse_replay
    if (args[k] == "page") rock_view_.gallery_page = std::atoi(args[k + 1].c_str()) - 1;
    if (args[k] == "sort") parse_gallery_sort(args[k + 1], &rock_view_.gallery_sort);
  }
}

std::string StudioApp::write_scene_list(const std::string& file) const {
  std::string text = ui_.selection_label + "\n";
  for (const int k : ui_.order) text += snap_->session->scenes()[k].stem + "\n";
  try {
    write_file_atomically(file, text);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

void StudioApp::replay_fail(const ReplayAction& a, const std::string& why) {
  fmt::print(stderr, "error: {}:{}: {}\n", o_.replay, a.line, why);
  replay_next_ = replay_.size() + 1;
  done_ = true;
  replay_failed_ = true;
}

int StudioApp::replay_rock(const ReplayAction& a, const std::string& number, Side side) {
  const Session& s = *snap_->session;
  const int n = std::atoi(number.c_str());
  const int count = s.scenes().empty() ? 0 : static_cast<int>(s.gt(side, ui_.scene).size());
  if (n > count) {
    replay_fail(a, fmt::format("rock {} does not exist: {} has {} rocks on the {} side", n, s.scenes()[ui_.scene].stem,
                               count, side == Side::kA ? "left" : "right"));
    return -1;
  }
  return n - 1;
}

bool StudioApp::replay_view_action(const ReplayAction& a, ui::UiCommands* cmd) {
  const Session& s = *snap_->session;
  if (a.verb == "wait") {
    replay_wait_ = std::atoi(a.args[0].c_str());
  } else if (a.verb == "conf") {
    cmd->conf_threshold = std::strtod(a.args[0].c_str(), nullptr);  // as `ipd --conf` reads it: 0.3 is 0.3
  } else if (a.verb == "class") {
    try {
      s.study().classes.resolve(a.args[0]);
      cmd->class_word = a.args[0];
    } catch (const StudyError& e) {
      replay_fail(a, fmt::format("'class': {}", e.what()));
    }
  } else if (a.verb == "model") {
    // As `domains`: a name the study lacks fails the replay, rather than showing (and exporting) nothing.
    const auto& models = s.study().models;
    if (std::none_of(models.begin(), models.end(), [&](const ModelInfo& m) { return m.name == a.args[0]; }))
      replay_fail(a, fmt::format("'model': the study has no model '{}'", a.args[0]));
    else
      cmd->model = a.args[0];
  } else if (a.verb == "domains") {
    if (!s.study().domain(a.args[0]) || !s.study().domain(a.args[1]))
      replay_fail(a, fmt::format("'domains': the study has no domain '{}'",
                                 s.study().domain(a.args[0]) ? a.args[1] : a.args[0]));
    else
      cmd->left_domain = a.args[0], cmd->right_domain = a.args[1];
  } else if (a.verb == "focus") {
    ui_.focus = a.args[0] == "on";
  } else if (a.verb == "problems") {
    ui_.show_problems = true;
  } else if (a.verb == "problem") {
    const int k = std::atoi(a.args[0].c_str());
    if (k > static_cast<int>(problems_.size()))
      replay_fail(a, fmt::format("no problem {}: the study has {}", k, problems_.size()));
    else
      cmd->goto_problem = k - 1;
  } else if (a.verb == "scene") {
    const auto at = std::find(ui_.order.begin(), ui_.order.end(), ui_.scene) - ui_.order.begin();
    if (a.args[0] == "next" && !ui_.order.empty())
      cmd->goto_scene = ui_.order[std::min<long>(at + 1, ui_.order.size() - 1)];
    else if (a.args[0] == "prev" && !ui_.order.empty())
      cmd->goto_scene = ui_.order[std::max<long>(at - 1, 0)];
    else if ((cmd->goto_scene = s.scene_index(a.args[0])) < 0)
      replay_fail(a, "no scene '" + a.args[0] + "' in this domain pair");
  } else if (a.verb == "rerun") {
    const auto& methods = registration_methods();
    for (size_t k = 0; k < methods.size(); ++k)
      if (a.args[0] == methods[k].name) ui_.rerun_method = static_cast<int>(k);
    cmd->rerun_registration = true;
    ui_.show_registration_tab = true;  // the rerun is watched where its replay is
  } else {
    return false;
  }
  return true;
}

bool StudioApp::replay_edit_action(const ReplayAction& a, ui::UiCommands* cmd) {
  const Session& s = *snap_->session;
  if (a.verb == "undo") {
    cmd->undo = true;
  } else if (a.verb == "redo") {
    cmd->redo = true;
  } else if (a.verb == "pair") {
    const int l = replay_rock(a, a.args[0], Side::kA), r = l < 0 ? -1 : replay_rock(a, a.args[1], Side::kB);
    if (l >= 0 && r >= 0) cmd->edits.push_back(Edit::pair(l, r));
  } else if (a.verb == "unpair") {
    if (const int l = replay_rock(a, a.args[0], Side::kA); l >= 0) cmd->edits.push_back(Edit::unpair(Side::kA, l));
  } else if (a.verb == "exclude") {
    if (const int l = replay_rock(a, a.args[0], Side::kA); l >= 0)
      cmd->edits.push_back(Edit::toggle_exclude(Side::kA, l));
  } else if (a.verb == "automatic") {
    cmd->edits.push_back(Edit::reset());  // the "reset to automatic" button
  } else if (a.verb == "review") {
    cmd->toggle_reviewed = true;
  } else if (a.verb == "suspect") {
    cmd->next_suspect = true;
  } else if (a.verb == "check") {
    // The pair given (left, right rock numbers), or the one selected (by `suspect`, say).
    const int l = a.args.empty() ? ui::selected_pair(s, ui_).first : replay_rock(a, a.args[0], Side::kA);
    const int r = a.args.empty() ? ui::selected_pair(s, ui_).second : l < 0 ? -1 : replay_rock(a, a.args[1], Side::kB);
    const RockPairs pairs = s.scenes().empty() ? RockPairs{} : s.view_pairs(ui_.scene);
    if (l >= 0 && r >= 0 && std::find(pairs.begin(), pairs.end(), std::make_pair(l, r)) != pairs.end())
      cmd->check_left = l, cmd->check_right = r;
    else if (!replay_failed_)
      replay_fail(a, a.args.empty() ? std::string("'check': no pair is selected")
                                    : fmt::format("'check': rocks {} and {} are not a pair in {}", a.args[0], a.args[1],
                                                  s.scenes()[ui_.scene].stem));
  } else {
    return false;
  }
  return true;
}

bool StudioApp::replay_blink(const ReplayAction& a) {
  if (a.verb != "blink") return false;
  ui::BlinkState& b = ui_.blink;
  const std::string& w = a.args[0];  // checked by parse_replay
  const float value = a.args.size() == 2 ? std::strtof(a.args[1].c_str(), nullptr) : 0;
  if (w == "on" || w == "off") b.on = w == "on";
  if (w == "flip") b.on = true, b.overlay = false, b.manual_right = !b.manual_right, b.flips_per_second = 0;
  if (w == "overlay") b.on = true, b.overlay = true, b.opacity = value;
  if (w == "rate") b.on = true, b.overlay = false, b.flips_per_second = value, b.rate_started = ImGui::GetTime();
  return true;
}

bool StudioApp::replay_rank(const ReplayAction& a, ui::UiCommands* cmd) {
  if (a.verb != "rank") return false;
  ui_.show_rank = true;
  if (a.args.empty()) return true;
  // A click on the setting's row: it must be one the window lists (ranked against the left domain).
  const Session& s = *snap_->session;
  const SessionRankRequest request = ui::rank_request(s);
  const SessionRanking* r = rank_.current(snap_, request) ? rank_.result().get() : nullptr;
  const bool listed = r && r->ranking &&
                      std::any_of(r->ranking->ranked.begin(), r->ranking->ranked.end(),
                                  [&](const RankedCandidate& c) { return c.domain == a.args[0]; });
  if (!listed)
    replay_fail(a, fmt::format("'rank': '{}' is not a ranked setting against {}{}", a.args[0], s.left_domain(),
                               r && !r->ranking ? " (" + r->error + ")" : ""));
  else
    ui::choose_ranked_domain(s, a.args[0], *cmd);
  return true;
}

std::string StudioApp::write_state(const std::string& file) const {
  const Session& s = *snap_->session;
  nlohmann::json j;
  j["left"] = s.left_domain();
  j["right"] = s.right_domain();
  j["model"] = s.model();
  j["scene"] = s.scenes().empty() ? "" : s.scenes()[ui_.scene].stem;
  j["edited"] = !s.scenes().empty() && (*snap_->summaries)[ui_.scene].edited;
  j["selected_left"] = ui_.selected_left + 1;  // 1-based as the replay's rocks; 0: none
  j["focus"] = ui_.focus;
  j["registration_tab"] = ui_.registration_tab_shown;
  auto view = [](const ui::CanvasView& v) { return nlohmann::json{{"zoom", v.zoom}, {"pan", {v.pan.x, v.pan.y}}}; };
  j["left_view"] = view(ui_.left_view);
  j["right_view"] = view(ui_.right_view);
  j["status"] = ui_.status;
  const ui::BlinkDrawn& b = ui_.blink_drawn;
  j["blink"] = {{"on", ui_.blink.on},
                {"mode", ui_.blink.overlay ? "overlay" : "blink"},
                {"drawn", b.drawn},
                {"pictures", b.pictures},
                {"right_opacity", b.right_opacity},
                {"gt", {b.gt_left, b.gt_right}},
                {"predictions", {b.predictions_left, b.predictions_right}},
                {"hand_pairs", b.hand_pairs},
                {"pane", {b.pane.x, b.pane.y}}};
  if (ui_.show_rock_view) {
    const auto ax = static_cast<PairAxis>(rock_view_.x_axis), ay = static_cast<PairAxis>(rock_view_.y_axis);
    j["rock_view"] = {{"x", axis_name(ax)},
                      {"y", axis_name(ay)},
                      {"points", rock_view_.points ? rock_view_.points->points.size() : 0},
                      {"highlighted", ui::highlighted_pairs(rock_view_)}};
  }
  if (ui_.show_rank) {
    nlohmann::json rank;
    if (const SessionRanking* r = rank_.result().get(); r && r->ranking) {
      rank["ref"] = r->ranking->ref;
      for (const RankedCandidate& c : r->ranking->ranked)
        rank["ranked"].push_back(
            {{"domain", c.domain}, {"rank", c.rank}, {"ipd", c.ipd}, {"in_best_group", c.in_best_group}});
    } else if (r) {
      rank["error"] = r->error;
    }
    j["rank"] = rank;
  }
  try {
    write_file_atomically(file, j.dump(1) + "\n");
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

bool StudioApp::replay_output_action(const ReplayAction& a) {
  const Session& s = *snap_->session;
  if (a.verb == "screenshot") {
    screenshot_now_ = a.args[0];
  } else if (a.verb == "rocks") {
    replay_rock_axes(a.args[0], a.args[1]);
  } else if (a.verb == "gallery") {
    replay_gallery(a.args);
  } else if (a.verb == "select") {
    replay_select(std::strtod(a.args[0].c_str(), nullptr), std::strtod(a.args[1].c_str(), nullptr),
                  std::strtod(a.args[2].c_str(), nullptr), std::strtod(a.args[3].c_str(), nullptr));
  } else if (a.verb == "list") {
    if (const std::string e = write_scene_list(a.args[0]); !e.empty()) replay_fail(a, e);
  } else if (a.verb == "state") {
    if (const std::string e = write_state(a.args[0]); !e.empty()) replay_fail(a, e);
  } else if (a.verb == "export") {
    if (s.scenes().empty()) return true;  // no view to export
    // The dialog's request with its defaults (single column, the view's layers and zoom) for the kind.
    ui::ExportDialogState d;
    const ui::ExportViewContext ctx = export_context();
    ui::open_export_dialog(d, ctx);
    if (a.args.size() == 2) ui::set_export_kind(d, a.args[0]);  // checked by parse_replay
    export_figure(ui::export_request(d, ctx, a.args.back()));
  } else {
    return false;
  }
  return true;
}

bool StudioApp::replay_input_action(const ReplayAction& a, ui::UiCommands* cmd) {
  if (a.verb == "click") {
    if (const int l = replay_rock(a, a.args[0], Side::kA); l >= 0) ui_.selected_left = l, ui_.selected_right = -1;
  } else if (a.verb == "dialog") {
    const std::string& d = a.args[0];  // checked by parse_replay
    if (d == "open") ui_.show_open = true;
    if (d == "export") cmd->export_dialog = true;
    if (d == "goto") ui_.show_goto = true, ui_.goto_text[0] = 0;
    if (d == "help") ui_.show_help = true;
    if (d == "search") ui_.focus_field = ui::UiState::Field::kSearch;
    if (d == "saveas") ui_.focus_field = ui::UiState::Field::kSaveAs;
  } else if (a.verb == "type") {
    for (size_t k = 0; k < a.args.size(); ++k) typing_ += (k ? " " : "") + a.args[k];
  } else if (a.verb == "key") {
    typing_ += a.args[0] == "enter" ? '\n' : a.args[0] == "escape" ? '\x1b' : '\t';
  } else {
    return false;
  }
  return true;
}

bool StudioApp::release_typed_key() {
  if (typed_key_ < 0) return false;
  ImGuiIO& io = ImGui::GetIO();
  // GLFW sends the character after the key: this frame's widgets read it while the key shows as pressed.
  if (typed_char_) io.AddInputCharacter(typed_char_);
  io.KeysDown[typed_key_] = false;
  typed_key_ = -1, typed_char_ = 0;
  return true;
}

void StudioApp::press_next_typed_key() {
  const char c = typing_.front();
  typing_.erase(0, 1);
  ImGuiIO& io = ImGui::GetIO();
  // GLFW's key codes, which ImGui 1.86's GLFW backend indexes KeysDown by: a printable key is its unshifted
  // ASCII character (letters upper case); Enter, Esc and Tab come from the backend's key map.
  int key = -1;
  if (c == '\n')
    key = io.KeyMap[ImGuiKey_Enter];
  else if (c == '\x1b')
    key = io.KeyMap[ImGuiKey_Escape];
  else if (c == '\t')
    key = io.KeyMap[ImGuiKey_Tab];
  else if (std::isalpha(static_cast<unsigned char>(c)))
    key = std::toupper(static_cast<unsigned char>(c));
  else if (c && std::strchr(" ',-./0123456789;=[\\]`", c))
    key = c;
  typed_char_ = c == '\n' || c == '\x1b' || c == '\t' ? 0 : static_cast<unsigned char>(c);
  if (key < 0) {  // a shifted character (_, ?, ~ ...): its character alone
    io.AddInputCharacter(typed_char_);
    typed_char_ = 0;
    return;
  }
  io.KeysDown[key] = true;  // seen as pressed by the next frame's NewFrame
  typed_key_ = key;
}

bool StudioApp::replay_step() {
  // A key typed last frame is let go whatever else waits: held longer, it would repeat.
  if (release_typed_key()) return false;
  if (replay_wait_ > 0) return --replay_wait_, false;
  if (!snap_ || !worker_.idle() || worker_.snapshot() != snap_ || worker_.saver().pending() > 0) return false;
  if (!typing_.empty()) return press_next_typed_key(), false;
  // The Rock pairs window's pairs are of this snapshot and list before the next action acts on them.
  if (ui_.show_rock_view && !rock_points_.current(snap_, ui::rock_view_scenes(ui_, rock_view_))) return false;
  // And the Rank window's ranking is of this snapshot, so `rank SETTING` clicks a row it lists.
  if (ui_.show_rank && !rank_.current(snap_, ui::rank_request(*snap_->session))) return false;
  if (replay_next_ >= replay_.size()) {
    replay_next_ = replay_.size() + 1;  // finished
    return true;
  }
  const ReplayAction& a = replay_[replay_next_++];
  ui::UiCommands cmd;
  // parse_replay accepted only known verbs, each of exactly one group.
  if (!replay_view_action(a, &cmd) && !replay_edit_action(a, &cmd) && !replay_input_action(a, &cmd) &&
      !replay_blink(a) && !replay_rank(a, &cmd))
    replay_output_action(a);
  apply(cmd);
  return true;
}

std::vector<std::string> StudioApp::replay_problems() const {
  std::vector<std::string> out;
  if (replay_.empty() || replay_failed_) return out;
  if (replay_next_ <= replay_.size())
    out.push_back(fmt::format("stopped before line {} (the window was closed)",
                              replay_[std::min(replay_next_, replay_.size() - 1)].line));
  for (const auto& why : worker_.saver().failures()) out.push_back("edit not saved: " + why);
  for (const auto& why : worker_.command_errors()) out.push_back("failed: " + why);
  if (const int n = worker_.saver().pending(); n > 0)
    out.push_back(fmt::format("{} edit(s) still being saved when the replay ended", n));
  if (const int n = worker_.unsaved_edits(); n > 0)
    out.push_back(fmt::format(
        "{} edit(s) only in memory: the study is read-only (save them elsewhere with 'save as', below undo and redo)",
        n));
  {
    std::lock_guard<std::mutex> l(export_failures_->mu);
    out.insert(out.end(), export_failures_->messages.begin(), export_failures_->messages.end());
  }
  if (const int n = *exports_running_; n > 0)
    out.push_back(fmt::format("{} export(s) still running when the replay ended", n));
  return out;
}

}  // namespace ipd::studio
