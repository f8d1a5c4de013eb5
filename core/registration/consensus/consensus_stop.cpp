#include "core/registration/consensus/consensus_stop.h"

#include <algorithm>
#include <cmath>

#include "core/registration/consensus/consensus_search.h"
#include "core/registration/consensus/consensus_tuning.h"
#include "core/registration/robust_loop.h"

namespace ipd::detail {

namespace {
constexpr int kSampleSize = 3;  // rocks a hypothesis is built from
}  // namespace

bool consensus_cannot_be_beaten(const ConsensusCounts& c) {
  if (c.best_inliers >= c.max_inliers) return true;
  if (c.confirmations >= kTuning.confirmations && c.best_inliers >= kTuning.min_confirmed_inliers &&
      c.scored >= compute_num_trials(c.best_inliers, c.max_inliers, kSampleSize, kTuning.trials_confidence,
                                     c.hypothesis_budget))
    return true;
  // Beyond chance is the right basin, not yet the whole alignment: on a dense layout turned by a few degrees
  // the identity matches the centre only, so it must also hold half the smaller side.
  return c.beyond_chance && 2 * c.best_inliers >= c.max_inliers;
}

double chance_of_agreement(const std::vector<Eigen::Vector2d>& b, double gate2) {
  Eigen::Vector2d lo = b.empty() ? Eigen::Vector2d(0, 0) : b[0], hi = lo;
  for (const auto& q : b) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  const double area = std::max((hi - lo).prod(), static_cast<double>(b.size()) * gate2);
  return std::min(kTuning.max_chance, static_cast<double>(b.size()) * M_PI * gate2 / area);
}

bool consensus_beyond_chance(int inliers, int a_rocks, double chance, int hypothesis_budget) {
  return inliers >= kTuning.min_beyond_chance_inliers &&
         binomial_tail(a_rocks - kSampleSize, chance, inliers - kSampleSize) * hypothesis_budget < kTuning.chance_level;
}

}  // namespace ipd::detail
