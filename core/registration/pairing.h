// Turning aligned point sets into rock pairs.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/geometry/geometry.h"
#include "core/registration/registration.h"

namespace ipd {

// Pairs (i, j) where a[i] and b[j] are each other's nearest neighbour and closer than `gate`.
RockPairs mutual_nearest_pairs(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b,
                               double gate);

// Optimal one-to-one assignment maximising total weight (weights[i * cols + j] >= 0); entries at or below
// `min_weight` are never assigned. Rectangular Hungarian algorithm,
// O(min(rows, cols)^2 * max(rows, cols)).
RockPairs max_weight_assignment(const std::vector<double>& weights, int rows, int cols, double min_weight);

// One allowed pair of a sparse assignment problem: row, column, weight.
struct WeightedEdge {
  int row, col;
  double weight;
};
// The same optimum over a sparse set of allowed pairs (edges with weight <= min_weight are never assigned):
// shortest augmenting paths with potentials and a heap, O(edges) memory. Each row's search only explores
// paths cheaper than leaving that row unassigned, so geometric overlap graphs stay near-linear where the
// dense solver needs rows x cols memory and cubic time. Among several optima it may pick another one than
// max_weight_assignment; the total weight is the same.
RockPairs sparse_max_weight_assignment(const std::vector<WeightedEdge>& edges, int rows, int cols, double min_weight);

}  // namespace ipd

namespace ipd {
// When two aligned boxes are one rock. Overlap alone is unfair to small rocks: a few pixels of label noise cost a
// 20 px box most of its IoU and a 200 px box almost none. So a pair is either an overlap (IoU > min_iou) or a
// near miss: centres closer than a noise floor that is the same number of pixels whatever the rocks' size, with
// sides that agree (a pebble beside a boulder is not the boulder). A near miss weighs less in the assignment
// than any overlap, and less the farther apart, so it only takes rocks that no overlap claims. With the floor at
// 0 (the default) the rule is overlap alone.
struct PairingRule {
  double min_iou = 0.1;
  double noise_floor = 0;       // centre distance, fraction of the image width; 0: overlap alone
  double max_size_ratio = 2.0;  // larger / smaller geometric-mean side of the two boxes
  double aspect = 1.0;          // image width / height: distances are measured in pixels
};

// The rule RegistrationOptions describe (min_pair_iou, pair_noise_floor, pair_max_size_ratio, aspect).
PairingRule pairing_rule(const RegistrationOptions& o);

// The rule's weight for one pair of boxes already in B's frame: the IoU when above min_iou, a near miss's weight
// in (0, min_iou] (more the closer), 0 when they are no pair (always for two classes).
double pair_weight(const Box& moved_a, const Box& b, const PairingRule& rule);

// Maps A's boxes by `a_to_b` (normalised image coordinates) and assigns them one-to-one to B's boxes under
// `rule`, maximising the total weight.
RockPairs pair_aligned_boxes(const Affine2& a_to_b, const std::vector<Box>& a, const std::vector<Box>& b,
                             const PairingRule& rule);

class Deadline;
// pair_aligned_boxes under a time budget: the same allowed pairs, found through a grid over B's centres; each
// overlap component is solved optimally while the deadline holds, and what is left when it passes (everything,
// when it had passed before) is paired greedily, heaviest pair first, and *greedy is set. Greedy takes one sort
// of the allowed pairs (about a millisecond for 5,000 rocks a side) and keeps at least half the optimal weight;
// on scattered rocks, where components are single pairs, it is the optimum.
RockPairs pair_aligned_boxes_within(const Affine2& a_to_b, const std::vector<Box>& a, const std::vector<Box>& b,
                                    const PairingRule& rule, const Deadline& deadline, bool* greedy);
}  // namespace ipd
