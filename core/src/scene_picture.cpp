#include "ipd/scene_picture.h"

#include <algorithm>
#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

namespace ipd {

namespace {

const cv::Scalar kPink(203, 102, 255), kRed(40, 40, 230), kGrey(150, 150, 150), kWhite(255, 255, 255);

void label(cv::Mat& img, const std::string& text, cv::Point at, const cv::Scalar& colour, double scale) {
  int base = 0;
  const int thick = std::max(1, static_cast<int>(scale * 2));
  const cv::Size sz = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, thick, &base);
  at.x = std::clamp(at.x, 0, std::max(0, img.cols - sz.width));
  at.y = std::clamp(at.y, sz.height + 2, img.rows - 2);
  cv::rectangle(img, cv::Rect(at.x - 1, at.y - sz.height - 2, sz.width + 2, sz.height + base + 2), cv::Scalar(0, 0, 0),
                cv::FILLED);
  cv::putText(img, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, colour, thick, cv::LINE_AA);
}

cv::Mat draw_side(const ScenePictureSide& s, const std::vector<int>& number, int width) {
  cv::Mat base = s.picture;
  if (base.empty()) {
    const int w = s.width > 0 ? s.width : 1936, h = s.height > 0 ? s.height : 1216;
    base = cv::Mat(h, w, CV_8UC3, cv::Scalar(60, 60, 60));
  }
  cv::Mat img;
  const double k = static_cast<double>(width) / base.cols;
  cv::resize(base, img, cv::Size(width, std::max(1, static_cast<int>(base.rows * k))), 0, 0, cv::INTER_AREA);
  if (s.picture.empty()) label(img, "no picture", {img.cols / 2 - 60, img.rows / 2}, kWhite, 0.8);
  const double W = img.cols, H = img.rows, text = std::max(0.4, width / 1400.0);
  const int thick = std::max(1, width / 500);
  auto rect = [&](const Box& b) {
    return cv::Rect(cv::Point(static_cast<int>(b.x0() * W), static_cast<int>(b.y0() * H)),
                    cv::Point(static_cast<int>(b.x1() * W), static_cast<int>(b.y1() * H)));
  };
  for (const auto& p : s.predictions) {
    const cv::Rect r = rect(p);
    cv::rectangle(img, r, kRed, thick, cv::LINE_AA);
    label(img, fmt::format("{:.2f}", p.conf), {r.x, r.y + r.height + static_cast<int>(18 * text)}, kRed, text * 0.8);
  }
  for (size_t i = 0; i < s.gt.size(); ++i) {
    const cv::Rect r = rect(s.gt[i]);
    const bool paired = number[i] > 0;
    cv::rectangle(img, r, paired ? kPink : kGrey, thick, cv::LINE_AA);
    // Partners share a number; unpaired rocks show their own index, marked with "x".
    label(img, paired ? std::to_string(number[i]) : fmt::format("x{}", i + 1), {r.x, r.y - 3}, paired ? kPink : kGrey,
          text);
  }
  label(img, s.caption, {8, static_cast<int>(30 * text) + 4}, kWhite, text * 1.2);
  return img;
}

}  // namespace

cv::Mat draw_scene_pair(const ScenePictureSide& left, const ScenePictureSide& right, const RockPairs& pairs,
                        const std::string& title, int out_width) {
  const int gap = std::max(8, out_width / 200);
  const int side_w = std::max(64, (out_width - gap) / 2);
  std::vector<int> num_l(left.gt.size(), 0), num_r(right.gt.size(), 0);
  int n = 0;
  for (const auto& [i, j] : pairs) {
    if (i < 0 || j < 0 || i >= static_cast<int>(num_l.size()) || j >= static_cast<int>(num_r.size())) continue;
    num_l[i] = num_r[j] = ++n;
  }
  const cv::Mat l = draw_side(left, num_l, side_w), r = draw_side(right, num_r, side_w);
  const int title_h = std::max(36, out_width / 40);
  cv::Mat out(title_h + std::max(l.rows, r.rows), side_w * 2 + gap, CV_8UC3, cv::Scalar(255, 255, 255));
  l.copyTo(out(cv::Rect(0, title_h, l.cols, l.rows)));
  r.copyTo(out(cv::Rect(side_w + gap, title_h, r.cols, r.rows)));
  const double ts = title_h / 45.0;
  cv::putText(out, title, {gap, static_cast<int>(title_h * 0.72)}, cv::FONT_HERSHEY_SIMPLEX, ts, cv::Scalar(20, 20, 20),
              std::max(1, static_cast<int>(ts * 2)), cv::LINE_AA);
  return out;
}

}  // namespace ipd
