// A record of a registration's search, for replaying it (ipd-studio's registration panel). Off by default:
// batch runs never pay for it. Every method fills it: paper and consensus one step per scored hypothesis and
// per refinement, cpd one step per EM iteration.
#pragma once

#include <string>
#include <vector>

#include "core/geometry/geometry.h"

namespace ipd {

enum class TraceStepKind { kHypothesis, kRefinement, kIteration, kPolish };

struct TraceStep {
  TraceStepKind kind = TraceStepKind::kHypothesis;
  // The rocks the hypothesis was built from, in matching order (a_sample[k] ↔ b_sample[k]); empty for
  // hypotheses not built from a sample (identity, voted translation) and for iterations.
  std::vector<int> a_sample, b_sample;
  Affine2 b_from_a = identity_affine();  // normalised A centres -> B's
  std::vector<int> inliers_a;            // A rocks within the gate of a B rock under this affine
  double fit = 0;                        // this step's fit, in the method's measure (RegistrationReport::fit)
  double best_fit = 0;                   // best so far, after this step
  bool new_best = false;                 // this step became the best
};

struct RegistrationTrace {
  std::vector<TraceStep> steps;
  int max_steps = 5000;  // recording stops here (truncated = true); the search itself goes on
  bool truncated = false;
  std::string stop;  // why the search stopped, in words

  // Appends unless full; returns false (and sets truncated) when the cap is reached.
  bool add(TraceStep step) {
    if (static_cast<int>(steps.size()) >= max_steps) {
      truncated = true;
      return false;
    }
    steps.push_back(std::move(step));
    return true;
  }
};

}  // namespace ipd
