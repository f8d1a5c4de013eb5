// Internal: when the consensus search may stop, as pure functions of counts (tested without a search): the
// confirmation rule, the chance rule, and the chance of one rock agreeing with a wrong affine.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace ipd::detail {

// What the stop rule reads after each sample.
struct ConsensusCounts {
  int best_inliers = 0;        // mutually nearest pairs of the best refined hypothesis
  int max_inliers = 0;         // the smaller side's rock count: no hypothesis can hold more
  int confirmations = 0;       // other anchor rocks that found the best again
  int scored = 0;              // hypotheses scored so far (refinement steps included)
  int hypothesis_budget = 1;   // the hypothesis cap
  bool beyond_chance = false;  // see consensus_beyond_chance()
};

// True when the best can't (or won't) be beaten: it pairs every rock of the smaller side; or it was found again
// from kTuning.confirmations other anchors, holds at least kTuning.min_confirmed_inliers rocks, and enough
// hypotheses were scored that a triple of true pairs would likely have come up if the best holds only part of
// them (COLMAP's rule, with the inlier ratio over the smaller side: a small consensus searches longer before it
// is believed); or it is beyond chance and holds half the smaller side.
bool consensus_cannot_be_beaten(const ConsensusCounts& c);

// The chance that a wrong affine drops one A rock within the gate of some B rock: the area of B's gate discs
// (n pi gate^2, overlaps not removed) over the area of B's bounding box (at least n gate^2), at most
// kTuning.max_chance. Clustered rocks are not weighed more: the chance is this ratio, not a multiple of it.
double chance_of_agreement(const std::vector<Eigen::Vector2d>& b, double gate2);

// A consensus of `inliers` of `a_rocks` that chance (`chance` per rock) would give less often than
// kTuning.chance_level over every hypothesis allowed; the three rocks a hypothesis is built from agree by
// construction, so they don't count. At least kTuning.min_beyond_chance_inliers rocks.
bool consensus_beyond_chance(int inliers, int a_rocks, double chance, int hypothesis_budget);

}  // namespace ipd::detail
