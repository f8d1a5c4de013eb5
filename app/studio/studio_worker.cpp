#include "app/studio/studio_worker.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>

#include "core/demo/demo_study.h"
#include "core/ipd/study_cache.h"
#include "core/registration/registration_cache.h"
#include "core/study/file_sets.h"

namespace fs = std::filesystem;

namespace ipd::studio {

namespace {

// The built-in demo (in the user cache, or a fresh private folder) is written whole beside its folder and renamed in
// (StagedFolder): windows started at once each write their own and the first one renamed in stays; a folder without
// study.yaml, a demo cut short, is replaced whole.
void write_demo_again(const std::string& dir) {
  StagedFolder staged(dir);
  write_demo_study((fs::path(staged.parent()) / fs::path(staged.inside("study.yaml")).parent_path()).string());
  std::error_code ec;
  if (fs::exists(fs::path(dir) / "study.yaml", ec)) return;  // another window's demo is in: this one goes
  staged.commit();
}
// A first look opens this many scenes; studies no bigger open in one go.
constexpr size_t kFirstLookScenes = 40;

double now_ms() {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// This thread's CPU time: an edit's cost, whatever else ran on the cores meanwhile.
double thread_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

bool study_fits_first_look(const std::string& root) {
  // Counting label files of the first domain is enough to tell a small study from a big one.
  std::error_code ec;
  for (fs::directory_iterator d(root, ec); !ec && d != fs::directory_iterator(); d.increment(ec)) {
    const fs::path labels = d->path() / "labels";
    if (d->path().filename().string().rfind('.', 0) == 0 || !fs::is_directory(labels, ec)) continue;
    size_t n = 0;
    for (fs::directory_iterator f(labels, ec); !ec && f != fs::directory_iterator(); f.increment(ec))
      if (++n > kFirstLookScenes) return false;
    return true;
  }
  return true;
}
}  // namespace

StudyWorker::StudyWorker() : thread_([this] { run(); }) {}

StudyWorker::~StudyWorker() {
  {
    std::lock_guard<std::mutex> l(mu_);
    stop_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

void StudyWorker::submit(WorkerCommand c) {
  {
    std::lock_guard<std::mutex> l(mu_);
    // A newer threshold or re-run replaces a queued one: dragging the slider or paging through scenes
    // never builds a backlog.
    if (std::holds_alternative<command::SetConfThreshold>(c) || std::holds_alternative<command::RerunRegistration>(c))
      for (auto& q : queue_)
        if (q.index() == c.index()) {
          q = std::move(c);
          return;
        }
    queue_.push_back(std::move(c));
  }
  cv_.notify_one();
}

std::shared_ptr<const Snapshot> StudyWorker::snapshot() const {
  std::lock_guard<std::mutex> l(mu_);
  return snapshot_;
}

OpenProgress StudyWorker::progress() const {
  std::lock_guard<std::mutex> l(mu_);
  return progress_;
}

std::string StudyWorker::open_error() const {
  std::lock_guard<std::mutex> l(mu_);
  return open_error_;
}

std::vector<std::string> StudyWorker::command_errors() const {
  std::lock_guard<std::mutex> l(mu_);
  return command_errors_;
}

std::vector<std::string> StudyWorker::take_messages() {
  std::lock_guard<std::mutex> l(mu_);
  return std::exchange(messages_, {});
}

bool StudyWorker::idle() const {
  std::lock_guard<std::mutex> l(mu_);
  return queue_.empty() && !busy_;
}

int StudyWorker::unsaved_edits() const {
  std::lock_guard<std::mutex> l(mu_);
  return unsaved_edits_;
}

void yield_to_the_view() { setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), 4); }

void StudyWorker::run() {
  yield_to_the_view();
  while (true) {
    WorkerCommand c;
    {
      std::unique_lock<std::mutex> l(mu_);
      while (!stop_ && queue_.empty()) {
        cv_.wait_for(l, std::chrono::milliseconds(250));
        std::vector<std::shared_ptr<const Snapshot>> unused;
        for (auto it = retired_.begin(); it != retired_.end();)
          if (it->use_count() == 1)
            unused.push_back(std::move(*it)), it = retired_.erase(it);
          else
            ++it;
        l.unlock();
        unused.clear();  // destroyed outside the lock
        l.lock();
      }
      if (stop_) return;
      c = std::move(queue_.front());
      queue_.pop_front();
      busy_ = true;
    }
    try {
      execute(c);
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> l(mu_);
      if (std::holds_alternative<command::OpenStudy>(c))
        open_error_ = e.what();
      else
        messages_.push_back(std::string("error: ") + e.what()), command_errors_.push_back(e.what());
    }
    std::lock_guard<std::mutex> l(mu_);
    busy_ = false;
  }
}

// A session was just opened: the last re-run belongs to the old one, and the view gets a whole new snapshot.
void StudyWorker::publish_new_session() {
  rerun_.reset();
  rerun_stem_.clear();
  published_.reset();
  publish(true);
}

void StudyWorker::publish(bool session_changed, int jump_to_scene, int edited_scene, double edit_started_ms,
                          double edit_started_cpu_ms) {
  auto snap = std::make_shared<Snapshot>();
  if (session_changed || !published_) {
    published_ = std::make_shared<const Session>(*session_);
    const Session& s = *session_;
    const std::tuple<int, bool, std::string, double> made_for{s.pair_index(), s.swapped(), s.model(),
                                                              s.conf_threshold()};
    if (edited_scene >= 0 && published_summaries_ && made_for == summaries_made_for_ &&
        edited_scene < static_cast<int>(published_summaries_->size())) {
      auto summaries = std::make_shared<std::vector<SceneSummary>>(*published_summaries_);
      (*summaries)[edited_scene] = s.summary(edited_scene);
      published_summaries_ = std::move(summaries);
    } else {
      published_summaries_ = std::make_shared<const std::vector<SceneSummary>>(s.summaries());
      summaries_made_for_ = made_for;
    }
  }
  snap->session = published_;
  snap->summaries = published_summaries_;
  snap->version = ++version_;
  if (jump_to_scene >= 0) ++jump_serial_;
  snap->jump_to_scene = jump_to_scene;
  snap->jump_serial = jump_serial_;
  snap->rerun = rerun_;
  snap->rerun_stem = rerun_stem_;
  snap->rerun_pair = rerun_pair_;
  snap->rerun_is_automatic = rerun_automatic_;
  if (edit_started_ms >= 0) snap->edit_ms = now_ms() - edit_started_ms;
  if (edit_started_cpu_ms >= 0) snap->edit_cpu_ms = thread_cpu_ms() - edit_started_cpu_ms;
  std::lock_guard<std::mutex> l(mu_);
  if (snapshot_) retired_.push_back(std::move(snapshot_));
  snapshot_ = std::move(snap);
}

void StudyWorker::open(const command::OpenStudy& c) {
  {
    std::lock_guard<std::mutex> l(mu_);
    progress_ = OpenProgress{};
    progress_.opening = true;
    progress_.stage = "label files";
    open_error_.clear();
    unsaved_edits_ = 0;
  }
  const auto start = std::chrono::steady_clock::now();
  if (c.demo && !fs::exists(fs::path(c.dir) / "study.yaml")) {
    {
      std::lock_guard<std::mutex> l(mu_);
      progress_.stage = "generating the demo study";
    }
    write_demo_again(c.dir);
  }
  // One writer per study: the lock is held while the study is open; without it the window is read-only.
  std::string held_by;
  lock_.reset();  // (reopening the same study must not find its own lock)
  std::unique_ptr<StudyLock> lock = StudyLock::try_acquire(c.dir, &held_by);
  const std::string lock_reason = lock ? std::string()
                                  : held_by.rfind("pid ", 0) == 0 || held_by == "another program"
                                      ? "another window holds this study (" + held_by + ")"
                                      : "the study's lock can't be taken: " + held_by;
  SessionOptions o;
  o.cache_dir = registration_cache_dir(c.dir);
  o.class_word = c.class_word;
  o.progress = [&](const char* stage, int done, int total) {
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::lock_guard<std::mutex> l(mu_);
    if (progress_.stage != stage) progress_.eta_s = -1;
    progress_.stage = stage;
    progress_.done = done;
    progress_.total = total;
    progress_.elapsed_s = s;
    if (done > 0 && done < total) progress_.eta_s = s / done * (total - done);
  };
  try {
    // Content first: the first scenes on their own (a few hundred files) while the whole study loads.
    if (!study_fits_first_look(c.dir)) {
      SessionOptions first = o;
      first.first_scenes = kFirstLookScenes;
      first.progress = {};
      session_ = std::make_unique<Session>(Session::open(c.dir, first));
      if (!lock) session_->set_read_only(lock_reason);
      publish_new_session();
      std::lock_guard<std::mutex> l(mu_);
      progress_.first_look = true;
    }
    o.study_cache_path = parsed_study_cache_path(c.dir);
    auto session = std::make_unique<Session>(Session::open(c.dir, o));
    if (!lock) session->set_read_only(lock_reason);
    session_ = std::move(session);
    lock_ = std::move(lock);
  } catch (...) {
    // The study still shown (the one before, or the new one's first look) keeps a lock, or becomes
    // read-only when someone took it meanwhile.
    if (session_ && !session_->read_only()) {
      if (lock && session_->study().root == c.dir) {
        lock_ = std::move(lock);
      } else {
        lock.reset();
        lock_ = StudyLock::try_acquire(session_->study().root, &held_by);
        if (!lock_) session_->set_read_only("another window took this study's lock (" + held_by + ")");
      }
    }
    std::lock_guard<std::mutex> l(mu_);
    progress_.opening = false;
    throw;
  }
  publish_new_session();
  std::lock_guard<std::mutex> l(mu_);
  progress_.opening = false;
  progress_.first_look = false;
  progress_.cached = session_->cached_registrations();
  progress_.study_cache = session_->study_cache_stats();
}

void StudyWorker::rerun(Session& s, const command::RerunRegistration& c) {
  if (c.scene < 0 || c.scene >= static_cast<int>(s.scenes().size())) return;
  const auto& [a, b] = s.domain_pairs()[s.pair_index()];
  const std::string& stem = s.scenes()[c.scene].stem;
  RegistrationOptions o = c.automatic ? s.study().config.registration : c.options;
  o.aspect = s.study().aspect();
  o.record_trace = true;
  rerun_ = std::make_shared<const RegistrationReport>(
      register_rocks(s.labels().gt_of(a, stem).boxes, s.labels().gt_of(b, stem).boxes, o));
  rerun_stem_ = stem;
  rerun_pair_ = s.pair_index();
  rerun_automatic_ = c.automatic;
  publish(false);
}

// Overload set for std::visit.
template <class... F>
struct Visitor : F... {
  using F::operator()...;
};
template <class... F>
Visitor(F...) -> Visitor<F...>;

void StudyWorker::save_edit(SaveJob job) {
  if (session_->read_only()) {
    std::lock_guard<std::mutex> l(mu_);
    messages_.push_back(
        "read-only study: the edit is kept in memory; save it elsewhere with 'save as', below undo and redo");
    ++unsaved_edits_;
  } else {
    saver_.submit(std::move(job));
  }
}

void StudyWorker::say(std::string message) {
  std::lock_guard<std::mutex> l(mu_);
  messages_.push_back(std::move(message));
}

void StudyWorker::execute(WorkerCommand& c) {
  if (auto* o = std::get_if<command::OpenStudy>(&c)) return open(*o);
  if (!session_) return;
  Session& s = *session_;
  // Each command says whether it changed the session (and publishes itself when it did not change it).
  const double started_ms = now_ms(), started_cpu_ms = thread_cpu_ms();
  int jump = -1, edited_scene = -1;
  const bool changed =
      std::visit(Visitor{
                     [&](const command::OpenStudy&) { return false; },
                     [&](const command::ApplyEdit& e) {
                       if (e.scene >= 0 && e.scene < static_cast<int>(s.scenes().size()))
                         save_edit(s.apply(e.scene, e.edit)), edited_scene = e.scene;
                       return true;
                     },
                     [&](const command::ToggleReviewed& r) {
                       // A mark changes its scene's summary alone: the other 9,999 are shared, not redone.
                       if (r.scene >= 0 && r.scene < static_cast<int>(s.scenes().size()))
                         save_edit(s.toggle_reviewed(r.scene)), edited_scene = r.scene;
                       return true;
                     },
                     [&](const command::ToggleChecked& c) {
                       if (c.scene >= 0 && c.scene < static_cast<int>(s.scenes().size()))
                         if (auto job = s.toggle_checked(c.scene, c.left, c.right))
                           save_edit(std::move(*job)), edited_scene = c.scene;
                       return true;
                     },
                     [&](const command::Undo&) {
                       if (auto job = s.undo())
                         save_edit(std::move(*job)), jump = edited_scene = std::max(0, s.last_edited_scene());
                       return true;
                     },
                     [&](const command::Redo&) {
                       if (auto job = s.redo())
                         save_edit(std::move(*job)), jump = edited_scene = std::max(0, s.last_edited_scene());
                       return true;
                     },
                     [&](const command::SelectDomains& d) { return s.select_domains(d.left, d.right), true; },
                     [&](const command::SelectModel& m) { return s.select(s.pair_index(), m.model), true; },
                     [&](const command::SetConfThreshold& t) { return s.set_conf_threshold(t.threshold), true; },
                     [&](const command::RerunRegistration& r) { return rerun(s, r), false; },
                     [&](const command::SaveAllTo& d) {
                       for (auto& job : s.save_all_to(d.dir)) saver_.submit(std::move(job));
                       {
                         std::lock_guard<std::mutex> l(mu_);
                         unsaved_edits_ = 0;
                       }
                       say("edited pairs and review marks written under " + d.dir);
                       return false;
                     },
                     [&](const command::ReloadScene& r) { return s.reload_scene(r.pair, r.stem), true; },
                     [&](const command::RegisterScene& r) {
                       if (r.pair != s.pair_index()) return false;  // another domain pair is shown by now
                       const int scene = s.scene_index(r.stem);
                       if (!s.register_scene(r.pair, scene)) return false;
                       edited_scene = scene;  // its summary (ambiguity) alone changes
                       return true;
                     },
                     [&](const command::ExportFigure& x) {
                       say(x.job ? x.job() : std::string("export failed: nothing to export"));
                       return false;
                     },
                 },
                 c);
  const bool edit = !std::holds_alternative<command::RegisterScene>(c);
  const bool timed = edited_scene >= 0 && edit;
  if (changed) publish(true, jump, edited_scene, timed ? started_ms : -1, timed ? started_cpu_ms : -1);
}

}  // namespace ipd::studio
