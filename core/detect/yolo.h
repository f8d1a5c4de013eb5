// Running a YOLOv5 ONNX export (export.py --include onnx) with OpenCV DNN, with detect.py's semantics:
// letterbox (keep aspect, pad with 114, centred), BGR -> RGB, /255; output [1, N, 5 + nc] decoded as
// cx, cy, w, h, objectness, class scores; confidence = objectness x best class score; class-aware NMS;
// boxes mapped back through the letterbox. A YOLOv8-style head [1, 4 + nc, N] (no objectness) is
// recognised and decoded too.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/geometry/geometry.h"
#include "core/util/errors.h"

namespace ipd {

struct YoloOptions {
  int imgsz = 640;
  double conf = 0.25, iou = 0.45;
  std::vector<int> classes;  // empty: all
  int max_det = 1000;
  std::string validate() const;
};

// Where the picture sits inside the square network input.
struct Letterbox {
  double scale = 1;           // input pixels per picture pixel
  int left = 0, top = 0;      // padding
  int width = 0, height = 0;  // of the resized picture
};
Letterbox letterbox_for(int image_w, int image_h, int imgsz);
cv::Mat apply_letterbox(const cv::Mat& bgr, const Letterbox& lb, int imgsz);

enum class YoloHead { kV5, kV8 };

// Decodes one raw output (already in [N, 5 + nc] or [N, 4 + nc] row form) into picture-normalised boxes.
std::vector<Box> decode_yolo(const cv::Mat& rows, YoloHead head, const Letterbox& lb, int image_w, int image_h,
                             const YoloOptions& options);

class YoloDetector {
 public:
  // Loads the network once and checks its output layout with a blank input; throws ModelError naming
  // the file and what was found.
  YoloDetector(const std::string& onnx_path, const YoloOptions& options);
  ~YoloDetector();
  YoloHead head() const { return head_; }
  int classes() const { return classes_; }
  std::vector<Box> detect(const cv::Mat& bgr);

 private:
  struct Net;
  std::unique_ptr<Net> net_;
  YoloOptions options_;
  YoloHead head_ = YoloHead::kV5;
  int classes_ = 0;
  cv::Mat forward(const cv::Mat& blob);
};

}  // namespace ipd
