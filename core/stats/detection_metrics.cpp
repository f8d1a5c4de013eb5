#include "core/stats/detection_metrics.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/geometry/confidence_threshold.h"
#include "core/stats/statistics.h"

namespace ipd {

namespace {

// Indices of the detections by descending score, stable (numpy's argsort(-score, kind="mergesort")).
std::vector<size_t> by_score(const std::vector<double>& scores) {
  std::vector<size_t> order(scores.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](size_t i, size_t j) { return scores[i] > scores[j]; });
  return order;
}

// COCOeval.evaluateImg for one image and threshold: per kept detection (in score order), matched or not.
struct ImageMatches {
  std::vector<double> scores;
  std::vector<char> matched;
};
ImageMatches match_image(const DetectionImage& im, double threshold, int max_detections) {
  std::vector<double> scores;
  for (const auto& d : im.detections) scores.push_back(d.conf);
  std::vector<size_t> order = by_score(scores);
  if (max_detections >= 0 && order.size() > static_cast<size_t>(max_detections)) order.resize(max_detections);
  ImageMatches out;
  std::vector<char> gt_taken(im.gt.size(), 0);
  for (size_t d : order) {
    double best = std::min(threshold, 1 - 1e-10);
    int m = -1;
    for (size_t g = 0; g < im.gt.size(); ++g) {
      if (gt_taken[g] || im.gt[g].cls != im.detections[d].cls) continue;  // per category, as COCOeval
      const double v = instance_iou(im.detections[d], im.gt[g], im.task);
      if (v < best) continue;
      best = v;
      m = static_cast<int>(g);
    }
    if (m >= 0) gt_taken[m] = 1;
    out.scores.push_back(scores[d]);
    out.matched.push_back(m >= 0);
  }
  return out;
}

}  // namespace

double average_precision(const std::vector<DetectionImage>& images, double iou_threshold, int max_detections) {
  long gt = 0;
  std::vector<double> scores;
  std::vector<char> matched;
  for (const auto& im : images) {
    gt += static_cast<long>(im.gt.size());
    const ImageMatches m = match_image(im, iou_threshold, max_detections);
    scores.insert(scores.end(), m.scores.begin(), m.scores.end());
    matched.insert(matched.end(), m.matched.begin(), m.matched.end());
  }
  if (gt == 0) return kNaN;
  const std::vector<size_t> order = by_score(scores);
  const size_t nd = order.size();
  std::vector<double> recall(nd), precision(nd);
  double tp = 0, fp = 0;
  const double eps = std::nextafter(1.0, 2.0) - 1.0;  // np.spacing(1)
  for (size_t k = 0; k < nd; ++k) {
    (matched[order[k]] ? tp : fp) += 1;
    recall[k] = tp / gt;
    precision[k] = tp / (fp + tp + eps);
  }
  for (size_t k = nd; k-- > 1;) precision[k - 1] = std::max(precision[k - 1], precision[k]);
  double sum = 0;
  for (int r = 0; r <= 100; ++r) {
    const double at = r == 100 ? 1.0 : r * 0.01;                                           // np.linspace(0, 1, 101)
    const size_t k = std::lower_bound(recall.begin(), recall.end(), at) - recall.begin();  // searchsorted left
    sum += k < nd ? precision[k] : 0.0;
  }
  return sum / 101;
}

double average_precision_50_95(const std::vector<DetectionImage>& images, int max_detections) {
  const double step = (0.95 - 0.5) / 9;  // np.linspace(.5, .95, 10)
  double sum = 0;
  for (int t = 0; t < 10; ++t) {
    const double ap = average_precision(images, t == 9 ? 0.95 : 0.5 + t * step, max_detections);
    if (std::isnan(ap)) return kNaN;
    sum += ap;
  }
  return sum / 10;
}

DetectionMetrics detection_metrics(const std::vector<DetectionImage>& images, double conf_threshold) {
  DetectionMetrics m;
  m.ap50 = average_precision(images, 0.5);
  m.ap50_95 = average_precision_50_95(images);
  for (const auto& im : images) {
    DetectionImage kept;
    kept.gt = im.gt;
    kept.task = im.task;  // precision and recall match as AP does: by mask IoU in the segment task
    kept.detections = predictions_kept(im.detections, conf_threshold);
    m.gt += static_cast<long>(kept.gt.size());
    m.detections += static_cast<long>(kept.detections.size());
    const ImageMatches r = match_image(kept, 0.5, -1);
    m.true_positives += std::count(r.matched.begin(), r.matched.end(), 1);
  }
  if (m.detections > 0) m.precision = static_cast<double>(m.true_positives) / m.detections;
  if (m.gt > 0) m.recall = static_cast<double>(m.true_positives) / m.gt;
  if (m.true_positives > 0)
    m.f1 = 2 * m.precision * m.recall / (m.precision + m.recall);
  else if (m.gt > 0 || m.detections > 0)
    m.f1 = 0;
  return m;
}

}  // namespace ipd
