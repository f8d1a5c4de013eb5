// StudioApp's frame: the view it hands the drawing code, the opening and error screens, the study's
// columns with their pictures (and the neighbours' prefetch), then the windows over them.
#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "app/studio/studio_app.h"
#include "core/util/number_text.h"

#include <nlohmann/json.hpp>

namespace fs = std::filesystem;

namespace ipd::studio {

namespace {

// One version of a pairs or review file for the conflict dialog: what it holds, then the start of its text.
std::string describe_pairs_file(const std::optional<std::string>& text) {
  if (!text) return "no file: the automatic pairs";
  std::string what = "not a pairs file";
  try {
    const nlohmann::json j = nlohmann::json::parse(*text);
    auto count = [&](const char* key) { return j.contains(key) && j[key].is_array() ? j[key].size() : size_t{0}; };
    if (j.contains("reviewed"))  // a review file (review_state.h)
      what = fmt::format("{} reviewed scene(s), {} checked pair(s)", count("reviewed"), count("checked"));
    else
      what = fmt::format("{} pair(s), {} excluded rock(s)", count("pairs"), count("excluded_a") + count("excluded_b"));
  } catch (const std::exception&) {
  }
  constexpr size_t kShown = 400;
  return what + ": " + (text->size() > kShown ? text->substr(0, kShown) + "..." : *text);
}

// How far an open got, as the opening view's bar and the status line of a first look both say it: "62,464 of
// 120,000 label files" ("registrations" for that stage), and the time left when it is known.
std::string progress_text(const OpenProgress& p) {
  const std::string what = p.stage == "registration" ? "registrations" : p.stage;
  // The last stage's count is whole before the numbers are: no "about 1 s left" while they are computed.
  if (p.total > 0 && p.done >= p.total)
    return fmt::format("all {} {} done; computing the numbers", grouped_thousands(p.total), what);
  return fmt::format("{} of {} {}{}", grouped_thousands(p.done), grouped_thousands(p.total), what,
                     p.eta_s >= 0 ? fmt::format(", about {:.0f} s left", std::ceil(p.eta_s)) : std::string());
}

}  // namespace

ui::Picture StudioApp::picture(const std::string& domain, const std::string& stem, bool urgent, bool* full) {
  const Domain* d = snap_->session->study().domain(domain);
  const auto img = d->images.find(stem);
  const TextureRef t = textures_.get(domain + "/" + stem, img == d->images.end() ? "" : img->second, urgent, loader_,
                                     snap_->session->study().root);
  if (full) *full = t.full;
  return ui::Picture{t.id ? reinterpret_cast<ImTextureID>(t.id) : nullptr, t.width, t.height, t.placeholder};
}

void StudioApp::list_browse_dir() {
  if (listed_dir_ == ui_.browse_dir) return;
  listed_dir_ = ui_.browse_dir;
  ui_.browse_dirs.clear();
  ui_.browse_is_study = false;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(ui_.browse_dir, fs::directory_options::skip_permission_denied, ec)) {
    std::error_code e2;
    if (!e.is_directory(e2)) continue;
    const std::string name = e.path().filename().string();
    if (!name.empty() && name[0] != '.') ui_.browse_dirs.push_back(name);
    if (fs::exists(e.path() / "labels", e2)) ui_.browse_is_study = true;
  }
  if (fs::exists(fs::path(ui_.browse_dir) / "study.yaml", ec)) ui_.browse_is_study = true;
  std::sort(ui_.browse_dirs.begin(), ui_.browse_dirs.end());
}

void StudioApp::frame() {
  adopt_snapshot();
  for (auto& d : loader_.take_ready()) {
    note_picture_problem(d);
    textures_.upload(std::move(d));
  }
  for (auto& m : worker_.take_messages()) ui_.status = m;
  ui::UiCommands cmd;
  if (!replay_.empty() && replay_next_ <= replay_.size()) replay_step();
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  ui_.picture_px[0] = ui_.picture_px[1] = ImVec2{};  // set again by the panes when they are drawn
  ImGui::SetNextWindowPos(vp->WorkPos);
  ImGui::SetNextWindowSize(vp->WorkSize);
  ImGui::Begin("IPD Studio", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoBringToFrontOnFocus |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBackground | ImGuiWindowFlags_MenuBar);
  ui::StudyView v = study_view();
  const Session* s = v.session;
  ui::draw_menu_bar(v, ui_, cmd);
  // The status line and the separator above it, never clipped (the line's own height and the spacing around).
  const float status_h = ImGui::GetFrameHeightWithSpacing() + 2 * ImGui::GetStyle().ItemSpacing.y;
  const float h = ImGui::GetContentRegionAvail().y - status_h;
  if (const std::string error = worker_.open_error(); !error.empty())
    draw_open_error(error, h);
  else if (const OpenProgress p = worker_.progress(); !s || (p.opening && !p.first_look))
    draw_opening(p, h);
  else
    draw_study(v, h, cmd);
  // The status bar sits on the window's last line, whatever the panels above took.
  ImGui::SetCursorPosY(ImGui::GetWindowHeight() - ImGui::GetFrameHeightWithSpacing());
  ImGui::Separator();
  ui::draw_status_bar(v, ui_, cmd);
  if (ui_.show_open) list_browse_dir();
  ui::draw_dialogs(v, ui_, cmd);
  ui::draw_problems_window(v, ui_, cmd);
  if (s && ui_.show_rock_view) {
    rock_points_.update(snap_, ui::rock_view_scenes(ui_, rock_view_));
    ui::draw_rock_view(v, rock_points_.result(), rock_points_.computing(), rock_view_, ui_, cmd);
  }
  if (s && ui_.show_rank) {
    const SessionRankRequest request = ui::rank_request(*s);
    rank_.update(snap_, request);
    ui::draw_rank_window(v, rank_.result().get(), rank_.current(snap_, request), ui_, cmd);
  }
  if (s)
    if (auto request = ui::draw_export_dialog(export_dialog_, export_context())) export_figure(*request);
  ImGui::End();
  stats_out_.set_picture_px(ui_.picture_px[0].x, ui_.picture_px[0].y, ui_.picture_px[1].x, ui_.picture_px[1].y,
                            vp->Size.x, vp->Size.y);
  if (const ui::BlinkDrawn& b = ui_.blink_drawn; b.drawn)
    stats_out_.set_blink_line(fmt::format(
        "blink pane={:.0f}x{:.0f} pane_share={:.3f} pictures={} right_opacity={:.2f} gt={}+{} pred={}+{} hand_pairs={}",
        b.pane.x, b.pane.y, b.pane.x * b.pane.y / (vp->Size.x * vp->Size.y), b.pictures ? "yes" : "no", b.right_opacity,
        b.gt_left, b.gt_right, b.predictions_left, b.predictions_right, b.hand_pairs));
  apply(cmd);
  textures_.end_frame();
}

ui::StudyView StudioApp::study_view() {
  ui::StudyView v;
  v.picture_of = [this](const std::string& domain, const std::string& stem) {
    return picture(domain, stem, false, nullptr);
  };
  v.pending_saves = worker_.saver().pending();
  v.failed_saves = worker_.saver().failures();
  v.unsaved_edits = worker_.unsaved_edits();
  for (const Conflict& c : worker_.saver().conflicts())
    v.conflicts.push_back({c.job.path, c.message, describe_pairs_file(c.job.contents), describe_pairs_file(c.on_disk)});
  v.busy = !worker_.idle();
  if (const OpenProgress p = worker_.progress(); p.opening && p.first_look)
    v.loading = p.total > 0 ? "first scenes shown; loading the study: " + progress_text(p)
                            : "first scenes shown; loading the study...";
  const Session* s = snap_ ? snap_->session.get() : nullptr;
  if (!s) return v;
  v.session = s;
  v.summaries = snap_->summaries.get();
  v.problems = &problems_;
  stats_.update(snap_, ui::stats_request(*s, stats_ui_));
  v.stats = stats_.result().get();
  if (snap_->rerun && !s->scenes().empty() && snap_->rerun_pair == s->pair_index() &&
      snap_->rerun_stem == s->scenes()[ui_.scene].stem) {
    v.rerun = snap_->rerun.get();
    v.rerun_is_automatic = snap_->rerun_is_automatic;
  }
  return v;
}

void StudioApp::draw_open_error(const std::string& error, float h) {
  open_failed_ = true;
  ImGui::TextColored({1, 0.4f, 0.3f, 1}, "Could not open the study:");
  ImGui::TextWrapped("%s", error.c_str());
  if (ImGui::Button("Open another study...")) ui_.show_open = true;
  ImGui::Dummy({0, std::max(0.0f, h - 4 * ImGui::GetTextLineHeightWithSpacing())});
}

void StudioApp::draw_opening(const OpenProgress& p, float h) {
  ImGui::Dummy({0, h * 0.35f});
  ImGui::Text("Opening %s", o_.study.c_str());
  const float f = p.total > 0 ? float(p.done) / p.total : 0.0f;
  const std::string label = p.total > 0 ? progress_text(p) : p.stage;
  ImGui::ProgressBar(f, {std::min(600.0f, ImGui::GetContentRegionAvail().x), 0}, label.c_str());
  ImGui::Text("%s, %.1f s so far",
              p.stage == "registration" ? "registering rocks (cached results are read back)" : "reading", p.elapsed_s);
  ImGui::Dummy({0, std::max(0.0f, h * 0.65f - 3 * ImGui::GetTextLineHeightWithSpacing())});
}

void StudioApp::draw_study(ui::StudyView& v, float h, ui::UiCommands& cmd) {
  ui::handle_shortcuts(v, ui_, cmd);
  // A new filter or sort order: the list's order is recomputed once, not every frame.
  if (order_filter_ != ui_.filter || order_sort_ != ui_.sort_column || order_desc_ != ui_.sort_descending ||
      ui_.order.empty()) {
    order_filter_ = ui_.filter;
    order_sort_ = ui_.sort_column;
    order_desc_ = ui_.sort_descending;
    ui::update_browser_order(*snap_->summaries, ui_);
  }
  if (o_.cycle_scenes > 0 && counted_ > 0 && !changing_ && ++since_change_ >= o_.cycle_scenes && ui_.order.size() > 1) {
    const auto at = std::find(ui_.order.begin(), ui_.order.end(), ui_.scene) - ui_.order.begin();
    cmd.goto_scene = ui_.order[(at + o_.cycle_step) % ui_.order.size()];
    change_started_ = std::chrono::steady_clock::now();
    changing_ = true;
    goto_scene(cmd.goto_scene);
  }
  ui::Picture left, right;
  if (!v.session->scenes().empty()) scene_pictures(*v.session, &left, &right);
  follow_selected_partner();
  ui_.blink_drawn = ui::BlinkDrawn{};  // set again when the blink view is drawn
  ui::draw_main_columns(
      v, ui_, left, right, h,
      [&] {
        // A first look's statistics are of the scenes read so far: marked as being updated until the study is in.
        ui::draw_stats_panels(v, v.stats, stats_.computing() || !v.loading.empty(), stats_ui_, ui_, cmd);
      },
      cmd);
}

void StudioApp::scene_pictures(const Session& s, ui::Picture* left, ui::Picture* right) {
  bool full_l = false, full_r = false;
  const std::string& stem = s.scenes()[ui_.scene].stem;
  if (!s.scenes()[ui_.scene].registered) {
    // A hand-paired scene opened without its registration: the worker computes it now it is shown.
    const std::string wanted = fmt::format("{}/{}", s.pair_index(), stem);
    if (registering_ != wanted) worker_.submit(command::RegisterScene{s.pair_index(), stem}), registering_ = wanted;
  }
  *left = picture(s.left_domain(), stem, true, &full_l);
  *right = picture(s.right_domain(), stem, true, &full_r);
  pictures_full_ = full_l && full_r;
  const auto at = std::find(ui_.order.begin(), ui_.order.end(), ui_.scene);
  for (int step : {1, -1}) {  // prefetch the neighbours in the list's order
    if (at == ui_.order.end()) break;
    const long k = (at - ui_.order.begin()) + step;
    if (k < 0 || k >= static_cast<long>(ui_.order.size())) continue;
    picture(s.left_domain(), s.scenes()[ui_.order[k]].stem, false, nullptr);
    picture(s.right_domain(), s.scenes()[ui_.order[k]].stem, false, nullptr);
  }
  // Record the search of the scene in view, for the replay panel.
  const std::string key = std::to_string(s.pair_index()) + "/" + stem;
  // A discarded re-run had replaced the study's own search in the panel: record that one again.
  const bool rerecord =
      ui_.rerun_discarded && snap_->rerun && !snap_->rerun_is_automatic && discarded_rerun_ != snap_->rerun.get();
  if (rerecord) discarded_rerun_ = snap_->rerun.get();
  if (traced_ != key || rerecord) {
    traced_ = key;
    command::RerunRegistration c;
    c.scene = ui_.scene;
    c.automatic = true;
    worker_.submit(std::move(c));
  }
}

}  // namespace ipd::studio
