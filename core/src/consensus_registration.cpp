// The default registration: consensus of plausible affines from guided hypotheses.
//
// Cheap hypotheses first (identity, the most voted translations), then triples drawn from local
// neighbourhoods (a rock and two of its nearest neighbours on each side), filtered by what a camera
// misalignment can do (bounded scale, shear and rotation, consistent box sizes) before any scoring.
// Each hypothesis is scored by a soft inlier count with every B rock claimed at most once, so shrinking A
// onto a few rocks earns nothing; a new best is refined by least squares on its inliers (LO-RANSAC); the
// search stops once the consensus cannot reasonably be beaten. Rocks are then paired by an optimal (Hungarian)
// assignment on the IoU of the aligned boxes.
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "ipd/affine_estimator.h"
#include "ipd/pairing.h"
#include "ipd/point_grid.h"
#include "consensus_search.h"
#include "registration_frame.h"
#include "registration_recorder.h"

namespace ipd::detail {

namespace {

constexpr int kNeighboursA = 5;  // a rock's neighbours used to form triples on side A
constexpr int kNeighboursB = 8;  // more on side B: some of A's neighbours may be hidden or displaced there
constexpr double kBoundSlackScale = 1.25, kBoundSlackDeg = 15.0;
// A consensus that chance would give less often than this, over every hypothesis allowed, ends the search.
constexpr double kChanceLevel = 0.05;
constexpr double kSizeSigma = 0.25, kSizeWeight = 1.0 / (2 * kSizeSigma * kSizeSigma);  // log size ratio
constexpr double kMaxLogSizeGap = 1.1;
constexpr double kRefineFraction = 0.5;
// Sets of at least twice this many rocks preview each hypothesis on this many; previews scaled up below this
// fraction of the best score end there (half the refinement threshold: room for the preview's noise).
constexpr size_t kPreviewRocks = 64;
constexpr double kPreviewReject = 0.25;
// The best consensus found again from this many other anchor rocks ends the search: the true alignment
// attracts hypotheses from every rock that kept its neighbours, wrong ones rarely from two.
constexpr int kConfirmations = 2;

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
      : a_(f.a), size_a_(f.size_a), grid_(f.b), gate2_(gate * gate), bounds_(bounds), anchor_(anchor),
        best_(f.b.size(), 0.0), stamp_(f.b.size(), 0) {
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

  // The soft consensus over every `stride`-th A rock.
  double consensus(const Affine2& m, size_t stride) {
    ++epoch_;
    const double l00 = std::abs(m(0, 0)), l01 = std::abs(m(0, 1)), l10 = std::abs(m(1, 0)), l11 = std::abs(m(1, 1));
    double total = 0;
    for (size_t i = 0; i < a_.size(); i += stride) {
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
    std::vector<Eigen::Vector2d> src, dst;
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
      beyond_chance_ = best_count_ >= 6 &&
                       binomial_tail(static_cast<int>(a_.size()) - 3, chance_, best_count_ - 3) * budget_ < kChanceLevel;
      if (std::find(best_anchors_.begin(), best_anchors_.end(), *anchor_) == best_anchors_.end())
        best_anchors_.push_back(*anchor_);
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
  void inlier_pairs(const Affine2& m, double g2, std::vector<Eigen::Vector2d>* src,
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

  // Robust least squares on the final consensus (Cauchy weights, scale a third of the gate): the
  // refinement above stops at the first fit that doesn't raise the score; this uses every inlier and
  // lets the few rocks labelled far off in one image pull less.
  void polish(Affine2* m) {
    std::vector<Eigen::Vector2d> src, dst;
    std::vector<double> w;
    const double c2 = gate2_ / 9.0;
    for (int round = 0; round < 4; ++round) {
      inlier_pairs(*m, gate2_, &src, &dst);
      w.resize(src.size());
      for (size_t k = 0; k < src.size(); ++k) w[k] = 1.0 / (1.0 + (apply(*m, src[k]) - dst[k]).squaredNorm() / c2);
      Affine2 cand;
      if (src.size() < 3 || !affine_weighted_least_squares(src, dst, w, &cand) || !bounds_.plausible(cand.leftCols<2>()))
        return;
      *m = cand;
    }
  }

  int count_inliers(const Affine2& m) {
    std::vector<Eigen::Vector2d> s, d;
    inlier_pairs(m, gate2_, &s, &d);
    return static_cast<int>(s.size());
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
  unsigned epoch_ = 0;
};

// Proposes hypotheses as affines directly (estimator = identity pass-through) so that the cheap ones and
// the triple ones share one loop, one budget and one stopping rule.
class GuidedSampler {
 public:
  GuidedSampler(const RegistrationFrame& f, const Bounds& bounds, double gate, std::uint64_t seed, bool record)
      : f_(f), bounds_(bounds), gate2_(gate * gate), min_det_(bounds.min_scale * bounds.min_scale),
        max_det_(bounds.max_scale * bounds.max_scale), record_(record) {
    // 1. identity in image coordinates
    queue_.push_back(f.from_image(identity_affine()));
    // 2. the most voted translations (identity linear part), votes binned at the gate size
    vote_translations(gate);
    // 3. neighbourhood triples, rocks of A in a seeded order
    // Small sets are cheap to search widely, and need it: fewer rocks keep fewer neighbours in common.
    small_ = f.a.size() <= 16 && f.b.size() <= 16;
    nn_a_ = nearest_neighbours(f.a, small_ ? kNeighboursA + 2 : kNeighboursA);
    // A side that few rocks are left on (the rest out of view): every one of them may be a neighbour.
    nn_b_ = nearest_neighbours(f.b, f.b.size() <= 12 ? static_cast<int>(f.b.size()) : small_ ? kNeighboursB + 3 : kNeighboursB);
    order_a_.resize(f.a.size());
    std::iota(order_a_.begin(), order_a_.end(), 0);
    Rng rng(seed);
    for (size_t k = order_a_.size(); k > 1; --k) std::swap(order_a_[k - 1], order_a_[rng.below(static_cast<int>(k))]);
    // For each A rock, B rocks in order of size agreement (after the sets' median size ratio): a rock's
    // partner is usually among the first few, so confirmations come after a handful of expansions.
    auto log_sizes = [](const std::vector<Eigen::Vector2d>& sz) {
      std::vector<double> l;
      for (const auto& s : sz) l.push_back(0.5 * std::log(std::max(s.x() * s.y(), 1e-300)));
      return l;
    };
    log_a_ = log_sizes(f.size_a);
    log_b_ = log_sizes(f.size_b);
    auto median = [](std::vector<double> v) {
      if (v.empty()) return 0.0;
      std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
      return v[v.size() / 2];
    };
    size_offset_ = median(log_b_) - median(log_a_);
    const size_t m = f.b.size();
    first_window_ = std::min(m, std::max<size_t>(6, (m + 2) / 3));
    b_by_size_.resize(f.a.size());  // rows sorted when their A rock is first expanded (most never are)
  }

  const std::vector<int>& b_by_size(int i) {
    auto& row = b_by_size_[i];
    if (row.empty() && !f_.b.empty()) {
      row.resize(f_.b.size());
      std::iota(row.begin(), row.end(), 0);
      const double want = log_a_[i] + size_offset_;
      std::stable_sort(row.begin(), row.end(),
                       [&](int x, int y) { return std::abs(log_b_[x] - want) < std::abs(log_b_[y] - want); });
    }
    return row;
  }

  bool next(Affine2* out) {
    has_sample = false;
    if (q_pos_ < queue_.size()) {
      anchor = -1 - static_cast<long>(q_pos_);
      *out = queue_[q_pos_++];
      return true;
    }
    // Triples that two more neighbours confirm come first, anchor by anchor: in a first pass each A rock
    // meets the third of B closest to it in size, in a second pass the rest. Triples only one more
    // neighbour confirms are kept aside until both passes are done.
    while (pending_.empty()) {
      if (pass_ >= 2) {
        if (deferred_pos_ >= deferred_.size() && !unsupported_.empty()) {
          // Last, for small sets: triples nothing else confirms (an overlap of three or four rocks).
          deferred_.insert(deferred_.end(), unsupported_.begin(), unsupported_.end());
          deferred_samples_.insert(deferred_samples_.end(), unsupported_samples_.begin(), unsupported_samples_.end());
          unsupported_.clear();
        }
        if (deferred_pos_ >= deferred_.size()) return false;
        anchor = deferred_[deferred_pos_].first;
        if (record_) sample = deferred_samples_[deferred_pos_], has_sample = true;
        *out = deferred_[deferred_pos_++].second;
        return true;
      }
      const size_t lo = pass_ == 0 ? 0 : first_window_, hi = pass_ == 0 ? first_window_ : f_.b.size();
      if (jb_ < lo) jb_ = lo;
      if (ia_ >= f_.a.size() || lo >= hi) {
        ++pass_;
        ia_ = 0;
        jb_ = 0;
        continue;
      }
      const int i = order_a_[ia_];
      pending_anchor_ = i;
      expand(i, b_by_size(i)[jb_]);
      if (++jb_ >= hi) jb_ = lo, ++ia_;
    }
    anchor = pending_anchor_;  // rock of A the hypothesis grew from; a wrong match rarely repeats
    *out = pending_.back();
    pending_.pop_back();
    if (record_) sample = pending_samples_.back(), has_sample = true, pending_samples_.pop_back();
    return true;
  }

  long anchor = -1;
  // The current hypothesis' rocks (record mode): A's three then B's three, in matching order.
  std::array<int, 6> sample{};
  bool has_sample = false;

 private:
  void vote_translations(double gate) {
    const Affine2 id = f_.from_image(identity_affine());
    if (f_.a.size() * f_.b.size() > 250000) return;  // huge sets: the triples alone are cheaper
    for (const auto& t : top_translations(id.leftCols<2>(), f_.a, f_.b, gate, 3)) {
      Affine2 m = id;
      m.col(2) = t;
      queue_.push_back(m);
    }
  }

  // All plausible triples anchored at A rock i and B rock j: pairs of compatible neighbour edges, each
  // kept only if another neighbour of i lands near a neighbour of j (local verification is far cheaper
  // than scoring the whole set).
  void expand(int i, int j) {
    if (!sizes_agree(i, j)) return;
    const auto& ni = nn_a_[i];
    const auto& nj = nn_b_[j];
    edges_.clear();
    for (size_t u = 0; u < ni.size(); ++u)
      for (size_t x = 0; x < nj.size(); ++x)
        if (sizes_agree(ni[u], nj[x]) && edge_plausible(f_.a[ni[u]] - f_.a[i], f_.b[nj[x]] - f_.b[j]))
          edges_.emplace_back(u, x);
    for (size_t e1 = 0; e1 < edges_.size(); ++e1)
      for (size_t e2 = e1 + 1; e2 < edges_.size(); ++e2) {
        const auto [u1, x1] = edges_[e1];
        const auto [u2, x2] = edges_[e2];
        if (u1 == u2 || x1 == x2) continue;
        const Eigen::Vector2d src[3] = {f_.a[i], f_.a[ni[u1]], f_.a[ni[u2]]};
        const Eigen::Vector2d dst[3] = {f_.b[j], f_.b[nj[x1]], f_.b[nj[x2]]};
        // Before solving: the triangle's orientation must survive (no reflection) and its area ratio is the
        // affine's determinant, bounded by the squared scale bounds. Two cross products reject most pairs.
        const Eigen::Vector2d a1 = src[1] - src[0], a2 = src[2] - src[0], b1 = dst[1] - dst[0], b2 = dst[2] - dst[0];
        const double area_a = a1.x() * a2.y() - a1.y() * a2.x(), area_b = b1.x() * b2.y() - b1.y() * b2.x();
        if (!(area_a * area_b > 0)) continue;
        const double det = area_b / area_a;
        if (det < min_det_ || det > max_det_) continue;
        Affine2 m;
        if (!affine_from_three(src, dst, &m) || !bounds_.plausible(m.leftCols<2>())) continue;
        const int support = ni.size() >= 4 ? local_support(m, i, j, u1, u2) : 2;
        if (support >= 2) pending_.push_back(m);
        else if (support == 1) deferred_.emplace_back(i, m);
        else if (small_) unsupported_.emplace_back(i, m);
        if (record_ && (support >= 1 || small_))
          (support >= 2 ? pending_samples_ : support == 1 ? deferred_samples_ : unsupported_samples_)
              .push_back({i, ni[u1], ni[u2], j, nj[x1], nj[x2]});
      }
    std::reverse(pending_.begin(), pending_.end());  // pop_back hands them out in generation order
    std::reverse(pending_samples_.begin(), pending_samples_.end());
  }

  // How many other neighbours of i land within the gate of a neighbour of j (counted up to 2).
  int local_support(const Affine2& m, int i, int j, size_t u1, size_t u2) const {
    const auto& ni = nn_a_[i];
    const auto& nj = nn_b_[j];
    int support = 0;
    for (size_t u = 0; u < ni.size() && support < 2; ++u) {
      if (u == u1 || u == u2) continue;
      const Eigen::Vector2d p = apply(m, f_.a[ni[u]]);
      for (int x : nj)
        if ((f_.b[x] - p).squaredNorm() < gate2_) {
          ++support;
          break;
        }
    }
    return support;
  }

  // An edge of A can only map onto an edge of B whose length ratio lies within the scale bounds and whose
  // direction turned by at most the rotation bound plus what shear and anisotropic scale can add.
  bool edge_plausible(const Eigen::Vector2d& ea, const Eigen::Vector2d& eb) const {
    const double la = ea.norm(), lb = eb.norm();
    if (!(la > 0) || !(lb > 0)) return false;
    const double ratio = lb / la;
    if (ratio < bounds_.min_scale || ratio > bounds_.max_scale) return false;
    return ea.dot(eb) >= bounds_.cos_edge_turn * la * lb;
  }

  // Two labellings of one rock differ in log size by < 0.56 in 99% of POLAR-Sim pairs; 1.1 leaves room for
  // the box growth a rotation causes and for the offset's error: the sets' median sizes differ by more than
  // the scale when one side keeps only part of the rocks (clipped, or missing its small ones). 0.8 lost the
  // true triples of such cases (large tier F1 0.924 -> 0.936 with it, 100 cases).
  bool sizes_agree(int i, int j) const { return std::abs(log_b_[j] - log_a_[i] - size_offset_) < kMaxLogSizeGap; }

  const RegistrationFrame& f_;
  Bounds bounds_;
  double gate2_;
  double min_det_, max_det_;  // the determinant lies between the squared singular-value bounds
  std::vector<Affine2> queue_, pending_;
  bool record_;
  bool small_ = false;
  std::vector<std::pair<long, Affine2>> deferred_, unsupported_;
  std::vector<std::array<int, 6>> pending_samples_, deferred_samples_, unsupported_samples_;  // record mode only
  size_t deferred_pos_ = 0;
  size_t q_pos_ = 0;
  std::vector<std::vector<int>> nn_a_, nn_b_;
  std::vector<int> order_a_;
  std::vector<std::vector<int>> b_by_size_;  // per A rock, B rocks by size agreement (filled lazily)
  std::vector<double> log_a_, log_b_;
  double size_offset_ = 0;
  std::vector<std::pair<size_t, size_t>> edges_;
  size_t ia_ = 0, jb_ = 0, first_window_ = 0;
  int pass_ = 0;
  long pending_anchor_ = 0;
};

struct PassThroughEstimator {
  void estimate(const Affine2& m, std::vector<Affine2>* out) const { out->push_back(m); }
};

}  // namespace

MethodOutcome register_consensus(const RegistrationFrame& f, const std::vector<Box>& boxes_a,
                                 const std::vector<Box>& boxes_b, const RegistrationOptions& o) {
  MethodOutcome out;
  // A triple of nearby rocks carries their labelling noise into its affine (several degrees, tens of
  // percent of scale), so hypotheses are held to the user's bounds with that much slack.
  const Bounds bounds{o.min_scale / kBoundSlackScale, o.max_scale * kBoundSlackScale,
                      (o.max_rotation_deg + kBoundSlackDeg) * M_PI / 180.0, o.max_anisotropy};
  // The gate: 0.3 of the typical spacing of B's rocks, within [0.02, 0.2] of the layout's spread, all in
  // normalised units so that scaling or shifting every coordinate changes nothing.
  double gate = o.inlier_gate / f.spread;
  if (!(gate > 0)) gate = std::clamp(0.3 * median_nn_distance(f.b), 0.02, 0.2);
  out.affine_normalised = f.from_image(identity_affine());
  if (!f.a.empty() && !f.b.empty()) {
    GuidedSampler sampler(f, bounds, gate, o.seed, o.record_trace);
    ConsensusScorer scorer(f, gate, bounds, o.max_trials, &sampler.anchor);
    PassThroughEstimator estimator;
    RobustLoopOptions lo;
    lo.max_trials = o.max_trials;
    lo.time_budget_ms = o.time_budget_ms;
    lo.max_work = work_budget(o, f.a.size(), f.b.size());
    lo.work_per_model = static_cast<double>(f.a.size());  // one nearest-neighbour query per A rock
    auto sample_of = [&](const Affine2&, std::vector<int>* sa, std::vector<int>* sb) {
      if (!sampler.has_sample) return;  // identity and voted translations are not built from rocks
      sa->assign(sampler.sample.begin(), sampler.sample.begin() + 3);
      sb->assign(sampler.sample.begin() + 3, sampler.sample.end());
    };
    SearchRecorder recorder(f, gate, o.record_trace, [](double s) { return s; }, sample_of);
    const auto r = run_robust_loop<Affine2, Affine2>(sampler, estimator, scorer, lo, recorder);
    out.trials = r.trials;
    out.hypotheses = r.hypotheses;
    out.work = r.work;
    out.stop = r.stop;
    if (r.found && std::isfinite(r.best_score)) {
      out.affine_normalised = r.best;
      out.score = r.best_score;
      scorer.polish(&out.affine_normalised);
      recorder.add_step(TraceStepKind::kPolish, out.affine_normalised, out.score, out.score, false);
      // The search stops as soon as its best can't be beaten, often before a rival is scored. Shifted
      // placements are the rivals a small overlap allows (a patch of rocks that fits in several places), so
      // the translations most rock pairs agree on under the best's linear part are scored too.
      double rival = recorder.rival_score();
      for (const auto& t : top_translations(r.best.leftCols<2>(), f.a, f.b, 2 * gate, 4)) {
        Affine2 m = r.best;
        m.col(2) = t;
        if (!recorder.agree(m, r.best)) rival = std::max(rival, scorer.score(m));
      }
      out.confidence = confidence_from_scores(r.best_score, rival);
    } else {
      out.note = "no plausible affine found: identity used";
      out.confidence = 0;
    }
    out.ambiguous = out.confidence < kAmbiguousBelow;
    out.trace = recorder.take_trace(describe_stop(r.stop, r.trials, r.hypotheses, r.work, lo.max_work));
    out.inliers = scorer.count_inliers(out.affine_normalised);
    if (f.a.size() < 3 || f.b.size() < 3) out.note = "fewer than 3 rocks on a side: translation at most";
  } else {
    out.stop = StopReason::kTooFewPoints;
    out.note = "a side has no rocks: nothing to register";
  }
  out.pairs = pair_by_aligned_iou(f.to_image(out.affine_normalised), boxes_a, boxes_b, o.min_pair_iou);
  return out;
}

}  // namespace ipd::detail
