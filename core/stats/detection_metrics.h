// The detection metrics every reader of a detection paper knows, beside IPD: COCO average precision
// (pycocotools' rules, one class) and precision / recall / F1 at a confidence threshold.
#pragma once

#include <limits>
#include <vector>

#include "core/geometry/geometry.h"

namespace ipd {

// One image: its GT boxes and its detections (Box::conf is the score), matched by box IoU (detect) or by mask IoU
// (segment: pycocotools' iouType 'segm'), through the one matching below.
struct DetectionImage {
  std::vector<Box> gt, detections;
  Task task = Task::kDetect;
};

// pycocotools' COCOeval for one category, area "all", no crowd: per image the detections sorted by score
// (stable) and cut to `max_detections`; each detection in turn takes the unmatched GT with the highest IoU
// >= the threshold (a later GT wins a tie); over all images (stable sort by score, images in order)
// precision is made monotone and read at the 101 recall points 0, 0.01, ..., 1 (0 beyond the last recall).
// NaN when there is no GT at all (COCO's -1).
// pycocotools' maxDets: AP counts at most this many detections of a picture, its most confident.
constexpr int kCocoMaxDetections = 100;

double average_precision(const std::vector<DetectionImage>& images, double iou_threshold,
                         int max_detections = kCocoMaxDetections);
// The mean over IoU thresholds 0.50, 0.55, ..., 0.95.
double average_precision_50_95(const std::vector<DetectionImage>& images, int max_detections = kCocoMaxDetections);

struct DetectionMetrics {
  double ap50 = std::numeric_limits<double>::quiet_NaN(), ap50_95 = std::numeric_limits<double>::quiet_NaN();
  double precision = std::numeric_limits<double>::quiet_NaN(), recall = std::numeric_limits<double>::quiet_NaN();
  double f1 = std::numeric_limits<double>::quiet_NaN();
  long gt = 0, detections = 0;  // detections at or above the threshold
  long true_positives = 0;
};

// AP over the kCocoMaxDetections most confident detections of each picture; precision, recall and F1 over
// every detection with conf >= threshold, matched
// greedily at IoU 0.5 as above (so the counts agree with AP's matching).
DetectionMetrics detection_metrics(const std::vector<DetectionImage>& images, double conf_threshold);

}  // namespace ipd
