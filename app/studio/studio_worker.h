// The worker of ipd-studio (Tracy's worker/view split): it owns the study data and does every heavy job
// (opening with progress, threshold/model/domain changes, edits, registration re-runs, exports); the view
// reads an immutable Snapshot that is swapped in whole after every change, so no frame waits on it.
#pragma once

#include <atomic>
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <tuple>
#include <variant>
#include <vector>

#include "app/studio/studio_saver.h"
#include "core/session/session.h"
#include "core/session/study_lock.h"

namespace ipd::studio {

// Everything the view may read; never modified after it is published.
struct Snapshot {
  std::shared_ptr<const Session> session;
  // Per scene of the current domain pair: after an edit only the edited scene's entry is computed again.
  std::shared_ptr<const std::vector<SceneSummary>> summaries;
  long version = 0;
  // Set by undo/redo: the scene the view should show (with jump_serial changing each time).
  int jump_to_scene = -1;
  long jump_serial = 0;
  // A registration re-run with its trace (the replay panel), for the scene `rerun_stem` of domain pair
  // `rerun_pair`; null when none.
  std::shared_ptr<const RegistrationReport> rerun;
  std::string rerun_stem;
  int rerun_pair = -1;
  bool rerun_is_automatic = false;  // recorded with the study's own options (the replay of what was done)
  // Made by an edit, undo or redo: the worker's time from taking the command to publishing this snapshot
  // (ipd-studio --frame-stats prints it as edit_ms); -1 for other snapshots. edit_cpu_ms: the worker thread's
  // own CPU time in it, the edit's cost apart from threads (the rasteriser's, say) that took the cores meanwhile.
  double edit_ms = -1, edit_cpu_ms = -1;
};

struct OpenProgress {
  bool opening = false;
  std::string stage;  // "labels", "registration"
  int done = 0, total = 0;
  double elapsed_s = 0, eta_s = -1;  // time left, -1 when unknown
  int cached = 0;                    // registrations read from the cache
  // The snapshot published so far shows the study's first scenes (a first look) while the rest loads.
  bool first_look = false;
  StudyCacheStats study_cache;  // of the last open
};

// What the view asks of the worker: one type per command, holding exactly what that command needs.
namespace command {
struct OpenStudy {
  std::string dir;
  bool demo = false;       // write the built-in demo study into `dir` first when it has none
  std::string class_word;  // the class to show (SessionOptions::class_word); empty: the study's
};
struct ApplyEdit {
  int scene = -1;
  Edit edit = Edit::reset();
};
// Review marks (review_state.h), undone like edits: a scene's "reviewed", a pair's "checked, correct".
struct ToggleReviewed {
  int scene = -1;
};
struct ToggleChecked {
  int scene = -1, left = -1, right = -1;  // a current pair, in view orientation
};
struct Undo {};
struct Redo {};
struct SelectDomains {
  std::string left, right;
};
struct SelectModel {
  std::string model;
};
struct SetConfThreshold {
  double threshold = 0;
};
// Registers one scene again with its trace (the replay panel).
struct RerunRegistration {
  int scene = -1;
  RegistrationOptions options;  // ignored when `automatic`
  bool automatic = false;       // the study's own registration, recorded for the replay of what was done
};
struct SaveAllTo {
  std::string dir;
};
// A hand-paired scene opened without its registration is shown: register it (Session::register_scene).
struct RegisterScene {
  int pair = -1;  // index into Session::domain_pairs()
  std::string stem;
};
// After a save conflict the user keeps the file on disk: the scene's pairs are read again.
struct ReloadScene {
  int pair = -1;  // index into Session::domain_pairs()
  std::string stem;
};
// Renders and writes a figure in-process (ui::export_figure on an immutable snapshot's session) and returns
// the status line.
struct ExportFigure {
  std::function<std::string()> job;
};
}  // namespace command

using WorkerCommand =
    std::variant<command::OpenStudy, command::ApplyEdit, command::ToggleReviewed, command::ToggleChecked, command::Undo,
                 command::Redo, command::SelectDomains, command::SelectModel, command::SetConfThreshold,
                 command::RerunRegistration, command::SaveAllTo, command::ReloadScene, command::ExportFigure,
                 command::RegisterScene>;

// Lowers the calling thread's CPU priority a little (threads it starts inherit it): heavy jobs yield to the
// window's frames, and to the rasteriser's threads, on a machine with few cores.
void yield_to_the_view();

class StudyWorker {
 public:
  StudyWorker();
  ~StudyWorker();  // finishes queued saves
  void submit(WorkerCommand c);
  std::shared_ptr<const Snapshot> snapshot() const;  // null until a study is open
  OpenProgress progress() const;
  std::string open_error() const;
  std::vector<std::string> take_messages();  // status lines (export finished, save failed, …)
  // Every command that failed (its exception's text), kept for the whole run: a replay that ends with one failed.
  std::vector<std::string> command_errors() const;
  bool idle() const;  // nothing queued or running
  // Edits of a read-only study kept only in memory since it was opened or last saved elsewhere.
  int unsaved_edits() const;
  Saver& saver() { return saver_; }
  const Saver& saver() const { return saver_; }

 private:
  void run();
  void execute(WorkerCommand& c);
  void open(const command::OpenStudy& c);
  void rerun(Session& s, const command::RerunRegistration& c);
  // An edit's save job to the saver; in a read-only study the edit stays in memory, counted and said.
  void save_edit(SaveJob job);
  void say(std::string message);  // a message for the window's status line
  // `edited_scene` >= 0: only that scene of the current domain pair changed (its summary alone is redone).
  // edit_started_ms / edit_started_cpu_ms: when the edit was taken, on the wall clock and the thread's CPU clock.
  void publish(bool session_changed, int jump_to_scene = -1, int edited_scene = -1, double edit_started_ms = -1,
               double edit_started_cpu_ms = -1);
  void publish_new_session();

  mutable std::mutex mu_;
  std::condition_variable cv_;
  std::deque<WorkerCommand> queue_;
  bool stop_ = false, busy_ = false;
  std::shared_ptr<const Snapshot> snapshot_;
  // Snapshots the view may still hold: freed here, on the worker, once the view lets go (freeing a
  // 10,000-scene session takes longer than a frame).
  std::vector<std::shared_ptr<const Snapshot>> retired_;
  OpenProgress progress_;
  std::string open_error_;
  std::vector<std::string> messages_;
  std::vector<std::string> command_errors_;
  int unsaved_edits_ = 0;
  // Worker-thread only:
  std::unique_ptr<Session> session_;
  std::shared_ptr<const RegistrationReport> rerun_;
  std::string rerun_stem_;
  int rerun_pair_ = -1;
  bool rerun_automatic_ = false;
  std::shared_ptr<const Session> published_;  // reused when a command did not change the session
  std::shared_ptr<const std::vector<SceneSummary>> published_summaries_;
  // What the published summaries were made for: another domain pair, order, model or threshold makes new ones.
  std::tuple<int, bool, std::string, double> summaries_made_for_{-1, false, {}, 0};
  long version_ = 0, jump_serial_ = 0;
  Saver saver_;
  std::unique_ptr<StudyLock> lock_;  // the open study's one-writer lock; null when read-only
  std::thread thread_;
};

}  // namespace ipd::studio
