#include "core/registration/consensus/consensus_scorer.h"

#include <algorithm>

#include "core/registration/consensus/consensus_tuning.h"
#include "core/registration/consensus/local_optimisers.h"

namespace ipd::detail {

bool Confirmations::agrees_with_best(const Affine2& m) const {
  if (!m.allFinite()) return false;
  int close = 0;
  for (const auto& p : a_) close += (apply(m, p) - apply(best_, p)).squaredNorm() < gate2_;
  return 2 * close > static_cast<int>(a_.size());
}

void Confirmations::confirm(long anchor) {
  if (std::find(anchors_.begin(), anchors_.end(), anchor) != anchors_.end()) return;
  anchors_.push_back(anchor);
  ++count_;
}

void Confirmations::restart() {
  anchors_.clear();
  count_ = 0;
}

void Confirmations::set_best(const Affine2& m, long anchor) {
  best_ = m;
  has_best_ = true;
  if (std::find(anchors_.begin(), anchors_.end(), anchor) == anchors_.end()) anchors_.push_back(anchor);
}

ConsensusScorer::ConsensusScorer(SupportMeasurer* support, int hypothesis_budget, const Deadline* deadline)
    : support_(support),
      deadline_(deadline),
      confirmations_(support->a(), support->gate2()),
      chance_(chance_of_agreement(support->grid().points(), support->gate2())),
      budget_(std::max(1, hypothesis_budget)),
      max_count_(static_cast<int>(std::min(support->a().size(), support->grid().size()))) {}

bool ConsensusScorer::confirm_or_pick_for_refinement(const GuidedHypothesis& h, const Affine2& m, double s,
                                                     double best) {
  if (s < kTuning.min_refine_score) return false;
  if (deadline_ != nullptr && deadline_->passed()) return false;
  if (confirmations_.has_best() && confirmations_.agrees_with_best(m)) {
    confirmations_.confirm(h.anchor);
    return false;
  }
  return s >= kTuning.refine_fraction * best;
}

void ConsensusScorer::refine(const GuidedHypothesis& h, Affine2* m, double* s) {
  improve(support_, m, s, deadline_);
  // The bookkeeping below counts inliers and a binomial tail over every rock: skipped once the budget is spent
  // (the search stops before its next sample; the refined model is still scored as the loop's best).
  if (deadline_ != nullptr && deadline_->passed()) return;
  if (confirmations_.has_best() && confirmations_.agrees_with_best(*m))
    confirmations_.confirm(h.anchor);
  else if (*s > best_refined_score_)
    confirmations_.restart();
  if (*s > best_refined_score_) {  // the best model and its inlier count, for the stop rule
    best_refined_score_ = *s;
    support_->set_preview_reference(best_refined_score_);
    confirmations_.set_best(*m, h.anchor);
    best_count_ = support_->count_inliers(*m);
    beyond_chance_ = consensus_beyond_chance(best_count_, static_cast<int>(support_->a().size()), chance_, budget_);
  }
}

bool ConsensusScorer::cannot_be_beaten(double) const {
  ConsensusCounts c;
  c.best_inliers = best_count_;
  c.max_inliers = max_count_;
  c.confirmations = confirmations_.count();
  c.scored = support_->scored();
  c.hypothesis_budget = budget_;
  c.beyond_chance = beyond_chance_;
  return consensus_cannot_be_beaten(c);
}

}  // namespace ipd::detail
