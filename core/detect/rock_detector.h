// A classical rock detector (OpenCV): rocks differ from the local ground brightness; threshold the
// difference to a smoothed background, clean up, take contours' bounding boxes. The demo study's "models"
// are this detector with parameters tuned on one domain.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/geometry/geometry.h"

namespace ipd {

struct RockDetectorParams {
  double threshold = 28;        // grey-level difference to the local background
  int background_kernel = 101;  // odd; the median filter that estimates the ground
  int min_area = 30;            // pixels; smaller blobs are noise
  int close_kernel = 5;         // joins a rock's lit and dark halves
  std::string validate() const;
};

// Boxes normalised to the picture, class 0, confidence from contrast and size. `outlines`: each box also carries
// its contour (simplified to within a pixel) and is the contour's bounds, as a YOLO-seg line; a contour with no
// area is left out.
std::vector<Box> detect_rocks(const cv::Mat& bgr, const RockDetectorParams& params, bool outlines = false);

// Grid search for the parameters that maximise mean best-IoU of the GT rocks (a detector "trained" on
// these pictures).
RockDetectorParams tune_detector(const std::vector<cv::Mat>& pictures, const std::vector<std::vector<Box>>& gt);

}  // namespace ipd
