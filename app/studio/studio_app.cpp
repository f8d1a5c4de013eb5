#include "app/studio/studio_app.h"

#include "app/studio/recent_studies.h"
#include "app/studio/study_folder.h"

#include "app/studio/studio_gl_textures.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <thread>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "core/report/provenance.h"
#include "core/util/atomic_file.h"
#include "core/util/cache_signer.h"
#include "ui/gui/scene_change.h"

namespace fs = std::filesystem;

namespace ipd::studio {

namespace {

// The user cache when it can be used safely (usable_user_cache_root), else "" and why in *why.
std::string cache_home(std::string* why = nullptr) { return usable_user_cache_root(why); }

// Where the demo study goes without a user cache: a fresh private folder (mkdtemp), never a shared name.
std::string private_demo_folder() {
  std::string templ = (fs::temp_directory_path() / "ipd-studio-demo-XXXXXX").string();
  if (!::mkdtemp(templ.data())) return "";
  return (fs::path(templ) / "demo-study").string();
}

}  // namespace

StudioApp::StudioApp(StudioOptions o) : o_(std::move(o)), textures_(gl_textures(), o_.texture_budget_mb << 20) {
  o_.check();
  if (!o_.replay.empty()) replay_ = parse_replay(read_file(o_.replay), o_.replay);
  const bool demo = o_.study.empty();
  std::string no_cache;
  const std::string cache = cache_home(&no_cache);
  if (demo) o_.study = cache.empty() ? private_demo_folder() : (fs::path(cache) / "demo-study").string();
  if (cache.empty()) fmt::print(stderr, "warning: {}; the recent-studies list is not kept\n", no_cache);
  ui_.recent = read_recent_studies(cache);
  ui_.browse_dir = fs::absolute(o_.study).parent_path().string();
  worker_.submit(command::OpenStudy{o_.study, demo, {}});
}

void StudioApp::adopt_snapshot() {
  auto snap = worker_.snapshot();
  if (!snap || snap == snap_) return;
  const bool first = !snap_ || snap->session->study().root != snap_->session->study().root;
  const bool other_pair = first || snap->session->pair_index() != snap_->session->pair_index() ||
                          snap->session->swapped() != snap_->session->swapped();
  const bool new_rerun = snap->rerun && (!snap_ || snap->rerun != snap_->rerun);
  // The scene in view, by name: another domain pair, class or model may list the scenes differently.
  std::string shown_stem;
  if (!first && ui_.scene >= 0 && ui_.scene < static_cast<int>(snap_->session->scenes().size()))
    shown_stem = snap_->session->scenes()[ui_.scene].stem;
  snap_ = std::move(snap);
  if (snap_->edit_ms >= 0) stats_out_.add_edit(snap_->edit_ms, snap_->edit_cpu_ms);
  const Session& s = *snap_->session;
  problems_ = s.problems();
  problems_.insert(problems_.end(), picture_problems_.begin(), picture_problems_.end());
  if (first) {
    // Remember the study among the recent ones, written off the UI thread. Not an edit: a list that can't be
    // written is a warning, never an edit reported lost.
    ui_.recent = with_recent_study(ui_.recent, s.study().root);
    if (recent_write_.valid()) recent_write_.wait();
    recent_write_ = std::async(std::launch::async, [list = ui_.recent] {
      std::string why;
      const std::string cache = cache_home(&why);
      const std::string failed = save_recent_studies(cache, list, why);
      if (!failed.empty() && why.empty()) fmt::print(stderr, "warning: {}\n", failed);  // no cache: said at start
    });
    // A scripted run has no banner to read: say on stderr that its edits will not be saved, and why.
    if (s.read_only() && (!o_.replay.empty() || !o_.screenshot.empty()))
      fmt::print(stderr, "note: {}: read-only{}{}: edits stay in memory\n", s.study().root,
                 s.read_only_reason().empty() ? "" : ": ", s.read_only_reason());
  }
  if (snap_->version != order_version_ || ui_.order.empty()) {
    ui::update_browser_order(*snap_->summaries, ui_);
    order_version_ = snap_->version;
  }
  const bool scene_moved = !shown_stem.empty() && (ui_.scene >= static_cast<int>(s.scenes().size()) ||
                                                   s.scenes()[ui_.scene].stem != shown_stem);
  if (other_pair || scene_moved) {
    // Comparing one scene across domain pairs, classes or renderer settings: it stays in view where it exists.
    const int same = shown_stem.empty() ? -1 : s.scene_index(shown_stem);
    goto_scene(same >= 0 ? same : ui_.order.empty() ? 0 : ui_.order.front());
  }
  if (other_pair && !pending_scene_.empty()) {
    if (const int k = s.scene_index(pending_scene_); k >= 0) goto_scene(k), ui_.status = pending_status_;
    pending_scene_.clear();
  }
  if (snap_->jump_serial != jump_serial_) {
    jump_serial_ = snap_->jump_serial;
    if (snap_->jump_to_scene >= 0 && snap_->jump_to_scene < static_cast<int>(s.scenes().size())) {
      ui::show_scene_of_edit(ui_, snap_->jump_to_scene);
      // Said, so a jump to another scene is not a mystery.
      if (!history_verb_.empty())
        ui_.status = fmt::format("{} in {}", history_verb_, s.scenes()[snap_->jump_to_scene].stem);
    }
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

// Edits, undo and redo, review marks: each says in the status line what was sent (a refusal comes back later
// and replaces it).
void StudioApp::submit_edits(const ui::UiCommands& cmd) {
  const Session& s = *snap_->session;
  for (const auto& e : cmd.edits) {
    if (std::string same = ui::unchanged_by_edit(s, ui_.scene, e); !same.empty()) {
      ui_.status = std::move(same);  // nothing to save: the scene must not turn into a hand-edited one
      continue;
    }
    ui_.status = ui::edit_status(s, ui_.scene, e);
    worker_.submit(command::ApplyEdit{ui_.scene, e});
  }
  if (cmd.undo) {
    worker_.submit(command::Undo{});
    history_verb_ = "undid the last change";
    if (!s.can_undo()) ui_.status = "nothing to undo";
  }
  if (cmd.redo) {
    worker_.submit(command::Redo{});
    history_verb_ = "redid the change undone last";
    if (!s.can_redo()) ui_.status = "nothing to redo";
  }
  // The status line says what a toggle did: else "suspect pair 3 in scene_02" stays up after `C` checked it.
  if (cmd.toggle_reviewed && !s.scenes().empty()) {
    worker_.submit(command::ToggleReviewed{ui_.scene});
    ui_.status = fmt::format("{} {}", s.scenes()[ui_.scene].stem,
                             s.reviewed(ui_.scene) ? "no longer marked reviewed" : "marked reviewed");
  }
  if (cmd.check_left >= 0 && !s.scenes().empty()) {
    worker_.submit(command::ToggleChecked{ui_.scene, cmd.check_left, cmd.check_right});
    // Both rocks named as the panes name them (a right rock's own number is not its pair's).
    ui_.status = fmt::format(
        "pair {} ({} rock {} | {} rock {}) in {} {}", cmd.check_left + 1, s.left_domain(), cmd.check_left + 1,
        s.right_domain(), cmd.check_right + 1, s.scenes()[ui_.scene].stem,
        s.checked(ui_.scene, cmd.check_left, cmd.check_right) ? "no longer checked as correct" : "checked as correct");
  }
}

void StudioApp::goto_scene(int scene) { ui::enter_scene(ui_, scene); }

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
  if (!cmd.open_study.empty() || (!cmd.class_word.empty() && snap_)) {
    // Another class is another study's worth of numbers: the study is opened again, showing that class.
    const std::string dir = cmd.open_study.empty() ? snap_->session->study().root : cmd.open_study;
    // Another class of the same study: the scene in view stays in view (found again by name once opened).
    if (cmd.open_study.empty() && ui_.scene >= 0 && ui_.scene < static_cast<int>(snap_->session->scenes().size())) {
      pending_scene_ = snap_->session->scenes()[ui_.scene].stem;
      pending_status_.clear();
    }
    o_.study = dir;
    worker_.submit(command::OpenStudy{dir, false, cmd.class_word});
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
  submit_edits(cmd);
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
    c.options.time_budget_ms = ui::rerun_time_budget(ui_, c.options);
    worker_.submit(std::move(c));
    ui_.rerun_discarded = false;
  }
  if ((cmd.export_figures || cmd.export_dialog) && !s.scenes().empty())
    ui::open_export_dialog(export_dialog_, export_context());
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

ui::ExportViewContext StudioApp::export_context() const {
  ui::ExportViewContext ctx = ui::export_view_context(*snap_->session, ui_, stats_ui_);
  ctx.gallery_sort = rock_view_.gallery_sort;
  return ctx;
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

void StudioApp::follow_selected_partner() {
  const Session& s = *snap_->session;
  if (!ui_.sync_views || s.scenes().empty() || ui_.selected_left < 0 ||
      ui_.selected_left >= static_cast<int>(s.gt(Side::kA, ui_.scene).size())) {
    followed_.clear();
    return;
  }
  int partner = -1;
  for (const auto& [l, r] : s.view_pairs(ui_.scene))
    if (l == ui_.selected_left) partner = r;
  const std::string key =
      fmt::format("{}/{}/{}/{}/{}", s.pair_index(), s.swapped(), ui_.scene, ui_.selected_left, partner);
  if (key == followed_) return;
  followed_ = key;
  if (ui_.left_view.zoom <= 1) return;  // the whole picture is in view, the partner too
  const Box& bl = s.gt(Side::kA, ui_.scene)[ui_.selected_left];
  const ImVec2 rock{float(bl.cx), float(bl.cy)};
  ImVec2 target = ui::towards_partner(s, ui_.scene, 0)(rock);  // unpaired: where registration puts it
  if (partner >= 0 && partner < static_cast<int>(s.gt(Side::kB, ui_.scene).size())) {
    const Box& br = s.gt(Side::kB, ui_.scene)[partner];
    target = {float(br.cx), float(br.cy)};
  }
  ui_.right_view = ui::view_on_partner(ui_.left_view, rock, target);
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

bool StudioApp::loading() const { return worker_.progress().opening; }

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
      if (counted_ > 2 && ui_.blink_drawn.drawn) stats_out_.add_blink_frame(ms);
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
  // The class shown, when the study names one (as figures and ipd table say it); nothing for an unnamed class.
  if (snap_)
    if (const std::string cls = provenance_class(snap_->session->labels()); !cls.empty())
      fmt::print(stderr, "class: {}\n", cls);
  // What the Problems window lists, for scripted runs to see (as `ipd table` prints its warnings).
  for (const Problem& p : problems_) fmt::print(stderr, "warning: {}\n", p.to_string());
  // Scripted runs (--screenshot, --replay) exit 1 on a study that can't be opened: say why on stderr too.
  if (open_failed_) fmt::print(stderr, "error: could not open the study: {}\n", worker_.open_error());
  const std::vector<std::string> problems = open_failed_ ? std::vector<std::string>{} : replay_problems();
  for (const auto& p : problems) fmt::print(stderr, "error: replay {}: {}\n", o_.replay, p);
  return open_failed_ || replay_failed_ || !problems.empty() ? 1 : 0;
}

}  // namespace ipd::studio
