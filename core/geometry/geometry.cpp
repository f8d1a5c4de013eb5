#include "core/geometry/geometry.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace ipd {

double iou(const Box& a, const Box& b) {
  const double aa = a.area(), ab = b.area();
  if (!(aa > 0) || !(ab > 0)) return 0.0;
  const double iw = std::min(a.x1(), b.x1()) - std::max(a.x0(), b.x0());
  const double ih = std::min(a.y1(), b.y1()) - std::max(a.y0(), b.y0());
  if (!(iw > 0) || !(ih > 0)) return 0.0;
  const double inter = iw * ih;
  const double uni = aa + ab - inter;
  if (!(uni > 0) || !std::isfinite(uni)) return 0.0;
  return std::clamp(inter / uni, 0.0, 1.0);
}

const char* task_name(Task task) { return task == Task::kSegment ? "segment" : "detect"; }

bool parse_task(const std::string& word, Task* task) {
  if (word != "detect" && word != "segment") return false;
  *task = word == "segment" ? Task::kSegment : Task::kDetect;
  return true;
}

namespace {
// A box as the mask of its rectangle, for an instance without an outline in the segment task.
Outline rectangle_outline(const Box& b) {
  Outline o;
  make_outline({{b.x0(), b.y0()}, {b.x1(), b.y0()}, {b.x1(), b.y1()}, {b.x0(), b.y1()}}, &o);
  return o;
}
}  // namespace

double instance_iou(const Box& a, const Box& b, Task task) {
  if (task == Task::kDetect) return iou(a, b);
  // Bounding-box prefilter: masks inside boxes that do not overlap do not overlap, so no clipping.
  if (!(iou(a, b) > 0)) return 0.0;
  if (a.outline && b.outline) return mask_iou(*a.outline, *b.outline);
  if (!a.outline && !b.outline) return iou(a, b);
  return a.outline ? mask_iou(*a.outline, rectangle_outline(b)) : mask_iou(rectangle_outline(a), *b.outline);
}

IouTable iou_table(const std::vector<Box>& gt, const std::vector<Box>& pred) {
  IouTable t;
  t.rows = static_cast<int>(gt.size());
  t.cols = static_cast<int>(pred.size());
  t.values.resize(gt.size() * pred.size());
  for (size_t i = 0; i < gt.size(); ++i)
    for (size_t j = 0; j < pred.size(); ++j) t.values[i * pred.size() + j] = iou(gt[i], pred[j]);
  return t;
}

PerformanceValues performance_values(const std::vector<Box>& gt, const std::vector<Box>& pred, Task task) {
  PerformanceValues pv;
  pv.value.assign(gt.size(), 0.0);
  pv.best_prediction.assign(gt.size(), -1);
  for (size_t i = 0; i < gt.size(); ++i) {
    for (size_t j = 0; j < pred.size(); ++j) {
      if (pred[j].cls != gt[i].cls) continue;  // a shadow prediction never scores a rock (COCO: per category)
      // Boxes call iou directly so that it is inlined: this loop is most of a warm run's IPD stage.
      const double v = task == Task::kDetect ? iou(gt[i], pred[j]) : instance_iou(gt[i], pred[j], task);
      if (v > pv.value[i]) {
        pv.value[i] = v;
        pv.best_prediction[i] = static_cast<int>(j);
      }
    }
  }
  return pv;
}

Affine2 compose(const Affine2& b, const Affine2& a) {
  Affine2 r;
  r.leftCols<2>() = b.leftCols<2>() * a.leftCols<2>();
  r.col(2) = b.leftCols<2>() * a.col(2) + b.col(2);
  return r;
}

bool invert(const Affine2& m, Affine2* out) {
  const Eigen::Matrix2d a = m.leftCols<2>();
  const double det = a.determinant();
  const double norm = a.cwiseAbs().maxCoeff();
  if (!std::isfinite(det) || std::abs(det) <= 1e-12 * std::max(1.0, norm * norm)) return false;
  const Eigen::Matrix2d ai = a.inverse();
  out->leftCols<2>() = ai;
  out->col(2) = -ai * m.col(2);
  return true;
}

Affine2 interpolate_from_identity(const Affine2& m, double t) {
  t = std::clamp(t, 0.0, 1.0);
  return (1.0 - t) * identity_affine() + t * m;
}

Box transform_box(const Affine2& m, const Box& b) {
  const Eigen::Vector2d corners[4] = {{b.x0(), b.y0()}, {b.x1(), b.y0()}, {b.x0(), b.y1()}, {b.x1(), b.y1()}};
  double lo_x = INFINITY, lo_y = INFINITY, hi_x = -INFINITY, hi_y = -INFINITY;
  for (const auto& c : corners) {
    const Eigen::Vector2d p = apply(m, c);
    lo_x = std::min(lo_x, p.x());
    hi_x = std::max(hi_x, p.x());
    lo_y = std::min(lo_y, p.y());
    hi_y = std::max(hi_y, p.y());
  }
  Box r = b;
  r.cx = 0.5 * (lo_x + hi_x);
  r.cy = 0.5 * (lo_y + hi_y);
  r.w = hi_x - lo_x;
  r.h = hi_y - lo_y;
  r.outline = nullptr;  // a box moved by m is no longer where its outline's points are
  return r;
}

std::vector<Eigen::Vector2d> centres(const std::vector<Box>& boxes) {
  std::vector<Eigen::Vector2d> c;
  c.reserve(boxes.size());
  for (const auto& b : boxes) c.push_back(b.centre());
  return c;
}

}  // namespace ipd
