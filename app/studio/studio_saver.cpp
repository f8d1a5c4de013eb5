#include "app/studio/studio_saver.h"

#include <algorithm>

namespace ipd::studio {

Saver::Saver() : thread_([this] { run(); }) {}

Saver::~Saver() {
  {
    std::lock_guard<std::mutex> l(mu_);
    stop_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

void Saver::submit(SaveJob job) {
  {
    std::lock_guard<std::mutex> l(mu_);
    // A newer version of the same file replaces a queued one.
    for (auto& q : queue_)
      if (q.path == job.path) {
        q = std::move(job);
        cv_.notify_one();
        return;
      }
    queue_.push_back(std::move(job));
  }
  cv_.notify_one();
}

void Saver::retry_failed() {
  std::vector<std::pair<SaveJob, std::string>> again;
  {
    std::lock_guard<std::mutex> l(mu_);
    again.swap(failed_);
  }
  for (auto& [job, why] : again) submit(std::move(job));
}

std::vector<std::string> Saver::failures() const {
  std::lock_guard<std::mutex> l(mu_);
  std::vector<std::string> out;
  for (const auto& [job, why] : failed_) out.push_back(why);
  return out;
}

int Saver::pending() const {
  std::lock_guard<std::mutex> l(mu_);
  return static_cast<int>(queue_.size()) + busy_;
}

void Saver::wait_idle() {
  std::unique_lock<std::mutex> l(mu_);
  idle_cv_.wait(l, [&] { return queue_.empty() && !busy_; });
}

void Saver::run() {
  while (true) {
    SaveJob job;
    {
      std::unique_lock<std::mutex> l(mu_);
      cv_.wait(l, [&] { return stop_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stopping, and everything is written
      job = std::move(queue_.front());
      queue_.pop_front();
      busy_ = 1;
    }
    std::string error;
    try {
      run_save_job(job);
    } catch (const std::exception& e) {
      error = e.what();
    }
    std::lock_guard<std::mutex> l(mu_);
    busy_ = 0;
    // The newest attempt for a file decides whether it is still failed.
    failed_.erase(std::remove_if(failed_.begin(), failed_.end(), [&](const auto& f) { return f.first.path == job.path; }),
                  failed_.end());
    if (!error.empty()) failed_.emplace_back(std::move(job), error);
    if (queue_.empty()) idle_cv_.notify_all();
  }
}

}  // namespace ipd::studio
