// Writes ipd-studio's save jobs on their own thread, in order, the newest contents of a path winning.
// A failed job is kept (not lost) until it is retried or a newer job for the same file succeeds.
#pragma once

#include <condition_variable>
#include <deque>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "core/session/session.h"

namespace ipd::studio {

class Saver {
 public:
  Saver();
  ~Saver();  // finishes every queued job first: nothing is lost on a normal exit
  void submit(SaveJob job);
  void retry_failed();  // queues every failed job again
  std::vector<std::string> failures() const;  // "path: why" of jobs that failed and were not redone
  int pending() const;
  void wait_idle();

 private:
  void run();
  mutable std::mutex mu_;
  std::condition_variable cv_, idle_cv_;
  std::deque<SaveJob> queue_;
  std::vector<std::pair<SaveJob, std::string>> failed_;
  bool stop_ = false;
  int busy_ = 0;
  std::thread thread_;
};

}  // namespace ipd::studio
