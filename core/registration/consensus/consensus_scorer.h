// Internal: the consensus search's scorer, the Scorer role of the robust loop (robust_loop.h). It scores with
// the support measurer, decides which hypotheses the local optimiser refines, keeps the confirmation count of
// the best (from the anchors the hypotheses carry) and asks the pure stop rule (consensus_stop.h) whether the
// search may end.
#pragma once

#include <vector>

#include "core/geometry/geometry.h"
#include "core/registration/consensus/consensus_stop.h"
#include "core/registration/consensus/guided_sampler.h"
#include "core/registration/consensus/support_measurer.h"
#include "core/registration/deadline.h"

namespace ipd::detail {

// The best refined hypothesis and the anchor rocks that found it: the true alignment attracts hypotheses from
// every rock that kept its neighbours, wrong ones rarely from two.
class Confirmations {
 public:
  Confirmations(const std::vector<Eigen::Vector2d>& a, double gate2) : a_(a), gate2_(gate2) {}
  // Two affines agree when they put most of A's rocks within a gate of each other.
  bool agrees_with_best(const Affine2& m) const;
  bool has_best() const { return has_best_; }
  // The best found again from `anchor`: counted once per anchor.
  void confirm(long anchor);
  // A new, different best: counting starts again.
  void restart();
  // The best is now m (grown from `anchor`, which found it and so never confirms it).
  void set_best(const Affine2& m, long anchor);
  int count() const { return count_; }

 private:
  const std::vector<Eigen::Vector2d>& a_;
  double gate2_;
  bool has_best_ = false;
  Affine2 best_ = identity_affine();
  std::vector<long> anchors_;
  int count_ = 0;
};

class ConsensusScorer {
 public:
  // `deadline` (may be null): once passed, no hypothesis is refined (a refinement on 5,000 rocks costs
  // milliseconds) and a refinement under way stops between its steps.
  ConsensusScorer(SupportMeasurer* support, int hypothesis_budget, const Deadline* deadline = nullptr);

  double score(const Affine2& m) { return support_->score(m); }
  // Acts on a scored hypothesis: one that agrees with the best so far is counted as confirming it (when it grew
  // from another anchor) and is not refined; otherwise true when it is worth a least-squares pass (close to the
  // best so far, after its own refinement, or early on).
  bool confirm_or_pick_for_refinement(const GuidedHypothesis& h, const Affine2& m, double s, double best);
  // The local optimiser (improve()), then the bookkeeping of the best and its confirmations.
  void refine(const GuidedHypothesis& h, Affine2* m, double* s);
  bool cannot_be_beaten(double) const;

 private:
  SupportMeasurer* support_;
  const Deadline* deadline_;
  Confirmations confirmations_;
  double chance_;
  int budget_, max_count_, best_count_ = 0;
  bool beyond_chance_ = false;
  double best_refined_score_ = -INFINITY;
};

}  // namespace ipd::detail
