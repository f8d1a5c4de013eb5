#include "core/detect/yolo.h"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <opencv2/dnn.hpp>
#include <opencv2/imgproc.hpp>

namespace ipd {

std::string YoloOptions::validate() const {
  if (imgsz < 32 || imgsz % 32 != 0) return fmt::format("imgsz must be a multiple of 32, got {}", imgsz);
  if (!(conf >= 0 && conf <= 1)) return fmt::format("conf must be in [0, 1], got {}", conf);
  if (!(iou >= 0 && iou <= 1)) return fmt::format("iou must be in [0, 1], got {}", iou);
  if (max_det < 1) return fmt::format("max_det must be at least 1, got {}", max_det);
  for (const int c : classes)  // a negative class matches no detection: every picture would read "no rocks"
    if (c < 0) return fmt::format("classes must be class numbers >= 0, got {}", c);
  return {};
}

Letterbox letterbox_for(int w, int h, int imgsz) {
  // As utils/augmentations.py letterbox(auto=False, scaleup=True): one scale, the rest split evenly.
  Letterbox lb;
  lb.scale = std::min(static_cast<double>(imgsz) / h, static_cast<double>(imgsz) / w);
  lb.width = static_cast<int>(std::lround(w * lb.scale));
  lb.height = static_cast<int>(std::lround(h * lb.scale));
  const double dw = (imgsz - lb.width) / 2.0, dh = (imgsz - lb.height) / 2.0;
  lb.left = static_cast<int>(std::lround(dw - 0.1));
  lb.top = static_cast<int>(std::lround(dh - 0.1));
  return lb;
}

cv::Mat apply_letterbox(const cv::Mat& bgr, const Letterbox& lb, int imgsz) {
  cv::Mat resized;
  if (bgr.cols != lb.width || bgr.rows != lb.height)
    cv::resize(bgr, resized, cv::Size(lb.width, lb.height), 0, 0, cv::INTER_LINEAR);
  else
    resized = bgr;
  cv::Mat out(imgsz, imgsz, CV_8UC3, cv::Scalar(114, 114, 114));
  resized.copyTo(out(cv::Rect(lb.left, lb.top, lb.width, lb.height)));
  return out;
}

std::vector<Box> decode_yolo(const cv::Mat& rows, YoloHead head, const Letterbox& lb, int image_w, int image_h,
                             const YoloOptions& o) {
  struct Candidate {
    double x0, y0, x1, y1, conf;
    int cls;
  };
  std::vector<Candidate> c;
  const int first_class = head == YoloHead::kV5 ? 5 : 4;
  const int nc = rows.cols - first_class;
  for (int r = 0; r < rows.rows; ++r) {
    const float* p = rows.ptr<float>(r);
    const double obj = head == YoloHead::kV5 ? p[4] : 1.0;
    if (head == YoloHead::kV5 && !(obj > o.conf)) continue;  // detect.py filters objectness first
    int best = 0;
    for (int k = 1; k < nc; ++k)
      if (p[first_class + k] > p[first_class + best]) best = k;
    const double conf = obj * p[first_class + best];
    if (!(conf > o.conf) || !std::isfinite(conf)) continue;
    if (!o.classes.empty() && std::find(o.classes.begin(), o.classes.end(), best) == o.classes.end()) continue;
    c.push_back({p[0] - p[2] / 2.0, p[1] - p[3] / 2.0, p[0] + p[2] / 2.0, p[1] + p[3] / 2.0, conf, best});
  }
  // Class-aware NMS (torchvision nms on boxes offset by class, as detect.py does), best first.
  std::vector<int> order(c.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) { return c[x].conf > c[y].conf; });
  auto iou = [&](const Candidate& a, const Candidate& b) {
    const double iw = std::min(a.x1, b.x1) - std::max(a.x0, b.x0), ih = std::min(a.y1, b.y1) - std::max(a.y0, b.y0);
    if (iw <= 0 || ih <= 0) return 0.0;
    const double inter = iw * ih;
    return inter / ((a.x1 - a.x0) * (a.y1 - a.y0) + (b.x1 - b.x0) * (b.y1 - b.y0) - inter);
  };
  std::vector<int> kept;
  for (int i : order) {
    bool keep = true;
    for (int k : kept)
      if (c[k].cls == c[i].cls && iou(c[k], c[i]) > o.iou) {
        keep = false;
        break;
      }
    if (keep) kept.push_back(i);
    if (static_cast<int>(kept.size()) >= o.max_det) break;
  }
  std::vector<Box> out;
  for (int i : kept) {
    // Back through the letterbox, clipped to the picture (scale_coords).
    auto ux = [&](double x) { return std::clamp((x - lb.left) / lb.scale, 0.0, static_cast<double>(image_w)); };
    auto uy = [&](double y) { return std::clamp((y - lb.top) / lb.scale, 0.0, static_cast<double>(image_h)); };
    const double x0 = ux(c[i].x0), x1 = ux(c[i].x1), y0 = uy(c[i].y0), y1 = uy(c[i].y1);
    if (!(x1 > x0) || !(y1 > y0)) continue;
    Box b;
    b.cls = c[i].cls;
    b.cx = (x0 + x1) / 2 / image_w;
    b.cy = (y0 + y1) / 2 / image_h;
    b.w = (x1 - x0) / image_w;
    b.h = (y1 - y0) / image_h;
    b.conf = c[i].conf;
    out.push_back(b);
  }
  return out;
}

struct YoloDetector::Net {
  cv::dnn::Net net;
};

YoloDetector::YoloDetector(const std::string& path, const YoloOptions& options)
    : net_(std::make_unique<Net>()), options_(options) {
  const std::string bad = options.validate();
  if (!bad.empty()) throw ModelError(bad);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw ModelError(path + ": no such model file");
  try {
    net_->net = cv::dnn::readNetFromONNX(path);
  } catch (const cv::Exception& e) {
    throw ModelError(path + ": not a readable ONNX model (" + std::string(e.err) + ")");
  }
  if (net_->net.empty()) throw ModelError(path + ": not a readable ONNX model");
  // Check the head with a blank input of the expected size.
  const cv::Mat blank(options.imgsz, options.imgsz, CV_8UC3, cv::Scalar(114, 114, 114));
  cv::Mat out;
  try {
    out = forward(cv::dnn::blobFromImage(blank, 1 / 255.0, cv::Size(), cv::Scalar(), true, false));
  } catch (const cv::Exception& e) {
    throw ModelError(fmt::format("{}: the network does not run on a 1x3x{}x{} input ({})", path, options.imgsz,
                                 options.imgsz, e.err));
  }
  std::string shape = "[";
  for (int d = 0; d < out.dims; ++d) shape += (d ? ", " : "") + std::to_string(out.size[d]);
  shape += "]";
  if (out.dims != 3 || out.size[0] != 1)
    throw ModelError(fmt::format(
        "{}: output {} is not a YOLO head (expected YOLOv5 [1, N, 5+nc] or YOLOv8 [1, 4+nc, N])", path, shape));
  const int a = out.size[1], b = out.size[2];
  // Real exports are told apart by their anchor counts (YOLOv5: 3 per cell of the 8/16/32-stride grids,
  // 25200 at 640; YOLOv8: one per cell, 8400); other shapes by which side is the long one.
  const int s = options.imgsz;
  const int cells = (s / 8) * (s / 8) + (s / 16) * (s / 16) + (s / 32) * (s / 32);
  if (a == 3 * cells && b >= 6) {
    head_ = YoloHead::kV5;
    classes_ = b - 5;
  } else if (b == cells && a >= 5) {
    head_ = YoloHead::kV8;
    classes_ = a - 4;
  } else if (b >= 6 && a > b) {
    head_ = YoloHead::kV5;
    classes_ = b - 5;
  } else if (a >= 5 && b > a) {
    head_ = YoloHead::kV8;  // YOLOv8 exports: no objectness, channels first
    classes_ = a - 4;
  } else {
    throw ModelError(fmt::format(
        "{}: output {} is not a YOLO head (expected YOLOv5 [1, N, 5+nc] or YOLOv8 [1, 4+nc, N])", path, shape));
  }
}

YoloDetector::~YoloDetector() = default;

cv::Mat YoloDetector::forward(const cv::Mat& blob) {
  net_->net.setInput(blob);
  return net_->net.forward().clone();
}

std::vector<Box> YoloDetector::detect(const cv::Mat& bgr) {
  const Letterbox lb = letterbox_for(bgr.cols, bgr.rows, options_.imgsz);
  const cv::Mat input = apply_letterbox(bgr, lb, options_.imgsz);
  const cv::Mat out = forward(cv::dnn::blobFromImage(input, 1 / 255.0, cv::Size(), cv::Scalar(), true, false));
  cv::Mat rows;
  if (head_ == YoloHead::kV5) {
    rows = cv::Mat(out.size[1], out.size[2], CV_32F, const_cast<float*>(out.ptr<float>()));
  } else {
    cv::transpose(cv::Mat(out.size[1], out.size[2], CV_32F, const_cast<float*>(out.ptr<float>())), rows);
  }
  return decode_yolo(rows, head_, lb, bgr.cols, bgr.rows, options_);
}

}  // namespace ipd
