// Internal: the set-level searches behind the consensus registration (neighbourhoods, translation votes,
// the chance of a consensus), kept apart from the hypothesis loop.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "core/registration/deadline.h"

namespace ipd::detail {

// Each point's k nearest other points, nearest first (ties by index; coincident points left out: a duplicate
// of the rock itself spans nothing). Grid queries in a disc that doubles until it holds k points, so the cost
// is about n k log n, not n^2. With a deadline that passes, it stops early (read every 256 points) and the rest
// of the lists stay empty: the caller must not use them.
std::vector<std::vector<int>> nearest_neighbours(const std::vector<Eigen::Vector2d>& p, int k,
                                                 const Deadline* deadline = nullptr);

// P(X >= k) for X ~ Binomial(n, p), summed in log space.
double binomial_tail(int n, double p, int k);

// The translations most (A, B) rock pairs agree on once A's rocks are mapped by `lin`: votes binned at
// `bin`, the mean of each of the `top` fullest bins (holding at least two votes), fullest first. A rocks
// are subsampled to about 16 so the cost stays linear in B.
std::vector<Eigen::Vector2d> top_translations(const Eigen::Matrix2d& lin, const std::vector<Eigen::Vector2d>& a,
                                              const std::vector<Eigen::Vector2d>& b, double bin, size_t top);

}  // namespace ipd::detail
