#include "core/registration/consensus/support_measurer.h"

#include <algorithm>

#include "core/registration/consensus/consensus_tuning.h"

namespace ipd::detail {

SupportMeasurer::SupportMeasurer(const RegistrationFrame& f, double gate, const Bounds& bounds)
    : a_(f.a),
      size_a_(f.size_a),
      grid_(f.b),
      gate2_(gate * gate),
      bounds_(bounds),
      best_(f.b.size(), 0.0),
      stamp_(f.b.size(), 0) {
  for (const auto& s : f.size_b) {
    log_w_b_.push_back(std::log(std::max(s.x(), 1e-300)));
    log_h_b_.push_back(std::log(std::max(s.y(), 1e-300)));
  }
}

// Sizes matter: two labellings of one rock agree in size far better than two different rocks do, which
// settles layouts that points alone leave ambiguous. Width and height are compared apart, not just the area:
// a wide rock and a tall one of equal area are different rocks.
double SupportMeasurer::score(const Affine2& m) {
  ++scored_;
  if (!bounds_.plausible(m.leftCols<2>())) return -INFINITY;
  // Large sets: a preview on every k-th A rock first. A hypothesis whose preview (scaled up) is far below
  // the best is turned down on it; its estimate is too low to be refined or to become the best, so the
  // search is unchanged while a hypothesis costs about preview_rocks queries instead of n.
  if (a_.size() >= 2 * kTuning.preview_rocks && preview_reference_ > 0) {
    const size_t stride = a_.size() / kTuning.preview_rocks;
    const double estimate = consensus(m, stride) * static_cast<double>(stride);
    if (estimate < kTuning.preview_reject * preview_reference_) return estimate;
  }
  return consensus(m, 1);
}

double SupportMeasurer::score_above(const Affine2& m, double floor) {
  ++scored_;
  if (!bounds_.plausible(m.leftCols<2>())) return -INFINITY;
  return consensus(m, 1, floor);
}

double SupportMeasurer::consensus(const Affine2& m, size_t stride, double floor) {
  ++epoch_;
  const double l00 = std::abs(m(0, 0)), l01 = std::abs(m(0, 1)), l10 = std::abs(m(1, 0)), l11 = std::abs(m(1, 1));
  double total = 0;
  for (size_t i = 0; i < a_.size(); i += stride) {
    if (total + static_cast<double>(a_.size() - i) < floor) return -INFINITY;
    double d2 = 0;
    const int j = grid_.nearest(apply(m, a_[i]), &d2, gate2_);
    if (j < 0 || !(d2 < gate2_)) continue;
    // Flat near zero, so labelling noise well inside the gate costs little; falls to 0 at the gate.
    const double r2 = d2 / gate2_;
    // The mapped box's bounding box has extents |L| (w, h).
    const double w_a = size_a_[i].x(), h_a = size_a_[i].y();
    const double w = (1.0 - r2 * r2) * shape_agreement(l00 * w_a + l01 * h_a, l10 * w_a + l11 * h_a, j);
    if (stamp_[j] != epoch_) {
      stamp_[j] = epoch_;
      best_[j] = w;
      total += w;
    } else if (w > best_[j]) {
      total += w - best_[j];
      best_[j] = w;
    }
  }
  return total;
}

double SupportMeasurer::shape_agreement(double mapped_w, double mapped_h, int j) const {
  if (!(mapped_w > 0) || !(mapped_h > 0)) return 1.0;
  const double lw = log_w_b_[j] - std::log(mapped_w), lh = log_h_b_[j] - std::log(mapped_h);
  return std::exp(-0.5 * (lw * lw + lh * lh) * kTuning.size_weight());
}

void SupportMeasurer::inlier_pairs(const Affine2& m, double g2, std::vector<Eigen::Vector2d>* src,
                                   std::vector<Eigen::Vector2d>* dst) {
  src->clear();
  dst->clear();
  claim_.assign(grid_.size(), {-1, INFINITY});
  for (size_t i = 0; i < a_.size(); ++i) {
    double d2 = 0;
    const int j = grid_.nearest(apply(m, a_[i]), &d2, g2);
    if (j >= 0 && d2 < g2 && d2 < claim_[j].second) claim_[j] = {static_cast<int>(i), d2};
  }
  for (size_t j = 0; j < claim_.size(); ++j) {
    if (claim_[j].first < 0) continue;
    src->push_back(a_[claim_[j].first]);
    dst->push_back(grid_.points()[j]);
  }
}

int SupportMeasurer::count_inliers(const Affine2& m) {
  inlier_pairs(m, gate2_, &scratch_src_, &scratch_dst_);
  return static_cast<int>(scratch_src_.size());
}

}  // namespace ipd::detail
