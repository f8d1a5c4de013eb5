// Internal: the consensus registration's support measurer, the soft consensus score of an affine between the
// frame's two rock sets. It knows nothing of the search: the search tells it the best refined score so far,
// which large sets preview hypotheses against.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <utility>
#include <vector>

#include "core/geometry/point_grid.h"
#include "core/registration/consensus/consensus_bounds.h"
#include "core/registration/registration_frame.h"

namespace ipd::detail {

// What the soft consensus calls close, in normalised units (consensus_registration.cpp): the consensus
// registration's inlier gate, and the gate cpd's confidence is measured with.
double consensus_gate(const RegistrationFrame& f, const RegistrationOptions& o, const Deadline& deadline);

class SupportMeasurer {
 public:
  // `gate`: the inlier distance in normalised units; hypotheses outside `bounds` score -inf.
  SupportMeasurer(const RegistrationFrame& f, double gate, const Bounds& bounds);

  // Sum over A's rocks of (closeness to a B rock) x (agreement of the mapped box's width and height with
  // that rock's), each B rock counted once; -inf for an implausible affine. Large sets are previewed first.
  double score(const Affine2& m);
  // score() for the second look, which keeps only its best few: -inf once `floor` is out of reach (exact: any
  // hypothesis scoring at least `floor` is scored in full).
  double score_above(const Affine2& m, double floor);
  // The soft consensus over every `stride`-th A rock. With a `floor`: -inf as soon as the rest of A's rocks
  // (each adds at most 1) can no longer lift it there.
  double consensus(const Affine2& m, size_t stride, double floor = -INFINITY);
  // exp(-mean squared log ratio of width and height / 2 sigma^2): 1 for a mapped box of B rock j's shape.
  double shape_agreement(double mapped_w, double mapped_h, int j) const;

  // Mutually nearest (A, B) pairs within sqrt(g2) after m.
  void inlier_pairs(const Affine2& m, double g2, std::vector<Eigen::Vector2d>* src, std::vector<Eigen::Vector2d>* dst);
  int count_inliers(const Affine2& m);

  // The best refined score of the search so far: previews scaled up far below it turn a hypothesis down.
  void set_preview_reference(double best) { preview_reference_ = best; }
  int scored() const { return scored_; }  // score() and score_above() calls so far

  const std::vector<Eigen::Vector2d>& a() const { return a_; }
  const std::vector<Eigen::Vector2d>& size_a() const { return size_a_; }
  const PointGrid& grid() const { return grid_; }
  double log_w_b(size_t j) const { return log_w_b_[j]; }
  double log_h_b(size_t j) const { return log_h_b_[j]; }
  double gate2() const { return gate2_; }
  const Bounds& bounds() const { return bounds_; }

 private:
  const std::vector<Eigen::Vector2d>& a_;
  const std::vector<Eigen::Vector2d>& size_a_;
  std::vector<double> log_w_b_, log_h_b_;  // B's box extents, log
  PointGrid grid_;
  double gate2_;
  Bounds bounds_;
  double preview_reference_ = -INFINITY;
  int scored_ = 0;
  std::vector<double> best_;  // per B rock, its best weight in the current consensus
  std::vector<unsigned> stamp_;
  unsigned epoch_ = 0;
  std::vector<std::pair<int, double>> claim_;
  std::vector<Eigen::Vector2d> scratch_src_, scratch_dst_;  // reused by count_inliers()
};

}  // namespace ipd::detail
