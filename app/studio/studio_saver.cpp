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
    // The disk still holds what a queued or failed job for the file expected (neither was written), so
    // that is what the newer job must find there.
    for (const auto& [old, why] : failed_)
      if (old.path == job.path && old.expected.size() == job.expected.size()) job.expected = old.expected;
    // A newer version of the same file replaces a queued one.
    for (auto& q : queue_)
      if (q.path == job.path) {
        if (q.expected.size() == job.expected.size()) job.expected = q.expected;
        q = std::move(job);
        cv_.notify_one();
        return;
      }
    queue_.push_back(std::move(job));
  }
  cv_.notify_one();
}

std::vector<Conflict> Saver::conflicts() const {
  std::lock_guard<std::mutex> l(mu_);
  return conflicts_;
}

void Saver::keep_mine(const std::string& path) {
  std::optional<SaveJob> again;
  {
    std::lock_guard<std::mutex> l(mu_);
    for (auto it = conflicts_.begin(); it != conflicts_.end(); ++it)
      if (it->job.path == path) {
        again = it->job;
        if (it->observed.size() == again->expected.size()) again->expected = it->observed;
        conflicts_.erase(it);
        break;
      }
    if (!again) return;
    failed_.erase(std::remove_if(failed_.begin(), failed_.end(), [&](const auto& f) { return f.first.path == path; }),
                  failed_.end());
  }
  submit(std::move(*again));
}

void Saver::keep_theirs(const std::string& path) {
  std::lock_guard<std::mutex> l(mu_);
  conflicts_.erase(
      std::remove_if(conflicts_.begin(), conflicts_.end(), [&](const auto& c) { return c.job.path == path; }),
      conflicts_.end());
  failed_.erase(std::remove_if(failed_.begin(), failed_.end(), [&](const auto& f) { return f.first.path == path; }),
                failed_.end());
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
    std::optional<Conflict> conflict;
    try {
      run_save_job(job);
    } catch (const SaveConflict& e) {
      error = e.what();
      conflict = Conflict{job, e.what(), e.file, e.on_disk, e.observed};
    } catch (const std::exception& e) {
      error = e.what();
    }
    std::lock_guard<std::mutex> l(mu_);
    busy_ = 0;
    // The newest attempt for a file decides whether it is still failed (or in conflict).
    failed_.erase(
        std::remove_if(failed_.begin(), failed_.end(), [&](const auto& f) { return f.first.path == job.path; }),
        failed_.end());
    conflicts_.erase(
        std::remove_if(conflicts_.begin(), conflicts_.end(), [&](const auto& c) { return c.job.path == job.path; }),
        conflicts_.end());
    if (conflict) conflicts_.push_back(std::move(*conflict));
    if (!error.empty()) failed_.emplace_back(std::move(job), error);
    if (queue_.empty()) idle_cv_.notify_all();
  }
}

}  // namespace ipd::studio
