// Internal: the consensus registration's second look, for small overlaps. When the guided search ends without
// a confirmed alignment (it ran out of hypotheses, or a rival came close), the true pairs may be too few, too
// far apart or too nearly collinear for the neighbourhood triples to propose them. Then every pair of A rocks
// meets every pair of B rocks whose box sizes agree with the scale the two edges imply; the best of those
// similarities are refined to affines, and every candidate is judged on the pairing it would produce.
#pragma once

#include <vector>

#include "core/geometry/geometry.h"
#include "core/registration/consensus/consensus_bounds.h"
#include "core/registration/consensus/support_measurer.h"
#include "core/registration/pairing.h"
#include "core/registration/registration.h"
#include "core/registration/registration_frame.h"

namespace ipd::detail {

// Its limits (kTuning.max_edge_pairs: about 18 rocks a side, the enumeration grows as n^4) and its constants are
// in consensus_tuning.h.

struct EdgeSearch {
  std::vector<Affine2> candidates;  // refined and polished, best consensus first
  int hypotheses = 0;               // similarities scored
  double work = 0;                  // edge pairs examined plus rocks scored
};

// Similarity hypotheses from every A edge and every B edge (both directions), the `keep` best by the support
// measurer's consensus, each refined (least squares on its inliers) and polished.
EdgeSearch edge_candidates(const RegistrationFrame& f, const Bounds& bounds, SupportMeasurer* support, size_t keep);

// The prior on the camera, in the judgement's units: kTuning.weight_log_scale x |log area scale| / 2 plus
// kTuning.weight_rotation x |rotation| (radians) of an affine between normalised sets. When the rocks fit two
// alignments about as well (three or four true pairs fix any affine), the smaller misalignment wins.
double misalignment_cost(const Affine2& normalised);

// A candidate judged on its final pairing: the consensus score, plus the IoU its pairs reach, minus the rocks
// left without a partner although the other picture shows their whole box (a wrong alignment leaves many), minus
// its misalignment_cost.
struct Judgement {
  double consensus = 0, iou_sum = 0;
  int unpaired_a = 0, unpaired_b = 0;
  double total = 0;
};
Judgement judge_candidate(const RegistrationFrame& f, const std::vector<Box>& boxes_a, const std::vector<Box>& boxes_b,
                          const Affine2& normalised, double consensus, const PairingRule& rule);

}  // namespace ipd::detail
