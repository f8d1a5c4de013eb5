// A generic robust hypothesise-and-verify loop, in the manner of COLMAP's optim/ransac.h, but for
// correspondence-free registration: a Sampler proposes minimal samples, an Estimator turns a sample into
// zero or more models, a Scorer rates a model (higher is better) and may refine a new best one.
//
//   Sampler:   bool next(Sample*)                      false when it has nothing more to propose
//   Estimator: void estimate(const Sample&, std::vector<Model>*)
//   Scorer:    double score(const Model&)
//              bool worth_refining(double score, double best)  whether to locally optimise this model
//              void refine(Model*, double* score)      local optimisation (may do nothing)
//              bool cannot_be_beaten(double score)     stop now: the best can't be (or won't be) improved
#pragma once

#include <chrono>
#include <cmath>
#include <string>
#include <vector>

namespace ipd {

enum class StopReason { kNotRun, kTooFewPoints, kMaxTrials, kExhausted, kConverged, kCannotBeBeaten, kTimeBudget };

inline const char* to_string(StopReason r) {
  switch (r) {
    case StopReason::kNotRun: return "not run";
    case StopReason::kTooFewPoints: return "too few points for a minimal sample";
    case StopReason::kMaxTrials: return "reached the trial limit";
    case StopReason::kExhausted: return "tried every hypothesis";
    case StopReason::kConverged: return "converged";
    case StopReason::kCannotBeBeaten: return "best score cannot be beaten";
    case StopReason::kTimeBudget: return "time budget spent";
  }
  return "?";
}

struct RobustLoopOptions {
  int max_trials = 1000;
  double time_budget_ms = 0.0;  // 0: no limit
};

template <typename Model>
struct RobustLoopResult {
  bool found = false;
  Model best{};
  double best_score = -INFINITY;
  int trials = 0;      // samples drawn
  int hypotheses = 0;  // models scored
  StopReason stop = StopReason::kNotRun;
};

template <typename Model, typename Sample, typename Sampler, typename Estimator, typename Scorer>
RobustLoopResult<Model> run_robust_loop(Sampler& sampler, Estimator& estimator, Scorer& scorer,
                                        const RobustLoopOptions& options) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  RobustLoopResult<Model> r;
  std::vector<Model> models;
  Sample sample;
  while (true) {
    if (r.trials >= options.max_trials) {
      r.stop = StopReason::kMaxTrials;
      break;
    }
    if (options.time_budget_ms > 0 && (r.trials & 15) == 0 && r.trials > 0) {
      const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
      if (ms > options.time_budget_ms) {
        r.stop = StopReason::kTimeBudget;
        break;
      }
    }
    if (!sampler.next(&sample)) {
      r.stop = StopReason::kExhausted;
      break;
    }
    ++r.trials;
    models.clear();
    estimator.estimate(sample, &models);
    for (auto& m : models) {
      ++r.hypotheses;
      double s = scorer.score(m);
      // Refine promising models, not only new bests: a minimal sample's model is noisy, and the right one
      // often scores below a wrong one until it is refined (LO-RANSAC).
      if (scorer.worth_refining(s, r.best_score)) scorer.refine(&m, &s);
      if (s > r.best_score) {
        r.best = m;
        r.best_score = s;
        r.found = true;
      }
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
