// Internal: how the consensus registration judges a hypothesis (the plausibility bounds of a camera
// misalignment, the soft consensus score, LO-RANSAC refinement and the stopping rule). Used by
// consensus_registration.cpp only; kept apart so each file stays readable.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/geometry/affine_estimator.h"
#include "core/geometry/point_grid.h"
#include "core/registration/consensus/consensus_search.h"
#include "core/registration/registration_frame.h"
#include "core/registration/registration_recorder.h"
#include "core/registration/robust_loop.h"

namespace ipd::detail {

// A consensus that chance would give less often than this, over every hypothesis allowed, ends the search.
inline constexpr double kChanceLevel = 0.05;
inline constexpr double kSizeSigma = 0.25, kSizeWeight = 1.0 / (2 * kSizeSigma * kSizeSigma);  // log size ratio
inline constexpr double kRefineFraction = 0.5;
// Sets of at least twice this many rocks preview each hypothesis on this many; previews scaled up below this
// fraction of the best score end there (half the refinement threshold: room for the preview's noise).
inline constexpr size_t kPreviewRocks = 64;
inline constexpr double kPreviewReject = 0.25;
// The best consensus found again from this many other anchor rocks ends the search: the true alignment
// attracts hypotheses from every rock that kept its neighbours, wrong ones rarely from two.
inline constexpr int kConfirmations = 2;
// polish() gives up at most this fraction of the consensus (of 1, if less) for its fit.
inline constexpr double kPolishLoss = 0.05;
// soft_refine(): the spread of each step in gates (annealed), the outlier class's weight (relative to a B
// rock at distance 0 of the same shape) and the largest A x B it runs on (its cost is A x B per step; the
// benchmark's sets are about 15 x 13). Large tier F1, mean of seeds 0-6: 0.9700 without it, 0.9721 with it;
// an outlier weight of 0.1 instead of 0.5 gained 0.0001 less (measured before the judged final fit).
inline constexpr double kSoftSigmas[] = {1.5, 1.2, 1.0, 0.8, 0.6, 0.5, 0.5};
inline constexpr double kSoftOutlier = 0.5;
inline constexpr size_t kSoftMaxPairs = 1024;

// What a camera misalignment can do to the linear part of the affine. Checked for every hypothesis, so in
// closed form without trigonometry: with e = (a+d)/2, f = (a-d)/2, g = (c+b)/2, h = (c-b)/2, the singular
// values are |(e,h)| +- |(f,g)| and the rotation of the closest similarity is the angle of (e, h).
struct Bounds {
  double min_scale, max_scale, max_rotation, max_anisotropy;
  double cos_rotation = std::cos(std::min(max_rotation, M_PI));
  // Edge directions may turn by the rotation plus what shear and anisotropic scale add (~0.5 rad).
  double cos_edge_turn = std::cos(std::min(max_rotation + 0.5, M_PI));

  bool plausible(const Eigen::Matrix2d& l) const {
    const double a = l(0, 0), b = l(0, 1), c = l(1, 0), d = l(1, 1);
    const double e = 0.5 * (a + d), f = 0.5 * (a - d), g = 0.5 * (c + b), h = 0.5 * (c - b);
    const double q = std::sqrt(e * e + h * h), r = std::sqrt(f * f + g * g);
    return q > r && q - r >= min_scale && q + r <= max_scale && e >= q * cos_rotation &&
           q + r <= max_anisotropy * (q - r);
  }
};

class ConsensusScorer {
 public:
  // `anchor` points at the sampler's id of the rock pair the current hypothesis grew from.
  ConsensusScorer(const RegistrationFrame& f, double gate, const Bounds& bounds, int hypothesis_budget,
                  const long* anchor)
      : a_(f.a),
        size_a_(f.size_a),
        grid_(f.b),
        gate2_(gate * gate),
        bounds_(bounds),
        anchor_(anchor),
        best_(f.b.size(), 0.0),
        stamp_(f.b.size(), 0) {
    const auto& b = f.b;
    for (const auto& s : f.size_b) {
      log_w_b_.push_back(std::log(std::max(s.x(), 1e-300)));
      log_h_b_.push_back(std::log(std::max(s.y(), 1e-300)));
    }
    // Chance that a wrong affine drops one A rock within the gate of some B rock: B's gate discs over the
    // area B spans (doubled, as rocks cluster). A consensus so large that even the best of every
    // hypothesis we could try would not reach it by chance ends the search.
    Eigen::Vector2d lo = b.empty() ? Eigen::Vector2d(0, 0) : b[0], hi = lo;
    for (const auto& q : b) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
    const double area = std::max((hi - lo).prod(), static_cast<double>(b.size()) * gate2_);
    chance_ = std::min(0.5, static_cast<double>(b.size()) * M_PI * gate2_ / area);
    budget_ = std::max(1, hypothesis_budget);
    max_count_ = static_cast<int>(std::min(a_.size(), b.size()));
  }

  // Sum over A's rocks of (closeness to a B rock) x (agreement of the mapped box's width and height with
  // that rock's), each B rock counted once. Sizes matter: two labellings of one rock agree in size (median
  // |log ratio| 0.08 on POLAR-Sim) far better than two different rocks do (0.44), which settles layouts that
  // points alone leave ambiguous. Width and height are compared apart, not just the area: a wide rock and a
  // tall one of equal area are different rocks (large tier F1 0.927 -> 0.941 and 0.944 -> 0.957, seeds 1, 2).
  double score(const Affine2& m) {
    current_ = m;
    ++scored_;
    if (!bounds_.plausible(m.leftCols<2>())) return -INFINITY;
    // Large sets: a preview on every k-th A rock first. A hypothesis whose preview (scaled up) is far below
    // the best is turned down on it; its estimate is too low to be refined or to become the best, so the
    // search is unchanged while a hypothesis costs about kPreviewRocks queries instead of n.
    if (a_.size() >= 2 * kPreviewRocks && best_refined_score_ > 0) {
      const size_t stride = a_.size() / kPreviewRocks;
      const double estimate = consensus(m, stride) * static_cast<double>(stride);
      if (estimate < kPreviewReject * best_refined_score_) return estimate;
    }
    return consensus(m, 1);
  }

  // score() for the second look, which keeps only its best few: -inf once `floor` is out of reach (exact: any
  // hypothesis scoring at least `floor` is scored in full).
  double score_above(const Affine2& m, double floor) {
    current_ = m;
    ++scored_;
    if (!bounds_.plausible(m.leftCols<2>())) return -INFINITY;
    return consensus(m, 1, floor);
  }

  // The soft consensus over every `stride`-th A rock.
  // With a `floor`: -inf as soon as the rest of A's rocks (each adds at most 1) can no longer lift it there.
  double consensus(const Affine2& m, size_t stride, double floor = -INFINITY) {
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

  // exp(-mean squared log ratio of width and height / 2 sigma^2): 1 for a mapped box of B rock j's shape.
  double shape_agreement(double mapped_w, double mapped_h, int j) const {
    if (!(mapped_w > 0) || !(mapped_h > 0)) return 1.0;
    const double lw = log_w_b_[j] - std::log(mapped_w), lh = log_h_b_[j] - std::log(mapped_h);
    return std::exp(-0.5 * (lw * lw + lh * lh) * kSizeWeight);
  }

  // Least squares on the inliers, first with a wide gate (a triple's affine extrapolates poorly far from
  // it) then the scoring gate, kept while the score improves (LO-RANSAC).
  void refine(Affine2* m, double* s) {
    improve(m, s);
    if (has_best_ && agrees_with_best(*m)) {
      confirm();
    } else if (*s > best_refined_score_) {  // a new, different best: start counting confirmations again
      best_anchors_.clear();
      confirmations_ = 0;
    }
    if (*s > best_refined_score_) {  // remember the best model and its inlier count for the stop rule
      best_refined_score_ = *s;
      best_model_ = *m;
      has_best_ = true;
      best_count_ = count_inliers(*m);
      beyond_chance_ =
          best_count_ >= 6 &&
          binomial_tail(static_cast<int>(a_.size()) - 3, chance_, best_count_ - 3) * budget_ < kChanceLevel;
      if (std::find(best_anchors_.begin(), best_anchors_.end(), *anchor_) == best_anchors_.end())
        best_anchors_.push_back(*anchor_);
    }
  }

  // The least-squares steps of refine() alone, without the search's bookkeeping (the second look uses it).
  void improve(Affine2* m, double* s) {
    auto& src = scratch_src_;
    auto& dst = scratch_dst_;
    static constexpr double kGateScale[] = {9.0, 4.0, 1.0, 1.0, 1.0};
    for (double scale : kGateScale) {
      inlier_pairs(*m, scale * gate2_, &src, &dst);
      Affine2 cand;
      if (src.size() < 3 || !affine_least_squares(src, dst, &cand)) continue;
      const double cs = score(cand);
      if (cs > *s + 1e-9) {
        *m = cand;
        *s = cs;
      }
    }
  }

  // Worth a least-squares pass: close to the best so far (after its own refinement), or early on. A
  // hypothesis that already agrees with the best one only confirms it (when it grew from another anchor).
  bool worth_refining(double s, double best) {
    if (s < 3.5) return false;  // nothing beyond its own three rocks (and a half) agrees
    if (has_best_ && agrees_with_best(current_)) {
      confirm();
      return false;
    }
    return s >= kRefineFraction * best;
  }

  bool cannot_be_beaten(double) const {
    if (best_count_ >= max_count_) return true;
    // Found again from other anchors, and enough hypotheses drawn that a triple of true pairs would likely
    // have come up if the best holds only part of them (COLMAP's rule, with the inlier ratio over the
    // smaller side): a small consensus must search longer before it is believed.
    if (confirmations_ >= kConfirmations && best_count_ >= 5 &&
        scored_ >= compute_num_trials(best_count_, max_count_, 3, 0.99, budget_))
      return true;
    // Beyond chance is the right basin, not yet the whole alignment: on a dense layout turned by a few
    // degrees the identity matches the centre only (36 of 200 rocks), so it must also hold half the smaller
    // side (synthetic 200 rocks a side: F1 0.76 -> 0.995; no change on the benchmark tiers).
    return beyond_chance_ && 2 * best_count_ >= max_count_;
  }

  // Mutually nearest (A, B) pairs within the gate after m.
  void inlier_pairs(const Affine2& m, double g2, std::vector<Eigen::Vector2d>* src, std::vector<Eigen::Vector2d>* dst) {
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

  // Robust least squares on the final consensus (Cauchy weights, scale a third of the gate): the
  // refinement above stops at the first fit that doesn't raise the score; this uses every inlier and
  // lets the few rocks labelled far off in one image pull less. It may cost a little consensus for a better
  // fit, not more than kPolishLoss of it: on nearly collinear inliers the least squares is free across their
  // line and swung a true alignment off its rocks (large tier F1, mean of seeds 0-6: 0.9701 without, 0.9721).
  void polish(Affine2* m) {
    std::vector<Eigen::Vector2d> src, dst;
    std::vector<double> w;
    const double c2 = gate2_ / 9.0;
    const Affine2 start = *m;
    const double before = score(start);
    for (int round = 0; round < 4; ++round) {
      inlier_pairs(*m, gate2_, &src, &dst);
      w.resize(src.size());
      for (size_t k = 0; k < src.size(); ++k) w[k] = 1.0 / (1.0 + (apply(*m, src[k]) - dst[k]).squaredNorm() / c2);
      Affine2 cand;
      if (src.size() < 3 || !affine_weighted_least_squares(src, dst, w, &cand) ||
          !bounds_.plausible(cand.leftCols<2>()))
        break;
      *m = cand;
    }
    if (score(*m) < before - kPolishLoss * std::max(1.0, before)) *m = start;
  }

  // Annealed soft assignment from m (EM with an outlier class, as in CPD, plus the shape agreement): every B
  // rock near a mapped A rock pulls in proportion to how close and how alike it is, so an alignment that a
  // couple of wrong nearest pairs hold in place can slide to the better one next to it, which least squares
  // on nearest pairs (refine) never leaves. Kept only when it raises the score. Small sets only (its cost is
  // A x B per step). True when it changed m.
  bool soft_refine(Affine2* m, double* s) {
    const size_t nb = grid_.size();
    if (a_.size() < 3 || nb < 3 || a_.size() * nb > kSoftMaxPairs) return false;
    const auto& b = grid_.points();
    Affine2 g = *m;
    std::vector<Eigen::Vector2d> src, dst;
    std::vector<double> w, pull(nb);
    for (double sigma : kSoftSigmas) {
      const double sig2 = sigma * sigma * gate2_;
      src.clear(), dst.clear(), w.clear();
      const double l00 = std::abs(g(0, 0)), l01 = std::abs(g(0, 1)), l10 = std::abs(g(1, 0)), l11 = std::abs(g(1, 1));
      for (size_t i = 0; i < a_.size(); ++i) {
        const Eigen::Vector2d p = apply(g, a_[i]);
        const double w_a = size_a_[i].x(), h_a = size_a_[i].y();
        const double mapped_w = l00 * w_a + l01 * h_a, mapped_h = l10 * w_a + l11 * h_a;
        // shape_agreement() with the mapped box's logarithms taken once, and one exp per pair.
        const bool sized = mapped_w > 0 && mapped_h > 0;
        const double log_w = sized ? std::log(mapped_w) : 0.0, log_h = sized ? std::log(mapped_h) : 0.0;
        double total = kSoftOutlier;
        for (size_t j = 0; j < nb; ++j) {
          const double d2 = (b[j] - p).squaredNorm();
          pull[j] = 0.0;
          if (!(d2 < 9 * sig2)) continue;
          const double lw = log_w_b_[j] - log_w, lh = log_h_b_[j] - log_h;
          pull[j] = std::exp(-0.5 * (d2 / sig2 + (sized ? (lw * lw + lh * lh) * kSizeWeight : 0.0)));
          total += pull[j];
        }
        for (size_t j = 0; j < nb; ++j)
          if (pull[j] > 1e-3 * total) src.push_back(a_[i]), dst.push_back(b[j]), w.push_back(pull[j] / total);
      }
      Affine2 cand;
      if (src.size() < 3 || !affine_weighted_least_squares(src, dst, w, &cand)) return false;
      g = cand;
    }
    // A slide, not a jump: most of the rocks m aligned stay within a gate of where m put them. From a sparse
    // small overlap the widest step can reach a different alignment altogether.
    int aligned = 0, stayed = 0;
    for (const auto& p : a_) {
      double d2 = 0;
      const Eigen::Vector2d at = apply(*m, p);
      if (grid_.nearest(at, &d2, gate2_) < 0 || !(d2 < gate2_)) continue;
      ++aligned;
      stayed += (apply(g, p) - at).squaredNorm() < gate2_;
    }
    if (2 * stayed <= aligned) return false;
    const double gs = score(g);
    if (!(gs > *s + 1e-9)) return false;
    *m = g;
    *s = gs;
    return true;
  }

  int count_inliers(const Affine2& m) {
    inlier_pairs(m, gate2_, &scratch_src_, &scratch_dst_);
    return static_cast<int>(scratch_src_.size());
  }

 private:
  const std::vector<Eigen::Vector2d>& a_;
  const std::vector<Eigen::Vector2d>& size_a_;
  std::vector<double> log_w_b_, log_h_b_;  // B's box extents, log
  PointGrid grid_;
  double gate2_;
  Bounds bounds_;
  // Two affines agree when they put most of A's rocks within a gate of each other.
  bool agrees_with_best(const Affine2& m) const {
    if (!m.allFinite()) return false;
    int close = 0;
    for (const auto& p : a_) close += (apply(m, p) - apply(best_model_, p)).squaredNorm() < gate2_;
    return 2 * close > static_cast<int>(a_.size());
  }
  void confirm() {
    if (std::find(best_anchors_.begin(), best_anchors_.end(), *anchor_) != best_anchors_.end()) return;
    best_anchors_.push_back(*anchor_);
    ++confirmations_;
  }

  const long* anchor_;
  Affine2 current_ = identity_affine(), best_model_ = identity_affine();
  bool has_best_ = false;
  // The best consensus is too large for chance over every hypothesis allowed (its own three rocks agree by
  // construction, so they don't count).
  bool beyond_chance_ = false;
  int confirmations_ = 0;
  std::vector<long> best_anchors_;
  double chance_ = 0.5;
  int budget_ = 1, max_count_ = 0, best_count_ = 0, scored_ = 0;
  double best_refined_score_ = -INFINITY;
  std::vector<double> best_;
  std::vector<unsigned> stamp_;
  std::vector<std::pair<int, double>> claim_;
  std::vector<Eigen::Vector2d> scratch_src_, scratch_dst_;  // reused by improve() and count_inliers()
  unsigned epoch_ = 0;
};

// The placements most rock pairs agree on under the linear part `linear` (top_translations), scored: the best of
// those that differ from `best` (the rivals a small overlap allows, a patch of rocks that fits in several
// places) and the best of those that agree with it (the same alignment, sometimes fitted better than the search
// left it: least squares cannot refine rocks on a line). Scores 0 and models untouched when there is none.
// `refine`: each is first fitted to its own rocks, for cpd, which scores no rival of its own (the consensus
// search has refined its rivals already and scores these as they come).
struct ShiftedPlacements {
  double rival = 0, same = 0;
  Affine2 rival_model = identity_affine(), same_model = identity_affine();
};
inline ShiftedPlacements shifted_placements(ConsensusScorer* scorer, const SearchRecorder& recorder,
                                            const RegistrationFrame& f, const Affine2& best,
                                            const Eigen::Matrix2d& linear, double gate, bool refine) {
  ShiftedPlacements out;
  for (const auto& t : top_translations(linear, f.a, f.b, 2 * gate, 4)) {
    Affine2 m;
    m.leftCols<2>() = linear;
    m.col(2) = t;
    double s = scorer->score(m);
    if (refine) scorer->improve(&m, &s);
    const bool same = recorder.agree(m, best);
    double& kept = same ? out.same : out.rival;
    if (s > kept) kept = s, (same ? out.same_model : out.rival_model) = m;
  }
  return out;
}

}  // namespace ipd::detail
