#include "core/registration/consensus/local_optimisers.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/geometry/affine_estimator.h"
#include "core/registration/consensus/consensus_tuning.h"

namespace ipd::detail {

void improve(SupportMeasurer* support, Affine2* m, double* s, const Deadline* deadline) {
  std::vector<Eigen::Vector2d> src, dst;
  for (double scale : kTuning.refine_gate_scales) {
    if (deadline != nullptr && deadline->passed()) return;
    support->inlier_pairs(*m, scale * support->gate2(), &src, &dst);
    Affine2 cand;
    if (src.size() < 3 || !affine_least_squares(src, dst, &cand)) continue;
    const double cs = support->score(cand);
    if (cs > *s + 1e-9) {
      *m = cand;
      *s = cs;
    }
  }
}

void polish(SupportMeasurer* support, Affine2* m) {
  std::vector<Eigen::Vector2d> src, dst;
  std::vector<double> w;
  const double gate2 = support->gate2(), c2 = gate2 / kTuning.polish_scale_divisor;
  const Affine2 start = *m;
  const double before = support->score(start);
  for (int round = 0; round < kTuning.polish_rounds; ++round) {
    support->inlier_pairs(*m, gate2, &src, &dst);
    w.resize(src.size());
    for (size_t k = 0; k < src.size(); ++k) w[k] = 1.0 / (1.0 + (apply(*m, src[k]) - dst[k]).squaredNorm() / c2);
    Affine2 cand;
    if (src.size() < 3 || !affine_weighted_least_squares(src, dst, w, &cand) ||
        !support->bounds().plausible(cand.leftCols<2>()))
      break;
    *m = cand;
  }
  if (support->score(*m) < before - kTuning.polish_loss * std::max(1.0, before)) *m = start;
}

namespace {

// One annealing step of soft_refine(): the weighted least-squares affine of every (A, B) rock pair that pulls,
// each A rock's pulls normalised against the outlier class. False when fewer than 3 pairs pull.
bool soft_step(const SupportMeasurer& support, double sigma, Affine2* g) {
  const auto& a = support.a();
  const auto& size_a = support.size_a();
  const auto& b = support.grid().points();
  const size_t nb = b.size();
  const double sig2 = sigma * sigma * support.gate2();
  std::vector<Eigen::Vector2d> src, dst;
  std::vector<double> w, pull(nb);
  const Affine2& m = *g;
  const double l00 = std::abs(m(0, 0)), l01 = std::abs(m(0, 1)), l10 = std::abs(m(1, 0)), l11 = std::abs(m(1, 1));
  for (size_t i = 0; i < a.size(); ++i) {
    const Eigen::Vector2d p = apply(m, a[i]);
    const double w_a = size_a[i].x(), h_a = size_a[i].y();
    const double mapped_w = l00 * w_a + l01 * h_a, mapped_h = l10 * w_a + l11 * h_a;
    // shape_agreement() with the mapped box's logarithms taken once, and one exp per pair.
    const bool sized = mapped_w > 0 && mapped_h > 0;
    const double log_w = sized ? std::log(mapped_w) : 0.0, log_h = sized ? std::log(mapped_h) : 0.0;
    double total = kTuning.soft_outlier;
    for (size_t j = 0; j < nb; ++j) {
      const double d2 = (b[j] - p).squaredNorm();
      pull[j] = 0.0;
      if (!(d2 < 9 * sig2)) continue;
      const double lw = support.log_w_b(j) - log_w, lh = support.log_h_b(j) - log_h;
      pull[j] = std::exp(-0.5 * (d2 / sig2 + (sized ? (lw * lw + lh * lh) * kTuning.size_weight() : 0.0)));
      total += pull[j];
    }
    for (size_t j = 0; j < nb; ++j)
      if (pull[j] > 1e-3 * total) src.push_back(a[i]), dst.push_back(b[j]), w.push_back(pull[j] / total);
  }
  Affine2 cand;
  if (src.size() < 3 || !affine_weighted_least_squares(src, dst, w, &cand)) return false;
  *g = cand;
  return true;
}

// A slide, not a jump: most of the rocks m aligned stay within a gate of where m put them. From a sparse
// small overlap the widest step can reach a different alignment altogether.
bool slid(const SupportMeasurer& support, const Affine2& from, const Affine2& to) {
  const double gate2 = support.gate2();
  int aligned = 0, stayed = 0;
  for (const auto& p : support.a()) {
    double d2 = 0;
    const Eigen::Vector2d at = apply(from, p);
    if (support.grid().nearest(at, &d2, gate2) < 0 || !(d2 < gate2)) continue;
    ++aligned;
    stayed += (apply(to, p) - at).squaredNorm() < gate2;
  }
  return 2 * stayed > aligned;
}

}  // namespace

bool soft_refine(SupportMeasurer* support, Affine2* m, double* s) {
  const size_t na = support->a().size(), nb = support->grid().size();
  if (na < 3 || nb < 3 || na * nb > kTuning.soft_max_pairs) return false;
  Affine2 g = *m;
  for (double sigma : kTuning.soft_sigmas)
    if (!soft_step(*support, sigma, &g)) return false;
  if (!slid(*support, *m, g)) return false;
  const double gs = support->score(g);
  if (!(gs > *s + 1e-9)) return false;
  *m = g;
  *s = gs;
  return true;
}

}  // namespace ipd::detail
