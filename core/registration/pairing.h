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
// Maps A's boxes by `a_to_b` (normalised image coordinates) and assigns them one-to-one to B's boxes,
// maximising total IoU; pairs overlapping no more than `min_iou` are left out.
RockPairs pair_by_aligned_iou(const Affine2& a_to_b, const std::vector<Box>& a, const std::vector<Box>& b,
                              double min_iou);
}  // namespace ipd
