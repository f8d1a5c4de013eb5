#include "app/studio/picture_loader.h"

#include <algorithm>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/picture/picture_codec.h"

namespace ipd::studio {

namespace {

bool is_jpeg(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  return ext == ".jpg" || ext == ".jpeg";
}

std::vector<cv::Mat> mip_chain(const cv::Mat& bgr) {
  std::vector<cv::Mat> levels(1);
  cv::cvtColor(bgr, levels[0], cv::COLOR_BGR2RGBA);
  while (levels.back().cols > 1 || levels.back().rows > 1) {
    cv::Mat next;
    const cv::Mat& prev = levels.back();
    cv::resize(prev, next, cv::Size(std::max(1, prev.cols / 2), std::max(1, prev.rows / 2)), 0, 0, cv::INTER_AREA);
    levels.push_back(next);
  }
  return levels;
}

}  // namespace

PictureLoader::PictureLoader(int threads, int max_width) : max_width_(max_width) {
  for (int k = 0; k < threads; ++k) threads_.emplace_back([this] { run(); });
}

PictureLoader::~PictureLoader() {
  {
    std::lock_guard<std::mutex> l(mu_);
    stop_ = true;
  }
  cv_.notify_all();
  for (auto& t : threads_) t.join();
}

void PictureLoader::request(const std::string& key, const std::string& path, bool urgent, const std::string& root) {
  {
    std::lock_guard<std::mutex> l(mu_);
    queue_.erase(std::remove_if(queue_.begin(), queue_.end(), [&](const Job& q) { return q.key == key; }),
                 queue_.end());
    if (urgent)
      queue_.push_front({key, path, root, true});
    else
      queue_.push_back({key, path, root, false});
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
    Job job;
    {
      std::unique_lock<std::mutex> l(mu_);
      cv_.wait(l, [&] { return stop_ || !queue_.empty(); });
      if (stop_) return;
      job = queue_.front();
      queue_.pop_front();
      ++busy_;
    }
    auto deliver = [&](DecodedPicture d) {
      std::lock_guard<std::mutex> l(mu_);
      ready_.push_back(std::move(d));
    };
    DecodedPicture d;
    d.key = job.key;
    d.full = true;
    d.path = job.path;
    PictureBytes file;
    if (!job.path.empty()) {
      const std::filesystem::path p(job.path);
      // Read once, beneath the study (or the picture's own folder): never through a link, never waiting on a FIFO.
      file = read_study_picture_bytes(job.root.empty() ? p.parent_path().string() : job.root, job.path);
    }
    std::error_code ec;
    if (job.path.empty()) {
      d.error = "no picture for this scene (labels only)";
    } else if (!std::filesystem::exists(job.path, ec) && !std::filesystem::is_symlink(job.path, ec)) {
      d.error = "missing picture: " + job.path;
    } else if (!file.problem.empty()) {
      d.error = file.problem;  // a link out of the study, a FIFO that would block this thread for good, too many pixels
    } else {
      // JPEG decodes at 1/4 scale directly (DCT scaling); other formats are reduced after decoding.
      if (job.urgent && is_jpeg(job.path)) {
        cv::Mat small = decode_picture(file.bytes, cv::IMREAD_REDUCED_COLOR_4);
        if (!small.empty()) {
          DecodedPicture p{job.key, {}, small.cols * 4, small.rows * 4, false, {}, job.path};
          cv::cvtColor(small, small, cv::COLOR_BGR2RGBA);
          p.levels.push_back(small);
          deliver(std::move(p));
        }
      }
      cv::Mat bgr = decode_picture(file.bytes, cv::IMREAD_COLOR);
      if (bgr.empty()) {
        d.error = "cannot decode " + job.path;
      } else {
        d.width = bgr.cols;
        d.height = bgr.rows;
        if (job.urgent && !is_jpeg(job.path)) {
          cv::Mat small;
          cv::resize(bgr, small, cv::Size(bgr.cols / 4, bgr.rows / 4), 0, 0, cv::INTER_NEAREST);
          cv::cvtColor(small, small, cv::COLOR_BGR2RGBA);
          deliver(DecodedPicture{job.key, {small}, bgr.cols, bgr.rows, false, {}, job.path});
        }
        if (bgr.cols > max_width_) {
          const double k = static_cast<double>(max_width_) / bgr.cols;
          cv::resize(bgr, bgr, cv::Size(), k, k, cv::INTER_AREA);
        }
        d.levels = mip_chain(bgr);
      }
    }
    deliver(std::move(d));
    std::lock_guard<std::mutex> l(mu_);
    --busy_;
  }
}

}  // namespace ipd::studio
