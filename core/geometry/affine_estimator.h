// Estimating a 2-D affine map from point correspondences: exactly from three, by least squares from more.
// Callers pass normalised coordinates (centred, unit spread) so the solves are well conditioned.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/geometry/geometry.h"

namespace ipd {

// Twice the triangle area over the squared longest side: 0 for collinear points, ~0.87 for equilateral.
double triangle_conditioning(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c);

// Triangles flatter than this are rejected: their affine would amplify noise without bound.
constexpr double kMinTriangleConditioning = 1e-3;

// The affine mapping src[k] onto dst[k] (k = 0..2); false when either triangle is near-collinear.
bool affine_from_three(const Eigen::Vector2d src[3], const Eigen::Vector2d dst[3], Affine2* out);

// The affine mapping src0 + a1, src0 + a2 onto dst0 + b1, dst0 + b2 (and src0 onto dst0), given the edges and
// `cross_a` = a1 x a2 (non-zero): [b1 b2] [a1 a2]^-1, written out. affine_from_three() after its checks, and
// the consensus search, which has the edges and cross product at hand for thousands of triples.
void affine_from_edges(const Eigen::Vector2d& a1, const Eigen::Vector2d& a2, const Eigen::Vector2d& b1,
                       const Eigen::Vector2d& b2, double cross_a, const Eigen::Vector2d& src0,
                       const Eigen::Vector2d& dst0, Affine2* out);

// Least-squares affine over n >= 3 correspondences; false when the points are degenerate.
bool affine_least_squares(const std::vector<Eigen::Vector2d>& src, const std::vector<Eigen::Vector2d>& dst,
                          Affine2* out);

// Least squares that a few wrong correspondences can't drag: fit, drop pairs whose residual exceeds three
// times the median of the kept ones, refit, until nothing changes. For hand-made pairs, where one wrong pair
// would otherwise bend the whole alignment. False when the points are degenerate.
bool affine_least_squares_trimmed(const std::vector<Eigen::Vector2d>& src, const std::vector<Eigen::Vector2d>& dst,
                                  Affine2* out);

// Least-squares similarity (rotation, uniform scale, translation) over n >= 2 correspondences: what a nearly
// collinear set still determines, where an affine would be free across the line. False when src is one point.
bool similarity_least_squares(const Eigen::Vector2d* src, const Eigen::Vector2d* dst, size_t n, Affine2* out);

// Weighted least squares (weights >= 0, at least three positive); used for robust (IRLS) refinement.
bool affine_weighted_least_squares(const std::vector<Eigen::Vector2d>& src, const std::vector<Eigen::Vector2d>& dst,
                                   const std::vector<double>& weights, Affine2* out);

// A 3 + 3 point sample whose correspondence is unknown: the estimator tries every ordering of dst.
struct TriplePair {
  Eigen::Vector2d src[3];
  Eigen::Vector2d dst[3];
};

// The paper's estimator: up to six models, one per permutation of the destination triple.
struct AffinePermutationEstimator {
  void estimate(const TriplePair& s, std::vector<Affine2>* models) const;
};

// An estimator for samples whose order is already known (guided samplers): at most one model.
struct AffineTripleEstimator {
  void estimate(const TriplePair& s, std::vector<Affine2>* models) const;
};

}  // namespace ipd
