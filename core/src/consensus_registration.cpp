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
#include <cmath>
#include <numeric>

#include "ipd/affine_estimator.h"
#include "ipd/pairing.h"
#include "ipd/point_grid.h"
#include "registration_frame.h"

namespace ipd::detail {

namespace {

constexpr int kNeighboursA = 4;  // a rock's neighbours used to form triples on side A
constexpr int kNeighboursB = 6;  // more on side B: some of A's neighbours may be hidden or displaced there
constexpr double kStopFraction = 0.8;  // consensus over this share of the smaller set ends the search

// Singular values, rotation angle and orientation of a 2x2 linear map, in closed form.
struct LinearShape {
  double s_max = 0, s_min = 0, rotation = 0, det = 0;
};
LinearShape shape_of(const Eigen::Matrix2d& l) {
  LinearShape s;
  const double a = l(0, 0), b = l(0, 1), c = l(1, 0), d = l(1, 1);
  const double e = 0.5 * (a + d), f = 0.5 * (a - d), g = 0.5 * (c + b), h = 0.5 * (c - b);
  const double q = std::hypot(e, h), r = std::hypot(f, g);
  s.s_max = q + r;
  s.s_min = std::abs(q - r);
  s.det = a * d - b * c;
  s.rotation = std::atan2(h, e);  // rotation of the closest similarity
  return s;
}

struct Bounds {
  double min_scale, max_scale, max_rotation, max_size_ratio;
  bool plausible(const Eigen::Matrix2d& l) const {
    const LinearShape s = shape_of(l);
    return s.det > 0 && s.s_min >= min_scale && s.s_max <= max_scale && std::abs(s.rotation) <= max_rotation;
  }
};

std::vector<std::vector<int>> nearest_neighbours(const std::vector<Eigen::Vector2d>& p, int k) {
  const int n = static_cast<int>(p.size());
  std::vector<std::vector<int>> nn(n);
  std::vector<std::pair<double, int>> d;
  for (int i = 0; i < n; ++i) {
    d.clear();
    for (int j = 0; j < n; ++j)
      if (j != i) d.emplace_back((p[j] - p[i]).squaredNorm(), j);
    const int kk = std::min<int>(k, static_cast<int>(d.size()));
    std::partial_sort(d.begin(), d.begin() + kk, d.end());
    for (int t = 0; t < kk; ++t)
      if (d[t].first > 0) nn[i].push_back(d[t].second);  // a duplicate of the rock itself spans nothing
  }
  return nn;
}

double median_nn_distance(const std::vector<Eigen::Vector2d>& p) {
  if (p.size() < 2) return 0;
  const PointGrid g(p);
  std::vector<double> d;
  std::vector<int> near;
  for (size_t i = 0; i < p.size(); ++i) {
    // nearest other point: search the grid for the two closest and skip itself
    double best = INFINITY;
    for (double r = 1e-9; best == INFINITY && r < 1e6; r *= 4) {
      g.within(p[i], r, &near);
      for (int j : near)
        if (j != static_cast<int>(i)) best = std::min(best, (p[j] - p[i]).norm());
      if (best == INFINITY && near.size() > 64) break;  // many duplicates: zero spacing
    }
    if (best == INFINITY) best = 0;
    d.push_back(best);
  }
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2];
}

class ConsensusScorer {
 public:
  ConsensusScorer(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b, double gate,
                  const Bounds& bounds)
      : a_(a), grid_(b), gate2_(gate * gate), bounds_(bounds), best_(b.size(), 0.0), stamp_(b.size(), 0) {
    target_ = std::max(3.0, kStopFraction * static_cast<double>(std::min(a.size(), b.size())));
  }

  double score(const Affine2& m) {
    if (!bounds_.plausible(m.leftCols<2>())) return -INFINITY;
    ++epoch_;
    double total = 0;
    for (const auto& p : a_) {
      double d2 = 0;
      const int j = grid_.nearest(apply(m, p), &d2);
      if (j < 0 || !(d2 < gate2_)) continue;
      const double w = 1.0 - d2 / gate2_;
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

  // Least squares on the inliers with a widening-then-tightening gate, kept while the score improves.
  void refine(Affine2* m, double* s) {
    std::vector<Eigen::Vector2d> src, dst;
    for (int round = 0; round < 4; ++round) {
      const double g2 = round == 0 ? 4.0 * gate2_ : gate2_;
      inlier_pairs(*m, g2, &src, &dst);
      Affine2 cand;
      if (src.size() < 3 || !affine_least_squares(src, dst, &cand)) return;
      const double cs = score(cand);
      if (!(cs > *s + 1e-9)) return;
      *m = cand;
      *s = cs;
    }
  }

  bool cannot_be_beaten(double s) const { return s >= target_; }
  double success_probability(double) const { return 0.0; }

  // Mutually nearest (A, B) pairs within the gate after m.
  void inlier_pairs(const Affine2& m, double g2, std::vector<Eigen::Vector2d>* src,
                    std::vector<Eigen::Vector2d>* dst) {
    src->clear();
    dst->clear();
    ++epoch_;
    std::vector<std::pair<int, double>> claim(grid_.size(), {-1, INFINITY});
    for (size_t i = 0; i < a_.size(); ++i) {
      double d2 = 0;
      const int j = grid_.nearest(apply(m, a_[i]), &d2);
      if (j >= 0 && d2 < g2 && d2 < claim[j].second) claim[j] = {static_cast<int>(i), d2};
    }
    for (size_t j = 0; j < claim.size(); ++j) {
      if (claim[j].first < 0) continue;
      src->push_back(a_[claim[j].first]);
      dst->push_back(grid_.points()[j]);
    }
  }

  int count_inliers(const Affine2& m) {
    std::vector<Eigen::Vector2d> s, d;
    inlier_pairs(m, gate2_, &s, &d);
    return static_cast<int>(s.size());
  }

 private:
  const std::vector<Eigen::Vector2d>& a_;
  PointGrid grid_;
  double gate2_;
  Bounds bounds_;
  double target_ = 3;
  std::vector<double> best_;
  std::vector<unsigned> stamp_;
  unsigned epoch_ = 0;
};

// Proposes hypotheses as affines directly (estimator = identity pass-through) so that the cheap ones and
// the triple ones share one loop, one budget and one stopping rule.
class GuidedSampler {
 public:
  GuidedSampler(const RegistrationFrame& f, const Bounds& bounds, double gate, std::uint64_t seed)
      : f_(f), bounds_(bounds) {
    // 1. identity in image coordinates
    queue_.push_back(f.from_image(identity_affine()));
    // 2. the most voted translations (identity linear part), votes binned at the gate size
    vote_translations(gate);
    // 3. neighbourhood triples, rocks of A in a seeded order
    nn_a_ = nearest_neighbours(f.a, kNeighboursA);
    nn_b_ = nearest_neighbours(f.b, kNeighboursB);
    order_a_.resize(f.a.size());
    std::iota(order_a_.begin(), order_a_.end(), 0);
    Rng rng(seed);
    for (size_t k = order_a_.size(); k > 1; --k) std::swap(order_a_[k - 1], order_a_[rng.below(static_cast<int>(k))]);
    for (int u = 0; u < kNeighboursA; ++u)
      for (int v = u + 1; v < kNeighboursA; ++v) configs_.emplace_back(u, v);
    std::stable_sort(configs_.begin(), configs_.end(),
                     [](auto x, auto y) { return x.first + x.second < y.first + y.second; });
  }

  bool next(Affine2* out) {
    if (q_pos_ < queue_.size()) {
      *out = queue_[q_pos_++];
      return true;
    }
    return next_triple(out);
  }

 private:
  void vote_translations(double gate) {
    const Eigen::Matrix2d lin = f_.from_image(identity_affine()).leftCols<2>();
    const Eigen::Vector2d t0 = f_.from_image(identity_affine()).col(2);
    struct Bin {
      long long key;
      int count;
      Eigen::Vector2d sum;
    };
    std::vector<Bin> bins;
    std::vector<std::pair<long long, Eigen::Vector2d>> votes;
    if (f_.a.size() * f_.b.size() > 250000) return;  // huge sets: the triples alone are cheaper
    for (const auto& p : f_.a)
      for (const auto& q : f_.b) {
        const Eigen::Vector2d t = q - lin * p;
        const long long kx = static_cast<long long>(std::floor(t.x() / gate));
        const long long ky = static_cast<long long>(std::floor(t.y() / gate));
        votes.emplace_back((kx << 32) ^ (ky & 0xffffffffLL), t);
      }
    std::sort(votes.begin(), votes.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    for (size_t k = 0; k < votes.size();) {
      size_t e = k;
      Eigen::Vector2d sum(0, 0);
      while (e < votes.size() && votes[e].first == votes[k].first) sum += votes[e++].second;
      bins.push_back({votes[k].first, static_cast<int>(e - k), sum});
      k = e;
    }
    std::partial_sort(bins.begin(), bins.begin() + std::min<size_t>(3, bins.size()), bins.end(),
                      [](const Bin& x, const Bin& y) { return x.count > y.count; });
    for (size_t k = 0; k < std::min<size_t>(3, bins.size()); ++k) {
      if (bins[k].count < 2) break;
      Affine2 m;
      m.leftCols<2>() = lin;
      m.col(2) = bins[k].sum / bins[k].count;
      if ((m.col(2) - t0).norm() > 1e-12) queue_.push_back(m);
    }
  }

  bool next_triple(Affine2* out) {
    const int na = static_cast<int>(f_.a.size()), nb = static_cast<int>(f_.b.size());
    for (; cfg_ < configs_.size(); ++cfg_, ia_ = 0) {
      const auto [u, v] = configs_[cfg_];
      for (; ia_ < na; ++ia_, jb_ = 0, xb_ = 0) {
        const int i = order_a_[ia_];
        const auto& ni = nn_a_[i];
        if (static_cast<int>(ni.size()) <= v) continue;
        const Eigen::Vector2d p0 = f_.a[i], p1 = f_.a[ni[u]], p2 = f_.a[ni[v]];
        if (triangle_conditioning(p0, p1, p2) < kMinTriangleConditioning) continue;
        for (; jb_ < nb; ++jb_, xb_ = 0) {
          if (!sizes_compatible(i, jb_)) continue;
          const auto& nj = nn_b_[jb_];
          const int kb = static_cast<int>(nj.size());
          for (; xb_ < kb * kb; ++xb_) {
            const int x = xb_ / kb, y = xb_ % kb;
            if (x == y) continue;
            const Eigen::Vector2d src[3] = {p0, p1, p2};
            const Eigen::Vector2d dst[3] = {f_.b[jb_], f_.b[nj[x]], f_.b[nj[y]]};
            if (!edge_plausible(src[1] - src[0], dst[1] - dst[0])) continue;
            if (!edge_plausible(src[2] - src[0], dst[2] - dst[0])) continue;
            Affine2 m;
            if (!affine_from_three(src, dst, &m) || !bounds_.plausible(m.leftCols<2>())) continue;
            ++xb_;
            *out = m;
            return true;
          }
        }
      }
    }
    return false;
  }

  // An edge of A can only map onto an edge of B whose length ratio lies within the scale bounds and whose
  // direction turned by at most the rotation bound plus what shear can add.
  bool edge_plausible(const Eigen::Vector2d& ea, const Eigen::Vector2d& eb) const {
    const double la = ea.norm(), lb = eb.norm();
    if (!(la > 0) || !(lb > 0)) return false;
    const double ratio = lb / la;
    if (ratio < bounds_.min_scale || ratio > bounds_.max_scale) return false;
    const double cosang = ea.dot(eb) / (la * lb);
    return cosang >= std::cos(std::min(M_PI, bounds_.max_rotation + 0.5));
  }

  bool sizes_compatible(int i, int j) const {
    const double sa = std::sqrt(f_.size_a[i].x() * f_.size_a[i].y());
    const double sb = std::sqrt(f_.size_b[j].x() * f_.size_b[j].y());
    if (!(sa > 0) || !(sb > 0)) return true;
    const double r = sb / sa;
    return r >= bounds_.min_scale / bounds_.max_size_ratio && r <= bounds_.max_scale * bounds_.max_size_ratio;
  }

  const RegistrationFrame& f_;
  Bounds bounds_;
  std::vector<Affine2> queue_;
  size_t q_pos_ = 0;
  std::vector<std::vector<int>> nn_a_, nn_b_;
  std::vector<int> order_a_;
  std::vector<std::pair<int, int>> configs_;
  size_t cfg_ = 0;
  int ia_ = 0, jb_ = 0, xb_ = 0;
};

struct PassThroughEstimator {
  void estimate(const Affine2& m, std::vector<Affine2>* out) const { out->push_back(m); }
};

}  // namespace

MethodOutcome register_consensus(const RegistrationFrame& f, const std::vector<Box>& boxes_a,
                                 const std::vector<Box>& boxes_b, const RegistrationOptions& o) {
  MethodOutcome out;
  const Bounds bounds{o.min_scale, o.max_scale, o.max_rotation_deg * M_PI / 180.0, 2.5};
  // The gate: a third of the typical spacing of B's rocks, within [0.5%, 5%] of the image width.
  double gate = o.inlier_gate / f.spread;
  if (!(gate > 0)) {
    const double spacing = median_nn_distance(f.b) * f.spread;
    gate = std::clamp(0.3 * spacing, 0.005, 0.05) / f.spread;
  }
  out.affine_normalised = f.from_image(identity_affine());
  if (!f.a.empty() && !f.b.empty()) {
    ConsensusScorer scorer(f.a, f.b, gate, bounds);
    GuidedSampler sampler(f, bounds, gate, o.seed);
    PassThroughEstimator estimator;
    RobustLoopOptions lo;
    lo.max_trials = o.max_trials;
    lo.time_budget_ms = o.time_budget_ms;
    const auto r = run_robust_loop<Affine2, Affine2>(sampler, estimator, scorer, lo);
    out.trials = r.trials;
    out.hypotheses = r.hypotheses;
    out.stop = r.stop;
    if (r.found && std::isfinite(r.best_score)) {
      out.affine_normalised = r.best;
      out.score = r.best_score;
    } else {
      out.note = "no plausible affine found: identity used";
    }
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
