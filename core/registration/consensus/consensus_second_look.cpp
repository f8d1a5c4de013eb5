#include "core/registration/consensus/consensus_second_look.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>

#include "core/geometry/affine_estimator.h"
#include "core/registration/consensus/consensus_tuning.h"
#include "core/registration/consensus/local_optimisers.h"
#include "core/registration/pairing.h"

namespace ipd::detail {

namespace {

struct Rect {
  double x0, y0, x1, y1;
  bool holds(const Box& b) const { return b.x0() >= x0 && b.x1() <= x1 && b.y0() >= y0 && b.y1() <= y1; }
};

// The picture a side's labels come from: the unit image, widened to every box when labels leave it.
Rect picture_of(const std::vector<Box>& boxes) {
  Rect r{0, 0, 1, 1};
  for (const auto& b : boxes) {
    r.x0 = std::min(r.x0, b.x0());
    r.y0 = std::min(r.y0, b.y0());
    r.x1 = std::max(r.x1, b.x1());
    r.y1 = std::max(r.y1, b.y1());
  }
  return r;
}

double log_size(const Eigen::Vector2d& wh) { return 0.5 * std::log(std::max(wh.x() * wh.y(), 1e-300)); }

}  // namespace

double misalignment_cost(const Affine2& normalised) {
  // The normalised frame is isotropic (pixels), so its linear part is the camera's in pixels.
  const Eigen::Matrix2d l = normalised.leftCols<2>();
  const double log_scale = 0.5 * std::log(std::max(std::abs(l(0, 0) * l(1, 1) - l(0, 1) * l(1, 0)), 1e-300));
  const double rotation = std::atan2(l(1, 0) - l(0, 1), l(0, 0) + l(1, 1));
  return kTuning.weight_log_scale * std::abs(log_scale) + kTuning.weight_rotation * std::abs(rotation);
}

EdgeSearch edge_candidates(const RegistrationFrame& f, const Bounds& bounds, SupportMeasurer* support, size_t keep) {
  EdgeSearch out;
  const size_t na = f.a.size(), nb = f.b.size();
  std::vector<double> la(na), lb(nb);
  for (size_t i = 0; i < na; ++i) la[i] = log_size(f.size_a[i]);
  for (size_t j = 0; j < nb; ++j) lb[j] = log_size(f.size_b[j]);
  std::vector<std::pair<double, Affine2>> scored;
  std::priority_queue<double, std::vector<double>, std::greater<double>> best_scores;  // the keep best so far
  // Every edge once (B's in both directions): vector, length and log length; then no logarithm or square root
  // per edge pair, which the filters below reject ~96% of (large tier).
  struct Edge {
    Eigen::Vector2d v;
    double length = 0, log_length = 0;
  };
  auto edge = [](const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
    Edge e;
    e.v = to - from;
    e.length = e.v.norm();
    e.log_length = std::log(e.length);
    return e;
  };
  std::vector<Edge> edges_a(na * na), edges_b(nb * nb);
  for (size_t i1 = 0; i1 < na; ++i1)
    for (size_t i2 = i1 + 1; i2 < na; ++i2) edges_a[i1 * na + i2] = edge(f.a[i1], f.a[i2]);
  for (size_t j1 = 0; j1 < nb; ++j1)
    for (size_t j2 = 0; j2 < nb; ++j2)
      if (j1 != j2) edges_b[j1 * nb + j2] = edge(f.b[j1], f.b[j2]);
  const double log_min_scale = std::log(bounds.min_scale), log_max_scale = std::log(bounds.max_scale);
  for (size_t i1 = 0; i1 < na; ++i1)
    for (size_t j1 = 0; j1 < nb; ++j1) {
      const double d1 = lb[j1] - la[i1];  // log size ratio of the first end
      for (size_t i2 = i1 + 1; i2 < na; ++i2) {
        const Edge& ea = edges_a[i1 * na + i2];
        if (!(ea.length > 0)) continue;
        for (size_t j2 = 0; j2 < nb; ++j2) {
          if (j1 == j2) continue;
          out.work += 1;
          const double d2 = lb[j2] - la[i2];
          if (std::abs(d1 - d2) > 2 * kTuning.edge_log_size_gap) continue;  // no scale suits both ends
          const Edge& eb = edges_b[j1 * nb + j2];
          // The similarity's scale must lie in the bounds and agree with both rocks' size ratios.
          const double log_scale = eb.log_length - ea.log_length;
          if (log_scale < log_min_scale || log_scale > log_max_scale) continue;
          if (std::abs(d1 - log_scale) > kTuning.edge_log_size_gap ||
              std::abs(d2 - log_scale) > kTuning.edge_log_size_gap)
            continue;
          if (ea.v.dot(eb.v) < bounds.cos_rotation * ea.length * eb.length) continue;
          const Eigen::Vector2d src[2] = {f.a[i1], f.a[i2]}, dst[2] = {f.b[j1], f.b[j2]};
          Affine2 m;
          if (!similarity_least_squares(src, dst, 2, &m) || !bounds.plausible(m.leftCols<2>())) continue;
          // Only the best `keep` go on: a hypothesis that can't reach the current keep-th best stops early.
          const double s = support->score_above(m, best_scores.size() < keep ? -INFINITY : best_scores.top());
          ++out.hypotheses;
          out.work += static_cast<double>(na);
          if (!std::isfinite(s)) continue;
          scored.emplace_back(s, m);
          best_scores.push(s);
          if (best_scores.size() > keep) best_scores.pop();
        }
      }
    }
  const size_t n = std::min(keep, scored.size());
  // Ties broken by the affine's entries, so the order never depends on the sort's implementation.
  std::partial_sort(scored.begin(), scored.begin() + n, scored.end(), [](const auto& x, const auto& y) {
    if (x.first != y.first) return x.first > y.first;
    return std::lexicographical_compare(x.second.data(), x.second.data() + 6, y.second.data(), y.second.data() + 6);
  });
  for (size_t k = 0; k < n; ++k) {
    Affine2 m = scored[k].second;
    double s = scored[k].first;
    improve(support, &m, &s);
    polish(support, &m);
    out.candidates.push_back(m);
  }
  return out;
}

Judgement judge_candidate(const RegistrationFrame& f, const std::vector<Box>& boxes_a, const std::vector<Box>& boxes_b,
                          const Affine2& normalised, double consensus, const PairingRule& rule) {
  Judgement j;
  j.consensus = consensus;
  const Affine2 b_from_a = f.to_image(normalised);
  Affine2 a_from_b;
  const bool invertible = invert(b_from_a, &a_from_b);
  const RockPairs pairs = pair_aligned_boxes(b_from_a, boxes_a, boxes_b, rule);
  std::vector<char> paired_a(boxes_a.size(), 0), paired_b(boxes_b.size(), 0);
  for (const auto& [i, k] : pairs) {
    j.iou_sum += iou(transform_box(b_from_a, boxes_a[i]), boxes_b[k]);
    paired_a[i] = 1;
    paired_b[k] = 1;
  }
  const Rect picture_a = picture_of(boxes_a), picture_b = picture_of(boxes_b);
  for (size_t i = 0; i < boxes_a.size(); ++i)
    if (!paired_a[i] && picture_b.holds(transform_box(b_from_a, boxes_a[i]))) ++j.unpaired_a;
  if (invertible)
    for (size_t k = 0; k < boxes_b.size(); ++k)
      if (!paired_b[k] && picture_a.holds(transform_box(a_from_b, boxes_b[k]))) ++j.unpaired_b;
  j.total = consensus + kTuning.weight_iou * j.iou_sum - kTuning.weight_unpaired_a * j.unpaired_a -
            kTuning.weight_unpaired_b * j.unpaired_b - misalignment_cost(normalised);
  return j;
}

}  // namespace ipd::detail
