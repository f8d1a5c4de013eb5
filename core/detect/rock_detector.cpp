#include "core/detect/rock_detector.h"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "core/io/label_io.h"

namespace ipd {

std::string RockDetectorParams::validate() const {
  if (!(threshold > 0)) return fmt::format("threshold must be > 0, got {}", threshold);
  if (background_kernel < 3 || background_kernel % 2 == 0)
    return fmt::format("background_kernel must be odd and >= 3, got {}", background_kernel);
  if (min_area < 1) return fmt::format("min_area must be >= 1, got {}", min_area);
  if (close_kernel < 1) return fmt::format("close_kernel must be >= 1, got {}", close_kernel);
  return {};
}

std::vector<Box> detect_rocks(const cv::Mat& bgr, const RockDetectorParams& p, bool outlines) {
  std::vector<Box> out;
  if (bgr.empty()) return out;
  cv::Mat grey, small_bg, bg, diff, mask;
  if (bgr.channels() == 3)
    cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  else
    grey = bgr;
  cv::GaussianBlur(grey, grey, cv::Size(3, 3), 0);
  // Median background at half resolution: same result for smooth ground, a quarter of the cost.
  cv::resize(grey, small_bg, cv::Size(), 0.5, 0.5, cv::INTER_AREA);
  cv::medianBlur(small_bg, small_bg, std::max(3, (p.background_kernel / 2) | 1));
  cv::resize(small_bg, bg, grey.size(), 0, 0, cv::INTER_LINEAR);
  cv::absdiff(grey, bg, diff);
  cv::threshold(diff, mask, p.threshold, 255, cv::THRESH_BINARY);
  const cv::Mat k = cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(p.close_kernel, p.close_kernel));
  cv::morphologyEx(mask, mask, cv::MORPH_CLOSE, k);
  cv::morphologyEx(mask, mask, cv::MORPH_OPEN, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(3, 3)));
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(mask, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
  const double W = bgr.cols, H = bgr.rows;
  for (const auto& c : contours) {
    const double area = cv::contourArea(c);
    if (area < p.min_area) continue;
    const cv::Rect r = cv::boundingRect(c);
    const double mean_diff = cv::mean(diff(r), mask(r))[0];
    Box b;
    b.cls = 0;
    b.cx = (r.x + 0.5 * r.width) / W;
    b.cy = (r.y + 0.5 * r.height) / H;
    b.w = r.width / W;
    b.h = r.height / H;
    // A rough, monotone confidence: strong contrast and a solid blob score high.
    const double solidity = area / std::max(1.0, static_cast<double>(r.area()));
    b.conf = std::clamp(0.25 + 0.5 * (mean_diff - p.threshold) / 60.0 + 0.3 * solidity, 0.05, 0.99);
    if (outlines) {
      std::vector<cv::Point> simplified;
      cv::approxPolyDP(c, simplified, 1.0, true);
      std::vector<Eigen::Vector2d> points;
      for (const cv::Point& q : simplified) points.emplace_back((q.x + 0.5) / W, (q.y + 0.5) / H);
      if (!set_outline(std::move(points), &b).empty()) continue;
    }
    out.push_back(b);
  }
  std::sort(out.begin(), out.end(), [](const Box& x, const Box& y) { return x.conf > y.conf; });
  return out;
}

RockDetectorParams tune_detector(const std::vector<cv::Mat>& pictures, const std::vector<std::vector<Box>>& gt) {
  RockDetectorParams best;
  double best_score = -1;
  for (double thr : {12.0, 16.0, 20.0, 25.0, 30.0, 36.0}) {
    for (int kernel : {61, 101}) {
      for (int close : {5, 9}) {
        RockDetectorParams p;
        p.threshold = thr;
        p.background_kernel = kernel;
        p.close_kernel = close;
        double sum = 0;
        long n = 0;
        for (size_t k = 0; k < pictures.size(); ++k) {
          const auto pred = detect_rocks(pictures[k], p);
          const auto pv = performance_values(gt[k], pred);
          for (double v : pv.value) sum += v;
          n += static_cast<long>(pv.value.size());
          // False alarms cost too: a detector that fires everywhere is not a good one.
          sum -= 0.1 * std::max<long>(0, static_cast<long>(pred.size()) - static_cast<long>(gt[k].size()));
        }
        const double score = n ? sum / n : 0;
        if (score > best_score) {
          best_score = score;
          best = p;
        }
      }
    }
  }
  return best;
}

}  // namespace ipd
