// Writes ipd-studio's save jobs on their own thread, in order, the newest contents of a path winning.
// A failed job is kept (not lost) until it is retried or a newer job for the same file succeeds. A job
// refused because the file changed on disk (SaveConflict) is kept as a conflict for the user to decide.
#pragma once

#include <condition_variable>
#include <deque>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "core/session/session.h"

namespace ipd::studio {

// A save refused because someone else changed the file: both versions, for the conflict dialog.
struct Conflict {
  SaveJob job;                         // this window's version (job.contents; nullopt: back to automatic)
  std::string message;                 // "FILE: changed on disk since ..."
  std::string file;                    // the file that changed
  std::optional<std::string> on_disk;  // its contents now (nullopt: removed)
  std::vector<DiskVersion> observed;
};

class Saver {
 public:
  Saver();
  ~Saver();  // finishes every queued job first: nothing is lost on a normal exit
  void submit(SaveJob job);
  void retry_failed();                        // queues every failed job again
  std::vector<std::string> failures() const;  // "path: why" of jobs that failed and were not redone
  int pending() const;
  void wait_idle();
  std::vector<Conflict> conflicts() const;
  // The user keeps this window's version of `path`: written over what the conflict found (and only that).
  void keep_mine(const std::string& path);
  // The user keeps the disk's version: the conflict is dropped (the caller reloads the scene).
  void keep_theirs(const std::string& path);

 private:
  void run();
  mutable std::mutex mu_;
  std::condition_variable cv_, idle_cv_;
  std::deque<SaveJob> queue_;
  std::vector<std::pair<SaveJob, std::string>> failed_;
  std::vector<Conflict> conflicts_;
  bool stop_ = false;
  int busy_ = 0;
  std::thread thread_;
};

}  // namespace ipd::studio
