// The paper's registration, as it describes it: random triples on each side, all six orderings, an exact
// affine per ordering, scored by the mean nearest-neighbour distance; best of K; then mutual nearest
// neighbours within a gate become pairs.
#include <chrono>
#include <cmath>

#include "core/geometry/affine_estimator.h"
#include "core/geometry/point_grid.h"
#include "core/registration/pairing.h"
#include "core/registration/registration_frame.h"
#include "core/registration/registration_recorder.h"

namespace ipd::detail {

namespace {

struct RandomTripleSampler {
  const std::vector<Eigen::Vector2d>& a;
  const std::vector<Eigen::Vector2d>& b;
  Rng rng;
  int ia[3] = {0, 0, 0}, ib[3] = {0, 0, 0};  // the current sample's rocks

  static void pick3(Rng& rng, int n, int out[3]) {
    out[0] = rng.below(n);
    do out[1] = rng.below(n);
    while (out[1] == out[0]);
    do out[2] = rng.below(n);
    while (out[2] == out[0] || out[2] == out[1]);
  }
  bool next(TriplePair* s) {
    pick3(rng, static_cast<int>(a.size()), ia);
    pick3(rng, static_cast<int>(b.size()), ib);
    for (int k = 0; k < 3; ++k) {
      s->src[k] = a[ia[k]];
      s->dst[k] = b[ib[k]];
    }
    return true;
  }
};

// Mean distances (in units of the layout's spread) below this are exact fits: the affine solve leaves ~1e-17.
constexpr double kExact = 1e-9;

// Higher is better, so the score is minus the mean nearest-neighbour distance of transformed A to B.
struct MeanNearestScorer {
  const std::vector<Eigen::Vector2d>& a;
  const PointGrid& grid_b;
  const Deadline& deadline;  // read every 16 rocks: a wild model's queries can each scan many grid rings
  double score(const Affine2& m) const {
    const double n = static_cast<double>(a.size());
    // A model scoring below the best distinct rival changes nothing: neither the best, nor the rival, nor
    // the confidence. Once its partial sum proves that, it is dropped (-inf, as a non-finite score is), and
    // each nearest-rock search stops at the distance left: on a dense layout a wild affine throws rocks far
    // outside, where each unbounded search would scan ring after ring of the grid. The 1e-9 margin keeps
    // rounding from dropping a model that ties the rival. A recorded trace shows every score: no dropping.
    const double rival = recorder && !recorder->recording() ? recorder->rival_score() : -INFINITY;
    const double drop_at = std::isfinite(rival) ? -rival * n * (1 + 1e-9) : INFINITY;
    double sum = 0;
    for (size_t k = 0; k < a.size(); ++k) {
      const Eigen::Vector2d& p = a[k];
      // Cut short by the budget: dropped like a model that cannot matter (the search stops before its next sample).
      if (deadline.has_budget() && (k & 15) == 15 && deadline.passed()) return -INFINITY;
      double d2 = 0;
      const double left = drop_at - sum;
      if (grid_b.nearest(apply(m, p), &d2, std::isfinite(drop_at) ? left * left : INFINITY) < 0 &&
          std::isfinite(drop_at))
        return -INFINITY;
      sum += std::sqrt(d2);
      if (sum >= drop_at) return -INFINITY;
    }
    const double mean = sum / n;
    return std::isfinite(mean) ? -mean : -INFINITY;
  }
  // The paper does no local optimisation.
  bool confirm_or_pick_for_refinement(const TriplePair&, const Affine2&, double, double) const { return false; }
  void refine(const TriplePair&, Affine2*, double*) const {}
  // Every centre lands exactly on one, and so does a distinct rival's (a symmetric layout): nothing more can
  // change the answer or its confidence 0. An exact fit alone is no reason to stop: its mirror may fit as
  // exactly, and only the rest of the K samples can tell (8 mirror-symmetric rocks read confidence 1).
  bool cannot_be_beaten(double s) const { return s >= -kExact && recorder && recorder->rival_score() >= -kExact; }
  const SearchRecorder* recorder = nullptr;
};

}  // namespace

MethodOutcome register_paper(const RegistrationFrame& f, const RegistrationOptions& o, const Deadline& deadline) {
  MethodOutcome out;
  const double gate = o.paper.pair_gate;  // the normalised frame has unit spread
  // The pairs (mutual nearest neighbours within the gate, as mutual_nearest_pairs finds them) and the inliers
  // (moved A centres within the gate of their nearest B centre) from one nearest query per rock: the final step
  // must stay cheap when a time budget leaves it little.
  auto count_inliers = [&](const Affine2& m) {
    std::vector<Eigen::Vector2d> moved;
    for (const auto& p : f.a) moved.push_back(apply(m, p));
    const PointGrid ga(moved), gb(f.b);
    int inl = 0;
    out.pairs.clear();
    for (size_t i = 0; i < moved.size(); ++i) {
      // Only centres within the gate matter: the query stops there (a wild answer's rocks land far from any).
      double d2 = INFINITY;
      const int j = gb.nearest(moved[i], &d2, std::nextafter(gate * gate, INFINITY));
      if (j < 0 || d2 > gate * gate) continue;
      ++inl;
      if (ga.nearest(f.b[j], nullptr) == static_cast<int>(i)) out.pairs.emplace_back(static_cast<int>(i), j);
    }
    out.inliers = inl;
  };
  if (f.a.size() < 3 || f.b.size() < 3) {
    out.stop = StopReason::kTooFewPoints;
    // Identity in image coordinates, expressed in the normalised frame.
    out.affine_normalised = f.from_image(identity_affine());
    out.note = "fewer than 3 rocks on a side: no affine can be fitted, identity used";
    if (!f.a.empty() && !f.b.empty()) count_inliers(out.affine_normalised);
    return out;
  }
  const PointGrid grid_b(f.b);
  RandomTripleSampler sampler{f.a, f.b, Rng(o.seed)};
  AffinePermutationEstimator estimator;
  MeanNearestScorer scorer{f.a, grid_b, deadline};
  RobustLoopOptions lo;
  lo.max_trials = o.paper.samples;
  lo.max_work = work_budget(o, f.a.size(), f.b.size());
  lo.work_per_model = static_cast<double>(f.a.size());  // one nearest-neighbour query per A rock
  // The trace's samples: A's triple in drawing order, B's in the order this model matched them.
  auto sample_of = [&](const Affine2& m, std::vector<int>* sa, std::vector<int>* sb) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d p = apply(m, f.a[sampler.ia[k]]);
      int best = 0;
      for (int t = 1; t < 3; ++t)
        if ((f.b[sampler.ib[t]] - p).squaredNorm() < (f.b[sampler.ib[best]] - p).squaredNorm()) best = t;
      sa->push_back(sampler.ia[k]);
      sb->push_back(sampler.ib[best]);
    }
  };
  const double spread = f.spread;
  SearchRecorder recorder(
      f, gate, o.record_trace, [spread](double s) { return -s * spread; }, sample_of);
  scorer.recorder = &recorder;
  DeadlineSampler<RandomTripleSampler> timed{sampler, deadline, o.paper.samples};
  auto r = run_robust_loop<Affine2, TriplePair>(timed, estimator, scorer, lo, recorder);
  r.stop = timed.stop(r.stop);
  out.samples = r.samples;
  out.hypotheses = r.hypotheses;
  out.work = r.work;
  out.stop = r.stop;
  // Scores are mean distances (lower is better): confidence = 1 - best / best distinct rival, each distance
  // counted from kExact so two exact fits (a layout and its mirror, 1e-17 and 0) read 0, not 1.
  if (r.found && std::isfinite(recorder.rival_score()))
    out.confidence = confidence_from_scores(kExact - recorder.rival_score(), kExact - r.best_score);
  out.trace = recorder.take_trace(describe_stop(r.stop, r.samples, r.hypotheses, r.work, lo.max_work));
  if (!r.found) {
    out.affine_normalised = f.from_image(identity_affine());
    const bool budget = r.stop == StopReason::kTimeBudget;
    out.note = budget ? "time budget spent before a triple was scored: identity used"
                      : "every sampled triple was degenerate: identity used";
    out.unjudged = budget ? Ambiguity::kUnchecked : Ambiguity::kDegenerate;
  } else {
    out.affine_normalised = r.best;
    out.fit = -r.best_score * f.spread;  // mean distance, as a fraction of the image width
  }
  const auto pairing_start = std::chrono::steady_clock::now();
  count_inliers(out.affine_normalised);  // the final pairing: mutual nearest centres
  out.pairing_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - pairing_start).count();
  return out;
}

}  // namespace ipd::detail
