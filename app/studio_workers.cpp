#include "studio_workers.h"

#include <algorithm>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace ipd::studio {

PictureLoader::PictureLoader(int max_width) : max_width_(max_width), thread_([this] { run(); }) {}

PictureLoader::~PictureLoader() {
  {
    std::lock_guard<std::mutex> l(mu_);
    stop_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

void PictureLoader::request(const std::string& key, const std::string& path, bool urgent) {
  {
    std::lock_guard<std::mutex> l(mu_);
    queue_.erase(std::remove_if(queue_.begin(), queue_.end(), [&](const auto& q) { return q.first == key; }),
                 queue_.end());
    if (urgent) queue_.emplace_front(key, path);
    else queue_.emplace_back(key, path);
  }
  cv_.notify_one();
}

std::vector<DecodedPicture> PictureLoader::take_ready() {
  std::lock_guard<std::mutex> l(mu_);
  return std::exchange(ready_, {});
}

bool PictureLoader::idle() {
  std::lock_guard<std::mutex> l(mu_);
  return queue_.empty() && !busy_ && ready_.empty();
}

void PictureLoader::run() {
  while (true) {
    std::pair<std::string, std::string> job;
    {
      std::unique_lock<std::mutex> l(mu_);
      cv_.wait(l, [&] { return stop_ || !queue_.empty(); });
      if (stop_) return;
      job = queue_.front();
      queue_.pop_front();
      busy_ = true;
    }
    DecodedPicture d;
    d.key = job.first;
    std::error_code ec;
    if (job.second.empty()) {
      d.error = "no picture for this scene (labels only)";
    } else if (!std::filesystem::exists(job.second, ec)) {
      d.error = "missing picture: " + job.second;
    } else {
      cv::Mat bgr = cv::imread(job.second, cv::IMREAD_COLOR);
      if (bgr.empty()) {
        d.error = "cannot decode " + job.second;
      } else {
        d.width = bgr.cols;
        d.height = bgr.rows;
        if (bgr.cols > max_width_) {
          const double k = static_cast<double>(max_width_) / bgr.cols;
          cv::resize(bgr, bgr, cv::Size(), k, k, cv::INTER_AREA);
        }
        cv::cvtColor(bgr, d.rgba, cv::COLOR_BGR2RGBA);
      }
    }
    std::lock_guard<std::mutex> l(mu_);
    ready_.push_back(std::move(d));
    busy_ = false;
  }
}

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

std::vector<std::string> Saver::take_errors() {
  std::lock_guard<std::mutex> l(mu_);
  return std::exchange(errors_, {});
}

int Saver::pending() {
  std::lock_guard<std::mutex> l(mu_);
  return static_cast<int>(queue_.size()) + busy_;
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
    if (!error.empty()) errors_.push_back(error);
  }
}

}  // namespace ipd::studio
