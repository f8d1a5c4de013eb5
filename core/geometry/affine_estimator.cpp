#include "core/geometry/affine_estimator.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace ipd {

double triangle_conditioning(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const Eigen::Vector2d u = b - a, v = c - a, w = c - b;
  const double longest = std::max({u.squaredNorm(), v.squaredNorm(), w.squaredNorm()});
  if (!(longest > 0) || !std::isfinite(longest)) return 0.0;
  return std::abs(u.x() * v.y() - u.y() * v.x()) / longest;
}

bool affine_from_three(const Eigen::Vector2d src[3], const Eigen::Vector2d dst[3], Affine2* out) {
  if (triangle_conditioning(src[0], src[1], src[2]) < kMinTriangleConditioning) return false;
  if (triangle_conditioning(dst[0], dst[1], dst[2]) < kMinTriangleConditioning) return false;
  const Eigen::Vector2d a1 = src[1] - src[0], a2 = src[2] - src[0];
  affine_from_edges(a1, a2, dst[1] - dst[0], dst[2] - dst[0], a1.x() * a2.y() - a1.y() * a2.x(), src[0], dst[0], out);
  return out->allFinite();
}

void affine_from_edges(const Eigen::Vector2d& a1, const Eigen::Vector2d& a2, const Eigen::Vector2d& b1,
                       const Eigen::Vector2d& b2, double cross_a, const Eigen::Vector2d& src0,
                       const Eigen::Vector2d& dst0, Affine2* out) {
  const double inv = 1.0 / cross_a;
  Affine2& m = *out;
  m(0, 0) = (b1.x() * a2.y() - b2.x() * a1.y()) * inv;
  m(0, 1) = (b2.x() * a1.x() - b1.x() * a2.x()) * inv;
  m(1, 0) = (b1.y() * a2.y() - b2.y() * a1.y()) * inv;
  m(1, 1) = (b2.y() * a1.x() - b1.y() * a2.x()) * inv;
  m.col(2) = dst0 - m.leftCols<2>() * src0;
}

bool affine_least_squares(const std::vector<Eigen::Vector2d>& src, const std::vector<Eigen::Vector2d>& dst,
                          Affine2* out) {
  return affine_weighted_least_squares(src, dst, std::vector<double>(src.size(), 1.0), out);
}

bool affine_least_squares_trimmed(const std::vector<Eigen::Vector2d>& src, const std::vector<Eigen::Vector2d>& dst,
                                  Affine2* out) {
  Affine2 m;
  if (!affine_least_squares(src, dst, &m)) return false;
  const size_t n = src.size();
  std::vector<double> keep(n, 1.0), residual(n);
  for (int round = 0; round < 8; ++round) {
    std::vector<double> kept;
    for (size_t k = 0; k < n; ++k) {
      residual[k] = (apply(m, src[k]) - dst[k]).norm();
      if (keep[k] > 0) kept.push_back(residual[k]);
    }
    std::nth_element(kept.begin(), kept.begin() + kept.size() / 2, kept.end());
    const double limit = 3 * kept[kept.size() / 2] + 1e-9;  // the floor: exact fits have residuals ~1e-16
    std::vector<double> next(n);
    for (size_t k = 0; k < n; ++k) next[k] = residual[k] <= limit ? 1.0 : 0.0;
    if (next == keep || std::count(next.begin(), next.end(), 1.0) < 3) break;
    Affine2 refit;
    if (!affine_weighted_least_squares(src, dst, next, &refit)) break;
    keep = next;
    m = refit;
  }
  *out = m;
  return true;
}

bool similarity_least_squares(const Eigen::Vector2d* src, const Eigen::Vector2d* dst, size_t n, Affine2* out) {
  if (n < 2) return false;
  Eigen::Vector2d ms = Eigen::Vector2d::Zero(), md = Eigen::Vector2d::Zero();
  for (size_t k = 0; k < n; ++k) ms += src[k], md += dst[k];
  ms /= static_cast<double>(n);
  md /= static_cast<double>(n);
  double c = 0, s = 0, norm = 0;  // the map is [c -s; s c] / norm
  for (size_t k = 0; k < n; ++k) {
    const Eigen::Vector2d p = src[k] - ms, q = dst[k] - md;
    c += p.dot(q);
    s += p.x() * q.y() - p.y() * q.x();
    norm += p.squaredNorm();
  }
  if (!(norm > 0)) return false;
  Eigen::Matrix2d lin;
  lin << c / norm, -s / norm, s / norm, c / norm;
  out->leftCols<2>() = lin;
  out->col(2) = md - lin * ms;
  return out->allFinite();
}

bool affine_weighted_least_squares(const std::vector<Eigen::Vector2d>& src, const std::vector<Eigen::Vector2d>& dst,
                                   const std::vector<double>& w, Affine2* out) {
  const size_t n = src.size();
  if (n < 3 || dst.size() != n || w.size() != n) return false;
  // Centre both sides: the translation separates out and the 2x2 normal equations stay well conditioned.
  Eigen::Vector2d ms = Eigen::Vector2d::Zero(), md = Eigen::Vector2d::Zero();
  double total = 0;
  for (size_t k = 0; k < n; ++k) {
    ms += w[k] * src[k];
    md += w[k] * dst[k];
    total += w[k];
  }
  if (!(total > 0)) return false;
  ms /= total;
  md /= total;
  Eigen::Matrix2d sxx = Eigen::Matrix2d::Zero(), syx = Eigen::Matrix2d::Zero();
  for (size_t k = 0; k < n; ++k) {
    const Eigen::Vector2d s = src[k] - ms, d = dst[k] - md;
    sxx += w[k] * s * s.transpose();
    syx += w[k] * d * s.transpose();
  }
  const double tr = sxx.trace();
  if (!(tr > 0)) return false;
  // Reject spreads that are (nearly) one-dimensional: the affine is then undetermined across the line.
  if (sxx.determinant() < 1e-8 * tr * tr) return false;
  const Eigen::Matrix2d lin = syx * sxx.inverse();
  out->leftCols<2>() = lin;
  out->col(2) = md - lin * ms;
  return out->allFinite();
}

void AffinePermutationEstimator::estimate(const TriplePair& s, std::vector<Affine2>* models) const {
  int perm[3] = {0, 1, 2};
  do {
    const Eigen::Vector2d d[3] = {s.dst[perm[0]], s.dst[perm[1]], s.dst[perm[2]]};
    Affine2 m;
    if (affine_from_three(s.src, d, &m)) models->push_back(m);
  } while (std::next_permutation(perm, perm + 3));
}

void AffineTripleEstimator::estimate(const TriplePair& s, std::vector<Affine2>* models) const {
  Affine2 m;
  if (affine_from_three(s.src, s.dst, &m)) models->push_back(m);
}

}  // namespace ipd
