// Axis-aligned boxes (with their outlines), IoU and 2-D affine maps: the geometry everything else builds on.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "core/geometry/outline.h"

namespace ipd {

// A labelled or predicted box in normalised image coordinates (centre, size), as in YOLO txt files.
struct Box {
  int cls = 0;
  double cx = 0, cy = 0, w = 0, h = 0;
  double conf = 1.0;  // 1 for ground truth
  // The instance's mask, when its label line gave one (YOLO-seg, COCO polygons); the box is then its bounds.
  // Shared: boxes are copied by every filter and view, an outline's points are not (OutlineRef).
  OutlineRef outline = nullptr;

  double x0() const { return cx - 0.5 * w; }
  double y0() const { return cy - 0.5 * h; }
  double x1() const { return cx + 0.5 * w; }
  double y1() const { return cy + 0.5 * h; }
  double area() const { return (w > 0 && h > 0) ? w * h : 0.0; }
  Eigen::Vector2d centre() const { return {cx, cy}; }
};
// A study holds millions of boxes: their size is its memory (56 bytes: the class, five numbers, the outline).
static_assert(sizeof(Box) <= 56, "a box grew: a 10,000-scene study holds 3.6 million of them");

// Intersection over union; 0 (never NaN) when either box is degenerate or they don't overlap.
double iou(const Box& a, const Box& b);

// The perception task a number is about: boxes (the paper's detection) or instance masks (segmentation).
enum class Task { kDetect, kSegment };
const char* task_name(Task task);                      // "detect", "segment"
bool parse_task(const std::string& word, Task* task);  // the inverse of task_name; false for any other word
// The IoU of two instances for a task: box IoU for detect; mask IoU for segment (an instance without an outline
// is the mask of its box's rectangle there, so two boxes give their box IoU). The one IoU every number uses.
double instance_iou(const Box& a, const Box& b, Task task);

// n x m table T[i][j] = iou(gt[i], pred[j]), row-major.
struct IouTable {
  int rows = 0, cols = 0;
  std::vector<double> values;
  double at(int i, int j) const { return values[static_cast<size_t>(i) * cols + j]; }
};
IouTable iou_table(const std::vector<Box>& gt, const std::vector<Box>& pred);

// The paper's performance-value: per GT rock, the best IoU over the predictions of its own class (0 when there
// are none; the COCO convention, so a shadow prediction over a rock never scores it), and which prediction gave
// it (-1 when none overlaps; the first of equal best IoUs).
struct PerformanceValues {
  std::vector<double> value;
  std::vector<int> best_prediction;
};
PerformanceValues performance_values(const std::vector<Box>& gt, const std::vector<Box>& pred,
                                     Task task = Task::kDetect);

// y = A x + t, stored as a 2x3 matrix [A | t].
using Affine2 = Eigen::Matrix<double, 2, 3>;

inline Affine2 identity_affine() {
  Affine2 m;
  m << 1, 0, 0, 0, 1, 0;
  return m;
}
inline Eigen::Vector2d apply(const Affine2& m, const Eigen::Vector2d& p) { return m.leftCols<2>() * p + m.col(2); }
// b ∘ a: first a, then b.
Affine2 compose(const Affine2& b, const Affine2& a);
// Inverse; returns false when the linear part is singular.
bool invert(const Affine2& m, Affine2* out);
// Linear interpolation from identity (t = 0) to m (t = 1), used to animate a registration.
Affine2 interpolate_from_identity(const Affine2& m, double t);

// The axis-aligned bounding box of a box's four corners mapped by m (class and confidence kept, outline not).
Box transform_box(const Affine2& m, const Box& b);

std::vector<Eigen::Vector2d> centres(const std::vector<Box>& boxes);

}  // namespace ipd
