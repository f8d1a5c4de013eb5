// Internal: the consensus registration's second look, for small overlaps. When the guided search ends without
// a confirmed alignment (it ran out of hypotheses, or a rival came close), the true pairs may be too few, too
// far apart or too nearly collinear for the neighbourhood triples to propose them. Then every pair of A rocks
// meets every pair of B rocks whose box sizes agree with the scale the two edges imply; the best of those
// similarities are refined to affines, and every candidate is judged on the pairing it would produce.
#pragma once

#include <vector>

#include "core/geometry/geometry.h"
#include "core/registration/consensus/consensus_scorer.h"
#include "core/registration/pairing.h"
#include "core/registration/registration.h"
#include "core/registration/registration_frame.h"

namespace ipd::detail {

// Edge pairs the second look may examine; beyond this (about 18 rocks a side) it is skipped: larger sets
// keep enough neighbours in common for the guided search, and the enumeration grows as n^4.
inline constexpr double kMaxEdgePairs = 60000;
// How far a rock's log box size may stray from the log scale of the edge it ends, and how many of the best
// similarities are refined into candidates. Large tier F1 over seeds 0-6: mean 0.9642 with 0.4 / 15, 0.9633
// with 0.6 / 30 (0.3-0.6 and 15-30 all within 0.001), and the search scores a third fewer hypotheses.
inline constexpr double kEdgeLogSizeGap = 0.4;
inline constexpr size_t kEdgeCandidates = 15;

struct EdgeSearch {
  std::vector<Affine2> candidates;  // refined and polished, best consensus first
  int hypotheses = 0;               // similarities scored
  double work = 0;                  // edge pairs examined plus rocks scored
};

// Similarity hypotheses from every A edge and every B edge (both directions), the `keep` best by the scorer's
// consensus, each refined (least squares on its inliers) and polished.
EdgeSearch edge_candidates(const RegistrationFrame& f, const Bounds& bounds, ConsensusScorer* scorer, size_t keep);

// A candidate judged on its final pairing: the consensus score, plus the IoU its pairs reach, minus the rocks
// left without a partner although the other picture shows their whole box (a wrong alignment leaves many).
struct Judgement {
  double consensus = 0, iou_sum = 0;
  int unpaired_a = 0, unpaired_b = 0;
  double total = 0;
};
Judgement judge_candidate(const RegistrationFrame& f, const std::vector<Box>& boxes_a, const std::vector<Box>& boxes_b,
                          const Affine2& normalised, double consensus, const PairingRule& rule);

}  // namespace ipd::detail
