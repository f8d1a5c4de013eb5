#include "app/studio/studio_app.h"

#include "app/studio/study_folder.h"

#include "app/studio/studio_gl_textures.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <thread>

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/util/atomic_file.h"
#include "ui/gui/scene_change.h"

#include <nlohmann/json.hpp>

namespace fs = std::filesystem;

namespace ipd::studio {

namespace {

// One version of a pairs file for the conflict dialog: what it pairs, then the start of its text.
std::string describe_pairs_file(const std::optional<std::string>& text) {
  if (!text) return "no file: the automatic pairs";
  std::string what = "not a pairs file";
  try {
    const nlohmann::json j = nlohmann::json::parse(*text);
    auto count = [&](const char* key) { return j.contains(key) && j[key].is_array() ? j[key].size() : size_t{0}; };
    what = fmt::format("{} pair(s), {} excluded rock(s)", count("pairs"), count("excluded_a") + count("excluded_b"));
  } catch (const std::exception&) {
  }
  constexpr size_t kShown = 400;
  return what + ": " + (text->size() > kShown ? text->substr(0, kShown) + "..." : *text);
}

fs::path cache_home() {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  const char* home = std::getenv("HOME");
  return (xdg && *xdg ? fs::path(xdg) : fs::path(home ? home : "/tmp") / ".cache") / "ipd-studio";
}

std::vector<std::string> read_recent() {
  std::vector<std::string> out;
  std::ifstream in(cache_home() / "recent.txt");
  for (std::string line; std::getline(in, line) && out.size() < 10;)
    if (!line.empty()) out.push_back(line);
  return out;
}

}  // namespace

StudioApp::StudioApp(StudioOptions o) : o_(std::move(o)), textures_(gl_textures(), o_.texture_budget_mb << 20) {
  if (!o_.replay.empty()) replay_ = parse_replay(read_file(o_.replay), o_.replay);
  const bool demo = o_.study.empty();
  if (demo) o_.study = (cache_home() / "demo-study").string();
  ui_.recent = read_recent();
  ui_.browse_dir = fs::absolute(o_.study).parent_path().string();
  worker_.submit(command::OpenStudy{o_.study, demo});
}

void StudioApp::adopt_snapshot() {
  auto snap = worker_.snapshot();
  if (!snap || snap == snap_) return;
  const bool first = !snap_ || snap->session->study().root != snap_->session->study().root;
  const bool other_pair = first || snap->session->pair_index() != snap_->session->pair_index() ||
                          snap->session->swapped() != snap_->session->swapped();
  const bool new_rerun = snap->rerun && (!snap_ || snap->rerun != snap_->rerun);
  snap_ = std::move(snap);
  if (snap_->edit_ms >= 0) stats_out_.add_edit(snap_->edit_ms);
  const Session& s = *snap_->session;
  problems_ = s.problems();
  problems_.insert(problems_.end(), picture_problems_.begin(), picture_problems_.end());
  if (first) {
    // Remember the study among the recent ones (written by the saver thread, atomically).
    auto& r = ui_.recent;
    r.erase(std::remove(r.begin(), r.end(), s.study().root), r.end());
    r.insert(r.begin(), s.study().root);
    if (r.size() > 10) r.resize(10);
    std::string text;
    for (const auto& x : r) text += x + "\n";
    SaveJob recent;  // in the user's cache, written as given (no study root to stay inside)
    recent.path = (cache_home() / "recent.txt").string();
    recent.contents = text;
    worker_.saver().submit(std::move(recent));
    // A scripted run has no banner to read: say on stderr that its edits will not be saved, and why.
    if (s.read_only() && (!o_.replay.empty() || !o_.screenshot.empty()))
      fmt::print(stderr, "note: {}: read-only{}{}: edits stay in memory\n", s.study().root,
                 s.read_only_reason().empty() ? "" : ": ", s.read_only_reason());
  }
  if (snap_->version != order_version_ || ui_.order.empty()) {
    ui::update_browser_order(*snap_->summaries, ui_);
    order_version_ = snap_->version;
  }
  if (other_pair) goto_scene(ui_.order.empty() ? 0 : ui_.order.front());
  if (other_pair && !pending_scene_.empty()) {
    if (const int k = s.scene_index(pending_scene_); k >= 0) goto_scene(k), ui_.status = pending_status_;
    pending_scene_.clear();
  }
  if (snap_->jump_serial != jump_serial_) {
    jump_serial_ = snap_->jump_serial;
    if (snap_->jump_to_scene >= 0 && snap_->jump_to_scene < static_cast<int>(s.scenes().size()))
      goto_scene(snap_->jump_to_scene);
  }
  if (new_rerun) {
    const int steps = static_cast<int>(snap_->rerun->trace.steps.size());
    ui_.replay.speed = std::clamp(steps / 6.0f, 5.0f, 2000.0f);
    // The study's own search is shown finished (press play to watch it); an explicit re-run plays.
    ui_.replay.position = snap_->rerun_is_automatic ? steps + 1.0f : 0.0f;
    ui_.replay.playing = !snap_->rerun_is_automatic;
    if (snap_->rerun_is_automatic) ui_.rerun_discarded = false;  // the study's own search is back on display
  }
}

void StudioApp::goto_scene(int scene) { ui::enter_scene(ui_, scene); }

ui::Picture StudioApp::picture(const std::string& domain, const std::string& stem, bool urgent, bool* full) {
  const Domain* d = snap_->session->study().domain(domain);
  const auto img = d->images.find(stem);
  const TextureRef t = textures_.get(domain + "/" + stem, img == d->images.end() ? "" : img->second, urgent, loader_);
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
  ImGui::SetNextWindowPos(vp->WorkPos);
  ImGui::SetNextWindowSize(vp->WorkSize);
  ImGui::Begin("IPD Studio", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoBringToFrontOnFocus |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBackground | ImGuiWindowFlags_MenuBar);
  ui::StudyView v;
  v.pending_saves = worker_.saver().pending();
  v.failed_saves = worker_.saver().failures();
  v.unsaved_edits = worker_.unsaved_edits();
  for (const Conflict& c : worker_.saver().conflicts())
    v.conflicts.push_back({c.job.path, c.message, describe_pairs_file(c.job.contents), describe_pairs_file(c.on_disk)});
  v.busy = !worker_.idle();
  if (const OpenProgress p = worker_.progress(); p.opening && p.first_look)
    v.loading = p.total > 0 ? fmt::format("first scenes shown; loading the study: {} / {} {}", p.done, p.total, p.stage)
                            : "first scenes shown; loading the study...";
  const Session* s = snap_ ? snap_->session.get() : nullptr;
  if (s) {
    v.session = s;
    v.summaries = snap_->summaries.get();
    v.problems = &problems_;
    stats_.update(snap_, ui::stats_request(*s, stats_ui_));
    v.stats = stats_.result();
    if (snap_->rerun && !s->scenes().empty() && snap_->rerun_pair == s->pair_index() &&
        snap_->rerun_stem == s->scenes()[ui_.scene].stem) {
      v.rerun = snap_->rerun.get();
      v.rerun_is_automatic = snap_->rerun_is_automatic;
    }
  }
  ui::draw_menu_bar(v, ui_, cmd);
  const float status_h = 2 * ImGui::GetFrameHeightWithSpacing();  // separator + status line, never clipped
  const float h = ImGui::GetContentRegionAvail().y - status_h;
  const std::string error = worker_.open_error();
  if (!error.empty()) {
    open_failed_ = true;
    ImGui::TextColored({1, 0.4f, 0.3f, 1}, "Could not open the study:");
    ImGui::TextWrapped("%s", error.c_str());
    if (ImGui::Button("Open another study...")) ui_.show_open = true;
    ImGui::Dummy({0, std::max(0.0f, h - 4 * ImGui::GetTextLineHeightWithSpacing())});
  } else if (const OpenProgress p = worker_.progress(); !s || (p.opening && !p.first_look)) {
    ImGui::Dummy({0, h * 0.35f});
    ImGui::Text("Opening %s", o_.study.c_str());
    const float f = p.total > 0 ? float(p.done) / p.total : 0.0f;
    const std::string label = p.total > 0 ? fmt::format("{} / {} {}", p.done, p.total, p.stage) : p.stage;
    ImGui::ProgressBar(f, {std::min(600.0f, ImGui::GetContentRegionAvail().x), 0}, label.c_str());
    ImGui::Text("%s, %.1f s%s",
                p.stage == "registration" ? "registering rocks (cached results are read back)" : "reading", p.elapsed_s,
                p.eta_s >= 0 ? fmt::format(", about {:.0f} s left", std::ceil(p.eta_s)).c_str() : "");
    ImGui::Dummy({0, std::max(0.0f, h * 0.65f - 3 * ImGui::GetTextLineHeightWithSpacing())});
  } else {
    ui::handle_shortcuts(v, ui_, cmd);
    // A new filter or sort order: the list's order is recomputed once, not every frame.
    if (order_filter_ != ui_.filter || order_sort_ != ui_.sort_column || order_desc_ != ui_.sort_descending ||
        ui_.order.empty()) {
      order_filter_ = ui_.filter;
      order_sort_ = ui_.sort_column;
      order_desc_ = ui_.sort_descending;
      ui::update_browser_order(*snap_->summaries, ui_);
    }
    if (o_.cycle_scenes > 0 && counted_ > 0 && !changing_ && ++since_change_ >= o_.cycle_scenes &&
        ui_.order.size() > 1) {
      const auto at = std::find(ui_.order.begin(), ui_.order.end(), ui_.scene) - ui_.order.begin();
      cmd.goto_scene = ui_.order[(at + o_.cycle_step) % ui_.order.size()];
      change_started_ = std::chrono::steady_clock::now();
      changing_ = true;
      goto_scene(cmd.goto_scene);
    }
    ui::Picture left, right;
    bool full_l = false, full_r = false;
    if (!s->scenes().empty() && !s->scenes()[ui_.scene].registered) {
      // A hand-paired scene opened without its registration: the worker computes it now it is shown.
      const std::string wanted = fmt::format("{}/{}", s->pair_index(), s->scenes()[ui_.scene].stem);
      if (registering_ != wanted)
        worker_.submit(command::RegisterScene{s->pair_index(), s->scenes()[ui_.scene].stem}), registering_ = wanted;
    }
    if (!s->scenes().empty()) {
      const std::string& stem = s->scenes()[ui_.scene].stem;
      left = picture(s->left_domain(), stem, true, &full_l);
      right = picture(s->right_domain(), stem, true, &full_r);
      pictures_full_ = full_l && full_r;
      const auto at = std::find(ui_.order.begin(), ui_.order.end(), ui_.scene);
      for (int step : {1, -1}) {  // prefetch the neighbours in the list's order
        if (at == ui_.order.end()) break;
        const long k = (at - ui_.order.begin()) + step;
        if (k < 0 || k >= static_cast<long>(ui_.order.size())) continue;
        picture(s->left_domain(), s->scenes()[ui_.order[k]].stem, false, nullptr);
        picture(s->right_domain(), s->scenes()[ui_.order[k]].stem, false, nullptr);
      }
      // Record the search of the scene in view, for the replay panel.
      const std::string key = std::to_string(s->pair_index()) + "/" + stem;
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
    ui::draw_main_columns(
        v, ui_, left, right, h, [&] { ui::draw_stats_panels(v, v.stats, stats_.computing(), stats_ui_, ui_, cmd); },
        cmd);
  }
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
  if (s)
    if (auto request = ui::draw_export_dialog(export_dialog_, ui::export_view_context(*s, ui_, stats_ui_)))
      export_figure(*request);
  ImGui::End();
  apply(cmd);
  textures_.end_frame();
}

void StudioApp::apply(const ui::UiCommands& cmd) {
  if (cmd.quit) done_ = true;
  if (!cmd.open_typed_path.empty()) {
    const std::string path = expand_typed_path(cmd.open_typed_path);
    ui_.open_error = open_path_problem(path);
    std::error_code ec;
    if (ui_.open_error.empty()) {
      ui::UiCommands open;
      open.open_study = path;
      ui_.show_open = false;
      return apply(open);
    }
    if (fs::is_directory(path, ec)) ui_.browse_dir = path;  // a folder, not a study: show what is in it
  }
  if (!cmd.open_study.empty()) {
    o_.study = cmd.open_study;
    worker_.submit(command::OpenStudy{cmd.open_study});
    snap_.reset();
    ui_.order.clear();
    traced_.clear();
    return;
  }
  if (cmd.retry_saves) worker_.saver().retry_failed();
  if (!cmd.keep_mine.empty()) worker_.saver().keep_mine(cmd.keep_mine);
  if (!cmd.keep_theirs.empty()) {
    for (const Conflict& c : worker_.saver().conflicts())
      if (c.job.path == cmd.keep_theirs) {
        worker_.submit(command::ReloadScene{c.job.pair, c.job.stem});
      }
    worker_.saver().keep_theirs(cmd.keep_theirs);
  }
  if (!snap_) return;
  const Session& s = *snap_->session;
  if (!cmd.left_domain.empty()) {
    worker_.submit(command::SelectDomains{cmd.left_domain, cmd.right_domain});
  }
  if (!cmd.model.empty()) {
    worker_.submit(command::SelectModel{cmd.model});
  }
  if (cmd.conf_threshold >= 0) {
    ui_.conf_threshold = cmd.conf_threshold;  // the slider shows a threshold set by a replay too
    worker_.submit(command::SetConfThreshold{cmd.conf_threshold});
  }
  if (cmd.goto_scene >= 0 && cmd.goto_scene != ui_.scene) goto_scene(cmd.goto_scene);
  if (cmd.goto_problem >= 0 && cmd.goto_problem < static_cast<int>(problems_.size()))
    goto_problem(problems_[cmd.goto_problem]);
  if (cmd.goto_pair_scene >= 0) goto_pair(cmd.goto_pair_scene, cmd.goto_pair_left, cmd.goto_pair_right);
  for (const auto& e : cmd.edits) worker_.submit(command::ApplyEdit{ui_.scene, e});
  if (cmd.undo) worker_.submit(command::Undo{});
  if (cmd.redo) worker_.submit(command::Redo{});
  if (cmd.next_suspect) next_suspect();
  if (cmd.save_as && ui_.save_as_dir[0]) {
    worker_.submit(command::SaveAllTo{ui_.save_as_dir});
  }
  if (cmd.rerun_registration && !s.scenes().empty()) {
    command::RerunRegistration c;
    c.scene = ui_.scene;
    c.options = s.study().config.registration;
    const auto& methods = registration_methods();
    c.options.method = methods[std::clamp<size_t>(ui_.rerun_method, 0, methods.size() - 1)].method;
    c.options.seed = static_cast<std::uint64_t>(std::max(0, ui_.rerun_seed));
    worker_.submit(std::move(c));
    ui_.rerun_discarded = false;
  }
  if ((cmd.export_figures || cmd.export_dialog) && !s.scenes().empty())
    ui::open_export_dialog(export_dialog_, ui::export_view_context(s, ui_, stats_ui_));
}

void StudioApp::note_picture_problem(const DecodedPicture& d) {
  if (d.error.empty() || d.path.empty()) return;  // read, or a labels-only scene (no picture expected)
  const auto slash = d.key.find('/');             // keys are "domain/stem"
  Problem p{d.path, 0, d.key.substr(0, slash), "", slash == std::string::npos ? "" : d.key.substr(slash + 1), d.error};
  for (const Problem& q : picture_problems_)
    if (q.file == p.file) return;
  picture_problems_.push_back(p);
  problems_.push_back(std::move(p));
}

void StudioApp::goto_problem(const Problem& p) {
  if (!snap_ || p.scene.empty()) return;
  const Session& s = *snap_->session;
  const auto& pairs = s.domain_pairs();
  auto has = [&](size_t k) {
    const auto& [a, b] = pairs[k];
    const bool domains = p.domain.empty() || a == p.domain || b == p.domain;
    const bool other = p.other_domain.empty() || a == p.other_domain || b == p.other_domain;
    return domains && other;
  };
  // The domain pair in view when it holds the scene; else the first one that does.
  if (has(static_cast<size_t>(s.pair_index())) && s.scene_index(p.scene) >= 0) {
    goto_scene(s.scene_index(p.scene));
    ui_.status = p.to_string();  // after the scene change, which clears the status line
    return;
  }
  for (size_t k = 0; k < pairs.size(); ++k) {
    if (!has(k)) continue;
    const Domain* a = s.study().domain(pairs[k].first);
    const Domain* b = s.study().domain(pairs[k].second);
    if (!std::binary_search(a->stems.begin(), a->stems.end(), p.scene) ||
        !std::binary_search(b->stems.begin(), b->stems.end(), p.scene))
      continue;
    pending_scene_ = p.scene;
    pending_status_ = p.to_string();
    worker_.submit(command::SelectDomains{pairs[k].first, pairs[k].second});
    return;
  }
  ui_.status = "scene " + p.scene + " is in no domain pair (it has no counterpart)";
}

void StudioApp::export_figure(const ui::ExportRequest& request) {
  command::ExportFigure c;
  ++*exports_running_;
  c.job = [session = snap_->session, request, running = exports_running_, failures = export_failures_] {
    // Rendering takes a second of CPU: a low-priority thread, so the window's frames keep theirs.
    std::string message;
    std::thread low([&] {
      setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), 15);
      message = ui::export_figure(*session, request);
    });
    low.join();
    if (message.rfind("exported ", 0) != 0) {  // a scripted run must hear of it, not only the status line
      std::lock_guard<std::mutex> l(failures->mu);
      failures->messages.push_back(request.path + ": " + message);
    }
    --*running;
    return message;
  };
  ui_.status = "exporting " + request.path + " ...";
  worker_.submit(std::move(c));
}

void StudioApp::goto_pair(int scene, int left, int right) {
  const Session& s = *snap_->session;
  if (scene < 0 || scene >= static_cast<int>(s.scenes().size())) return;
  if (scene != ui_.scene) goto_scene(scene);
  ui_.selected_left = left;
  const Box& bl = s.gt(Side::kA, scene)[left];
  const Box& br = s.gt(Side::kB, scene)[right];
  ui_.left_view = {std::max(ui_.left_view.zoom, 3.0f), {float(bl.cx - 0.5), float(bl.cy - 0.5)}};
  ui_.right_view = {ui_.left_view.zoom, {float(br.cx - 0.5), float(br.cy - 0.5)}};
  ui_.status = fmt::format("pair {} | {} in {}", left + 1, right + 1, s.scenes()[scene].stem);
}

void StudioApp::replay_rock_axes(const std::string& x, const std::string& y) {
  PairAxis ax, ay;  // both checked by parse_replay
  parse_pair_axis(x, &ax);
  parse_pair_axis(y, &ay);
  ui_.show_rock_view = true;
  rock_view_.select_tab = 0;  // the scatter, whichever tab was shown
  rock_view_.x_axis = static_cast<int>(ax);
  rock_view_.y_axis = static_cast<int>(ay);
}

void StudioApp::replay_select(double x0, double y0, double x1, double y1) {
  const Session& s = *snap_->session;
  ui::adopt_rock_points(s, rock_points_.result(), rock_view_);  // current: replay_step waited for them
  static const std::vector<RockPairPoint> kNone;
  const auto& points = rock_view_.points ? rock_view_.points->points : kNone;
  const auto ax = static_cast<PairAxis>(rock_view_.x_axis), ay = static_cast<PairAxis>(rock_view_.y_axis);
  rock_view_.has_box = true;
  rock_view_.box_x = rock_view_.x_axis, rock_view_.box_y = rock_view_.y_axis;
  rock_view_.bx0 = x0, rock_view_.by0 = y0, rock_view_.bx1 = x1, rock_view_.by1 = y1;
  ui::apply_pair_selection(s, select_in_box(points, ax, ay, x0, y0, x1, y1), ui_);
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

void StudioApp::next_suspect() {
  const Session& s = *snap_->session;
  if (ui_.order.empty()) return;
  // Suspect pairs of a scene in the view's (left, right) orientation, by left rock.
  auto suspects = [&](int scene) {
    std::vector<std::pair<int, int>> out;
    for (const auto& p : s.audit(scene).pairs)
      if (p.suspect) out.emplace_back(s.swapped() ? p.b : p.a, s.swapped() ? p.a : p.b);
    std::sort(out.begin(), out.end());
    return out;
  };
  auto select = [&](int scene, std::pair<int, int> pair) {
    if (scene != ui_.scene) goto_scene(scene);
    ui_.selected_left = pair.first;
    const Box& bl = s.gt(Side::kA, scene)[pair.first];
    const Box& br = s.gt(Side::kB, scene)[pair.second];
    ui_.left_view = {std::max(ui_.left_view.zoom, 2.5f), {float(bl.cx - 0.5), float(bl.cy - 0.5)}};
    ui_.right_view = {ui_.left_view.zoom, {float(br.cx - 0.5), float(br.cy - 0.5)}};
    ui_.status = fmt::format("suspect pair {} in {}", pair.first + 1, s.scenes()[scene].stem);
  };
  for (const auto& p : suspects(ui_.scene))
    if (p.first > ui_.selected_left) return select(ui_.scene, p);
  const long at = std::find(ui_.order.begin(), ui_.order.end(), ui_.scene) - ui_.order.begin();
  for (size_t k = 1; k <= ui_.order.size(); ++k) {
    const int scene = ui_.order[(at + k) % ui_.order.size()];
    if ((*snap_->summaries)[scene].suspects == 0) continue;
    const auto list = suspects(scene);
    if (!list.empty()) return select(scene, list.front());
  }
  ui_.status = "no suspect pair in the listed scenes";
}

bool StudioApp::replay_step() {
  if (replay_wait_ > 0) return --replay_wait_, false;
  if (!snap_ || !worker_.idle() || worker_.snapshot() != snap_ || worker_.saver().pending() > 0) return false;
  // The Rock pairs window's pairs are of this snapshot and list before the next action acts on them.
  if (ui_.show_rock_view && !rock_points_.current(snap_, ui::rock_view_scenes(ui_, rock_view_))) return false;
  if (replay_next_ >= replay_.size()) {
    replay_next_ = replay_.size() + 1;  // finished
    return true;
  }
  const ReplayAction& a = replay_[replay_next_++];
  const Session& s = *snap_->session;
  ui::UiCommands cmd;
  auto fail = [&](const std::string& why) {
    fmt::print(stderr, "error: {}:{}: {}\n", o_.replay, a.line, why);
    replay_next_ = replay_.size() + 1;
    done_ = true;
    replay_failed_ = true;
  };
  auto rock = [&](const std::string& w, Side side) {
    const int n = std::atoi(w.c_str());
    const int count = s.scenes().empty() ? 0 : static_cast<int>(s.gt(side, ui_.scene).size());
    if (n > count) {
      fail(fmt::format("rock {} does not exist: {} has {} rocks on the {} side", n, s.scenes()[ui_.scene].stem, count,
                       side == Side::kA ? "left" : "right"));
      return -1;
    }
    return n - 1;
  };
  if (a.verb == "wait")
    replay_wait_ = std::atoi(a.args[0].c_str());
  else if (a.verb == "conf")
    cmd.conf_threshold = std::strtof(a.args[0].c_str(), nullptr);
  else if (a.verb == "model")
    cmd.model = a.args[0];
  else if (a.verb == "domains" && (!s.study().domain(a.args[0]) || !s.study().domain(a.args[1])))
    fail(fmt::format("'domains': the study has no domain '{}'", s.study().domain(a.args[0]) ? a.args[1] : a.args[0]));
  else if (a.verb == "domains")
    cmd.left_domain = a.args[0], cmd.right_domain = a.args[1];
  else if (a.verb == "focus")
    ui_.focus = a.args[0] == "on";
  else if (a.verb == "undo")
    cmd.undo = true;
  else if (a.verb == "redo")
    cmd.redo = true;
  else if (a.verb == "screenshot")
    screenshot_now_ = a.args[0];
  else if (a.verb == "problems")
    ui_.show_problems = true;
  else if (a.verb == "problem") {
    const int k = std::atoi(a.args[0].c_str());
    if (k > static_cast<int>(problems_.size()))
      fail(fmt::format("no problem {}: the study has {}", k, problems_.size()));
    else
      cmd.goto_problem = k - 1;
  } else if (a.verb == "scene") {
    const auto at = std::find(ui_.order.begin(), ui_.order.end(), ui_.scene) - ui_.order.begin();
    if (a.args[0] == "next" && !ui_.order.empty())
      cmd.goto_scene = ui_.order[std::min<long>(at + 1, ui_.order.size() - 1)];
    else if (a.args[0] == "prev" && !ui_.order.empty())
      cmd.goto_scene = ui_.order[std::max<long>(at - 1, 0)];
    else if ((cmd.goto_scene = s.scene_index(a.args[0])) < 0)
      fail("no scene '" + a.args[0] + "' in this domain pair");
  } else if (a.verb == "pair") {
    const int l = rock(a.args[0], Side::kA), r = l < 0 ? -1 : rock(a.args[1], Side::kB);
    if (l >= 0 && r >= 0) cmd.edits.push_back(Edit::pair(l, r));
  } else if (a.verb == "unpair") {
    if (const int l = rock(a.args[0], Side::kA); l >= 0) cmd.edits.push_back(Edit::unpair(Side::kA, l));
  } else if (a.verb == "exclude") {
    if (const int l = rock(a.args[0], Side::kA); l >= 0) cmd.edits.push_back(Edit::toggle_exclude(Side::kA, l));
  } else if (a.verb == "rerun") {
    const auto& methods = registration_methods();
    for (size_t k = 0; k < methods.size(); ++k)
      if (a.args[0] == methods[k].name) ui_.rerun_method = static_cast<int>(k);
    cmd.rerun_registration = true;
  } else if (a.verb == "rocks") {
    replay_rock_axes(a.args[0], a.args[1]);
  } else if (a.verb == "gallery") {
    replay_gallery(a.args);
  } else if (a.verb == "select") {
    replay_select(std::strtod(a.args[0].c_str(), nullptr), std::strtod(a.args[1].c_str(), nullptr),
                  std::strtod(a.args[2].c_str(), nullptr), std::strtod(a.args[3].c_str(), nullptr));
  } else if (a.verb == "list") {
    if (const std::string e = write_scene_list(a.args[0]); !e.empty()) fail(e);
  } else if (a.verb == "export" && !s.scenes().empty()) {
    // The dialog's request with its defaults (single column, the view's layers and zoom) for the kind.
    ui::ExportDialogState d;
    const ui::ExportViewContext ctx = ui::export_view_context(s, ui_, stats_ui_);
    ui::open_export_dialog(d, ctx);
    if (a.args.size() == 2) ui::set_export_kind(d, a.args[0]);  // checked by parse_replay
    export_figure(ui::export_request(d, ctx, a.args.back()));
  }
  apply(cmd);
  return true;
}

std::string StudioApp::after_render(double ms, double ui_cpu_ms) {
  if (snap_) stats_out_.content_shown();
  const bool loaded = snap_ != nullptr && !worker_.progress().opening;
  if (loaded) stats_out_.study_loaded();
  // Frames count once the whole study is in (a first look is drawn while the worker still loads).
  const bool ready = loaded || open_failed_;
  if (changing_ && pictures_full_) {
    stats_out_.add_scene_change(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - change_started_).count());
    changing_ = false;
    since_change_ = 0;
  }
  if (*exports_running_ > 0) stats_out_.add_export_frame(ms, ui_cpu_ms);
  if (ready && (!o_.screenshot.empty() || !replay_.empty())) {
    // Count frames once the study is open and the current pictures are in (or after a grace period).
    if (loader_.idle() || ++settle_ > 600) {
      if (counted_ > 2) stats_out_.add_frame(ms, ui_cpu_ms);  // the first frames upload textures
      ++counted_;
    }
    // A study that can't be opened ends the replay: its actions have nothing to act on.
    const bool replay_done = replay_.empty() || replay_next_ > replay_.size() || open_failed_;
    if (replay_done && counted_ >= o_.frames && (o_.cycle_scenes == 0 || !changing_)) {
      worker_.saver().wait_idle();
      done_ = true;
      if (!o_.screenshot.empty()) return o_.screenshot;
    }
  }
  return std::exchange(screenshot_now_, {});
}

int StudioApp::print_stats() const {
  const OpenProgress p = worker_.progress();
  stats_out_.print(o_.frame_stats,
                   fmt::format("{} of {} registrations from the cache; parsed-study cache {}: {} label files reused, "
                               "{} parsed",
                               p.cached, snap_ ? snap_->summaries->size() * snap_->session->domain_pairs().size() : 0,
                               p.study_cache.state, p.study_cache.files_reused, p.study_cache.files_parsed));
  if (!o_.screenshot.empty()) fmt::print("{}\n", o_.screenshot);
  // What the Problems window lists, for scripted runs to see (as `ipd table` prints its warnings).
  for (const Problem& p : problems_) fmt::print(stderr, "warning: {}\n", p.to_string());
  // Scripted runs (--screenshot, --replay) exit 1 on a study that can't be opened: say why on stderr too.
  if (open_failed_) fmt::print(stderr, "error: could not open the study: {}\n", worker_.open_error());
  const std::vector<std::string> problems = open_failed_ ? std::vector<std::string>{} : replay_problems();
  for (const auto& p : problems) fmt::print(stderr, "error: replay {}: {}\n", o_.replay, p);
  return open_failed_ || replay_failed_ || !problems.empty() ? 1 : 0;
}

std::vector<std::string> StudioApp::replay_problems() const {
  std::vector<std::string> out;
  if (replay_.empty() || replay_failed_) return out;
  if (replay_next_ <= replay_.size())
    out.push_back(fmt::format("stopped before line {} (the window was closed)",
                              replay_[std::min(replay_next_, replay_.size() - 1)].line));
  for (const auto& why : worker_.saver().failures()) out.push_back("edit not saved: " + why);
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
