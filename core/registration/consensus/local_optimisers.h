// Internal: the consensus registration's local optimisers, each a function of the support measurer and an
// affine: least squares on the inliers (LO-RANSAC), the robust polish, and the annealed soft refinement.
#pragma once

#include "core/geometry/geometry.h"
#include "core/registration/consensus/support_measurer.h"
#include "core/registration/deadline.h"

namespace ipd::detail {

// Least squares on the inliers, first with a wide gate (a triple's affine extrapolates poorly far from it)
// then the scoring gate, each step kept while the score `*s` improves.
// With a deadline that has passed, no further step starts.
void improve(SupportMeasurer* support, Affine2* m, double* s, const Deadline* deadline = nullptr);

// Robust least squares on the final consensus (Cauchy weights, scale a third of the gate): improve() stops at
// the first fit that doesn't raise the score; this uses every inlier and lets the few rocks labelled far off
// in one image pull less. It gives up at most kTuning.polish_loss of the consensus for a better fit: on nearly
// collinear inliers least squares is free across their line and can swing a true alignment off its rocks.
void polish(SupportMeasurer* support, Affine2* m);

// Annealed soft assignment from m (EM with an outlier class, as in CPD, plus the shape agreement): every B rock
// near a mapped A rock pulls in proportion to how close and how alike it is, so an alignment that a couple of
// wrong nearest pairs hold in place can slide to the better one next to it, which improve() never leaves.
// Kept only when it raises the score `*s` and keeps most aligned rocks in place. Small sets only (its cost is
// A x B per step). True when it changed m.
bool soft_refine(SupportMeasurer* support, Affine2* m, double* s);

}  // namespace ipd::detail
