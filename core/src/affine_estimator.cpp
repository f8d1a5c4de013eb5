#include "ipd/affine_estimator.h"

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
  // lin = Q P^-1 with P, Q the edge matrices [s1 - s0, s2 - s0]; written out, as the consensus search solves
  // thousands of these per registration (Eigen's comma initialiser and general inverse cost ~3x as much).
  const double p00 = src[1].x() - src[0].x(), p10 = src[1].y() - src[0].y();
  const double p01 = src[2].x() - src[0].x(), p11 = src[2].y() - src[0].y();
  const double q00 = dst[1].x() - dst[0].x(), q10 = dst[1].y() - dst[0].y();
  const double q01 = dst[2].x() - dst[0].x(), q11 = dst[2].y() - dst[0].y();
  const double inv_det = 1.0 / (p00 * p11 - p01 * p10);
  const double i00 = p11 * inv_det, i01 = -p01 * inv_det, i10 = -p10 * inv_det, i11 = p00 * inv_det;
  Affine2& m = *out;
  m(0, 0) = q00 * i00 + q01 * i10;
  m(0, 1) = q00 * i01 + q01 * i11;
  m(1, 0) = q10 * i00 + q11 * i10;
  m(1, 1) = q10 * i01 + q11 * i11;
  m(0, 2) = dst[0].x() - (m(0, 0) * src[0].x() + m(0, 1) * src[0].y());
  m(1, 2) = dst[0].y() - (m(1, 0) * src[0].x() + m(1, 1) * src[0].y());
  return m.allFinite();
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
