// A generic robust hypothesise-and-verify loop, in the manner of COLMAP's optim/ransac.h, but for
// correspondence-free registration: a Sampler proposes minimal samples, an Estimator turns a sample into
// zero or more models, a Scorer rates a model (higher is better) and may refine a new best one. The Scorer is
// handed the sample a model came from, so it never needs to read the Sampler's state.
//
//   Sampler:   bool next(Sample*)                      false when it has nothing more to propose
//   Estimator: void estimate(const Sample&, std::vector<Model>*)
//   Scorer:    double score(const Model&)
//              bool confirm_or_pick_for_refinement(const Sample&, const Model&, double score, double best)
//                                                      whether to locally optimise this model
//              void refine(const Sample&, Model*, double* score)  local optimisation (may do nothing)
//              bool cannot_be_beaten(double score)     stop now: the best can't be (or won't be) improved
//   Observer (optional): void on_model(const Model& raw, double raw_score, const Model& final, double score,
//                                      bool refined, double best_score, bool new_best)
//              after each model is scored (and refined if worth it); NoObserver costs nothing.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>
#include <vector>

namespace ipd {

enum class StopReason {
  kNotRun,
  kTooFewPoints,
  kMaxTrials,
  kExhausted,
  kConverged,
  kCannotBeBeaten,
  kTimeBudget,
  kWorkBudget,
  kIdenticalLayouts  // both sides hold exactly the same boxes: the identity, without a search
};
// The last stop reason: caches read a stored reason back only up to it (keep it the enum's last).
inline constexpr StopReason kLastStopReason = StopReason::kIdenticalLayouts;

inline const char* to_string(StopReason r) {
  switch (r) {
    case StopReason::kNotRun:
      return "not run";
    case StopReason::kTooFewPoints:
      return "too few points for a minimal sample";
    case StopReason::kMaxTrials:
      return "reached the trial limit";
    case StopReason::kExhausted:
      return "tried every hypothesis";
    case StopReason::kConverged:
      return "converged";
    case StopReason::kCannotBeBeaten:
      return "best score cannot be beaten";
    case StopReason::kTimeBudget:
      return "time budget spent";
    case StopReason::kWorkBudget:
      return "work budget spent";
    case StopReason::kIdenticalLayouts:
      return "identical layouts (no search needed)";
  }
  return "?";
}

// COLMAP's ComputeNumTrials: how many samples of `sample_size` must be drawn so that, with probability
// `confidence`, at least one holds only inliers when `num_inliers` of `num_points` are. 1 when every point
// is an inlier; `cap` when none is (or confidence is 1).
inline int compute_num_trials(int num_inliers, int num_points, int sample_size, double confidence, int cap) {
  if (num_points <= 0 || num_inliers <= 0) return cap;
  const double ratio = std::min(1.0, static_cast<double>(num_inliers) / num_points);
  const double nom = 1.0 - confidence;
  if (nom <= 0) return cap;
  const double denom = 1.0 - std::pow(ratio, sample_size);
  if (denom <= 0) return 1;
  const double n = std::ceil(std::log(nom) / std::log(denom));
  return n >= cap ? cap : std::max(1, static_cast<int>(n));
}

struct RobustLoopOptions {
  int max_trials = 1000;
  // No time: a loop under a time budget draws from a DeadlineSampler, which stops at the registration's
  // Deadline (set-up included), the one clock of a budget.
  // Work bound: each scored model costs `work_per_model` units (e.g. the points it maps); the loop stops
  // before the total would pass `max_work`. 0: no limit.
  double max_work = 0.0, work_per_model = 1.0;

  // Empty when usable; otherwise the field that is wrong and the accepted range, in one sentence.
  std::string validate() const;
  // Throws std::invalid_argument("robust loop options: " + validate()) when not usable.
  void check() const;
};

struct NoObserver {
  template <typename Model>
  void on_model(const Model&, double, const Model&, double, bool, double, bool) {}
};

template <typename Model>
struct RobustLoopResult {
  bool found = false;
  Model best{};
  double best_score = -INFINITY;
  int samples = 0;     // samples drawn
  int hypotheses = 0;  // models scored
  double work = 0;     // hypotheses x work_per_model
  StopReason stop = StopReason::kNotRun;
};

template <typename Model, typename Sample, typename Sampler, typename Estimator, typename Scorer,
          typename Observer = NoObserver>
RobustLoopResult<Model> run_robust_loop(Sampler& sampler, Estimator& estimator, Scorer& scorer,
                                        const RobustLoopOptions& options, Observer&& observer = Observer()) {
  options.check();
  RobustLoopResult<Model> r;
  std::vector<Model> models;
  Sample sample;
  while (true) {
    if (r.samples >= options.max_trials) {
      r.stop = StopReason::kMaxTrials;
      break;
    }
    if (!sampler.next(&sample)) {
      r.stop = StopReason::kExhausted;
      break;
    }
    ++r.samples;
    models.clear();
    estimator.estimate(sample, &models);
    bool out_of_work = false;
    for (auto& m : models) {
      if (options.max_work > 0 && r.work + options.work_per_model > options.max_work) {
        out_of_work = true;
        break;
      }
      ++r.hypotheses;
      r.work += options.work_per_model;
      double s = scorer.score(m);
      const double raw_score = s;
      // Refine promising models, not only new bests: a minimal sample's model is noisy, and the right one
      // often scores below a wrong one until it is refined (LO-RANSAC).
      bool refined = false;
      if constexpr (std::is_same_v<std::decay_t<Observer>, NoObserver>) {
        if (scorer.confirm_or_pick_for_refinement(sample, m, s, r.best_score)) scorer.refine(sample, &m, &s);
      } else {
        const Model raw = m;
        if (scorer.confirm_or_pick_for_refinement(sample, m, s, r.best_score)) {
          scorer.refine(sample, &m, &s);
          refined = true;
        }
        const bool new_best = s > r.best_score;
        observer.on_model(raw, raw_score, m, s, refined, new_best ? s : r.best_score, new_best);
      }
      if (s > r.best_score) {
        r.best = m;
        r.best_score = s;
        r.found = true;
      }
    }
    if (out_of_work) {
      r.stop = StopReason::kWorkBudget;
      break;
    }
    // Checked after every sample: the best may also become unbeatable by being confirmed.
    if (r.found && scorer.cannot_be_beaten(r.best_score)) {
      r.stop = StopReason::kCannotBeBeaten;
      break;
    }
  }
  return r;
}

}  // namespace ipd
