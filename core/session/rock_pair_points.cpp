#include "core/session/rock_pair_points.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <tuple>

#include <fmt/format.h>

#include "core/stats/statistics.h"
#include "core/stats/study_statistics.h"

namespace ipd {
namespace {

double best_confidence(const PerformanceValues& perf, const std::vector<Box>& predictions, int rock) {
  const int best = perf.best_prediction[rock];
  return best >= 0 ? predictions[best].conf : kNaN;
}

// One scene's counted pairs, turned to the view's orientation (contributions are in the domain pair's).
void add_scene(const Session& session, int scene, const SceneIpd& contribution, double pixel_area,
               std::vector<RockPairPoint>* out) {
  const bool swapped = session.swapped();
  const auto& gt_left = session.gt(Side::kA, scene);
  const PerformanceValues& perf_left = session.performance(Side::kA, scene);
  const PerformanceValues& perf_right = session.performance(Side::kB, scene);
  const auto& pred_left = session.predictions(Side::kA, scene);
  const auto& pred_right = session.predictions(Side::kB, scene);
  for (size_t k = 0; k < contribution.counted.size(); ++k) {
    const auto [a, b] = contribution.counted[k];
    RockPairPoint p;
    p.scene = scene;
    p.rock_a = swapped ? b : a;
    p.rock_b = swapped ? a : b;
    p.perf_a = swapped ? contribution.perf_b[k] : contribution.perf_a[k];
    p.perf_b = swapped ? contribution.perf_a[k] : contribution.perf_b[k];
    p.abs_diff = std::abs(p.perf_a - p.perf_b);
    const Box& box = gt_left[p.rock_a];
    p.size = box.area() * pixel_area;
    p.x = box.cx;
    p.y = box.cy;
    p.conf_a = best_confidence(perf_left, pred_left, p.rock_a);
    p.conf_b = best_confidence(perf_right, pred_right, p.rock_b);
    out->push_back(p);
  }
}

bool inside(double v, double lo, double hi) { return v >= lo && v <= hi; }  // false for NaN

}  // namespace

std::vector<RockPairPoint> rock_pair_points(const Session& session, const std::vector<int>& scenes) {
  std::vector<RockPairPoint> out;
  const auto& contributions = session.contributions_for(session.model(), session.pair_index());
  if (contributions.empty()) return out;
  const auto [width, height] = domain_image_size(session.study(), session.left_domain());
  const double pixel_area = width > 0 ? static_cast<double>(width) * height : 1e6;
  if (scenes.empty()) {
    for (size_t s = 0; s < contributions.size(); ++s)
      add_scene(session, static_cast<int>(s), contributions[s], pixel_area, &out);
  } else {
    for (const int s : scenes)
      if (s >= 0 && static_cast<size_t>(s) < contributions.size())
        add_scene(session, s, contributions[s], pixel_area, &out);
  }
  return out;
}

double axis_value(const RockPairPoint& p, PairAxis axis) {
  switch (axis) {
    case PairAxis::kPerfA:
      return p.perf_a;
    case PairAxis::kPerfB:
      return p.perf_b;
    case PairAxis::kAbsDiff:
      return p.abs_diff;
    case PairAxis::kSize:
      return p.size;
    case PairAxis::kX:
      return p.x;
    case PairAxis::kY:
      return p.y;
    case PairAxis::kConfA:
      return p.conf_a;
    case PairAxis::kConfB:
      return p.conf_b;
  }
  return kNaN;
}

const char* axis_name(PairAxis axis) {
  switch (axis) {
    case PairAxis::kPerfA:
      return "perf A";
    case PairAxis::kPerfB:
      return "perf B";
    case PairAxis::kAbsDiff:
      return "|diff|";
    case PairAxis::kSize:
      return "size (px²)";
    case PairAxis::kX:
      return "x";
    case PairAxis::kY:
      return "y";
    case PairAxis::kConfA:
      return "conf A";
    case PairAxis::kConfB:
      return "conf B";
  }
  return "?";
}

bool parse_pair_axis(const std::string& word, PairAxis* axis) {
  static const std::pair<const char*, PairAxis> kWords[] = {{"perf-a", PairAxis::kPerfA}, {"perf-b", PairAxis::kPerfB},
                                                            {"diff", PairAxis::kAbsDiff}, {"size", PairAxis::kSize},
                                                            {"x", PairAxis::kX},          {"y", PairAxis::kY},
                                                            {"conf-a", PairAxis::kConfA}, {"conf-b", PairAxis::kConfB}};
  for (const auto& [w, a] : kWords)
    if (word == w) return *axis = a, true;
  return false;
}

bool parse_gallery_sort(const std::string& word, GallerySort* sort) {
  static const std::pair<const char*, GallerySort> kWords[] = {{"diff", GallerySort::kDiff},
                                                               {"perf-a", GallerySort::kPerfA},
                                                               {"perf-b", GallerySort::kPerfB},
                                                               {"size", GallerySort::kSize}};
  for (const auto& [w, s] : kWords)
    if (word == w) {
      *sort = s;
      return true;
    }
  return false;
}

std::string gallery_sort_label(GallerySort sort, const std::string& a, const std::string& b) {
  if (sort == GallerySort::kPerfA) return "perf " + a;
  if (sort == GallerySort::kPerfB) return "perf " + b;
  return gallery_sort_name(sort);
}

const char* gallery_sort_name(GallerySort sort) {
  switch (sort) {
    case GallerySort::kDiff:
      return "|diff|";
    case GallerySort::kPerfA:
      return "perf A";
    case GallerySort::kPerfB:
      return "perf B";
    case GallerySort::kSize:
      return "size";
  }
  return "";
}

std::vector<int> gallery_sorted(const std::vector<RockPairPoint>& points, GallerySort sort) {
  std::vector<int> order = gallery_order(points);
  if (sort == GallerySort::kDiff) return order;
  const PairAxis key = sort == GallerySort::kPerfA   ? PairAxis::kPerfA
                       : sort == GallerySort::kPerfB ? PairAxis::kPerfB
                                                     : PairAxis::kSize;
  std::stable_sort(order.begin(), order.end(),
                   [&](int i, int j) { return axis_value(points[i], key) > axis_value(points[j], key); });
  return order;
}

std::vector<RockPairPoint> cell_pair_points(const StudyLabels& labels, const TableCell& cell) {
  std::vector<RockPairPoint> out;
  if (cell.missing_predictions) return out;
  const auto [width, height] = domain_image_size(labels.study, cell.a);
  const double pixel_area = width > 0 ? static_cast<double>(width) * height : 1e6;
  for (size_t s = 0; s < cell.per_scene.size(); ++s) {
    const SceneIpd& sc = cell.per_scene[s];
    const auto& gt_a = labels.gt_of(cell.a, sc.stem).boxes;
    const auto& gt_b = labels.gt_of(cell.b, sc.stem).boxes;
    const auto& pred_a = labels.predictions_of(cell.a, cell.model, sc.stem).boxes;
    const auto& pred_b = labels.predictions_of(cell.b, cell.model, sc.stem).boxes;
    const Task task = labels.study.config.task;
    const PerformanceValues perf_a = performance_values(gt_a, pred_a, task);
    const PerformanceValues perf_b = performance_values(gt_b, pred_b, task);
    for (size_t k = 0; k < sc.counted.size(); ++k) {
      RockPairPoint p;
      p.scene = static_cast<int>(s);
      std::tie(p.rock_a, p.rock_b) = sc.counted[k];
      p.perf_a = sc.perf_a[k];
      p.perf_b = sc.perf_b[k];
      p.abs_diff = std::abs(p.perf_a - p.perf_b);
      const Box& box = gt_a[p.rock_a];
      p.size = box.area() * pixel_area;
      p.x = box.cx;
      p.y = box.cy;
      p.conf_a = best_confidence(perf_a, pred_a, p.rock_a);
      p.conf_b = best_confidence(perf_b, pred_b, p.rock_b);
      out.push_back(p);
    }
  }
  return out;
}

std::vector<int> gallery_order(const std::vector<RockPairPoint>& points) {
  std::vector<int> order(points.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::sort(order.begin(), order.end(), [&](int i, int j) {
    const RockPairPoint &p = points[i], &q = points[j];
    if (p.abs_diff != q.abs_diff) return p.abs_diff > q.abs_diff;
    if (p.scene != q.scene) return p.scene < q.scene;
    if (p.rock_a != q.rock_a) return p.rock_a < q.rock_a;
    return p.rock_b < q.rock_b;
  });
  return order;
}

bool RockPairKey::operator<(const RockPairKey& o) const {
  return std::tie(scene, rock_a, rock_b) < std::tie(o.scene, o.rock_a, o.rock_b);
}
bool RockPairKey::operator==(const RockPairKey& o) const {
  return scene == o.scene && rock_a == o.rock_a && rock_b == o.rock_b;
}
RockPairKey key_of(const RockPairPoint& p) { return {p.scene, p.rock_a, p.rock_b}; }

std::vector<char> marked_pairs(const std::vector<RockPairPoint>& points, const std::vector<RockPairKey>& pairs) {
  std::vector<char> marked(points.size(), 0);
  for (size_t i = 0; i < points.size(); ++i)
    marked[i] = std::binary_search(pairs.begin(), pairs.end(), key_of(points[i])) ? 1 : 0;
  return marked;
}

std::string PairSelection::label() const {
  return fmt::format("selection: {} pair{} in {} scene{}", points.size(), points.size() == 1 ? "" : "s", scenes.size(),
                     scenes.size() == 1 ? "" : "s");
}

PairSelection select_in_box(const std::vector<RockPairPoint>& points, PairAxis x_axis, PairAxis y_axis, double x0,
                            double y0, double x1, double y1) {
  PairSelection out;
  const double xlo = std::min(x0, x1), xhi = std::max(x0, x1), ylo = std::min(y0, y1), yhi = std::max(y0, y1);
  std::set<int> scenes;
  for (size_t i = 0; i < points.size(); ++i) {
    if (!inside(axis_value(points[i], x_axis), xlo, xhi) || !inside(axis_value(points[i], y_axis), ylo, yhi)) continue;
    out.points.push_back(static_cast<int>(i));
    out.pairs.push_back(key_of(points[i]));
    scenes.insert(points[i].scene);
  }
  out.scenes.assign(scenes.begin(), scenes.end());
  std::sort(out.pairs.begin(), out.pairs.end());
  return out;
}

}  // namespace ipd
