#include "core/registration/consensus/consensus_search.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "core/geometry/point_grid.h"
#include "core/registration/consensus/consensus_tuning.h"

namespace ipd::detail {

// Each point's k nearest other points, nearest first (ties by index; coincident points left out: a duplicate
// of the rock itself spans nothing). Grid queries in a disc that doubles until it holds k points, so the cost
// is about n k log n, not n^2.
std::vector<std::vector<int>> nearest_neighbours(const std::vector<Eigen::Vector2d>& p, int k,
                                                 const Deadline* deadline) {
  const int n = static_cast<int>(p.size());
  std::vector<std::vector<int>> nn(n);
  const int kk = std::min(k, n - 1);
  if (kk <= 0) return nn;
  const PointGrid grid(p);
  Eigen::Vector2d lo = p[0], hi = p[0];
  for (const auto& q : p) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  const double diagonal = (hi - lo).norm();
  // A disc expected to hold about k + 1 points of a uniform layout.
  double r0 = std::sqrt(std::max((hi - lo).prod(), 0.0) * (kk + 1) / (M_PI * n));
  if (!(r0 > 0)) r0 = diagonal > 0 ? diagonal / n : 1.0;
  std::vector<int> near;
  std::vector<std::pair<double, int>> d;
  for (int i = 0; i < n; ++i) {
    if (deadline != nullptr && (i & 255) == 0 && deadline->passed()) break;
    for (double r = r0;; r *= 2) {
      grid.within(p[i], r, &near);
      // Every point is inside once the disc covers the layout (or the radius stops growing).
      if (static_cast<int>(near.size()) - 1 >= kk || r > 2 * diagonal || !(r * 2 > r)) break;
    }
    if (static_cast<int>(near.size()) - 1 < kk) {  // not enough in the disc: take all (cannot happen above)
      near.resize(n);
      std::iota(near.begin(), near.end(), 0);
    }
    d.clear();
    for (int j : near)
      if (j != i) d.emplace_back((p[j] - p[i]).squaredNorm(), j);
    std::partial_sort(d.begin(), d.begin() + kk, d.end());
    for (int t = 0; t < kk; ++t)
      if (d[t].first > 0) nn[i].push_back(d[t].second);
  }
  return nn;
}

namespace {
// ln Γ(x) without lgamma's write to the global `signgam`: registrations run on many threads at once.
double log_gamma(double x) {
  int sign = 0;
  return ::lgamma_r(x, &sign);
}
}  // namespace

// P(X >= k) for X ~ Binomial(n, p), summed in log space.
double binomial_tail(int n, double p, int k) {
  if (k <= 0) return 1.0;
  if (k > n || p <= 0) return 0.0;
  if (p >= 1) return 1.0;
  double tail = 0;
  for (int x = k; x <= n; ++x)
    tail += std::exp(log_gamma(n + 1.0) - log_gamma(x + 1.0) - log_gamma(n - x + 1.0) + x * std::log(p) +
                     (n - x) * std::log1p(-p));
  return std::min(1.0, tail);
}

// The translations most (A, B) rock pairs agree on once A's rocks are mapped by `lin`: votes binned at
// `bin`, the mean of each of the `top` fullest bins (holding at least two votes), fullest first. A rocks
// are subsampled to about 16 so the cost stays linear in B.
std::vector<Eigen::Vector2d> top_translations(const Eigen::Matrix2d& lin, const std::vector<Eigen::Vector2d>& a,
                                              const std::vector<Eigen::Vector2d>& b, double bin, size_t top) {
  struct Bin {
    int count;
    Eigen::Vector2d sum;
    std::uint64_t key;
  };
  // Votes sorted by bin key (stably, so each bin sums its votes in the order they were cast), then counted run
  // by run; equally full bins are ranked by key, so the order depends on nothing but the votes. A sort of a
  // few hundred keys costs less than the hash map it replaced (one allocation per bin).
  // kTuning.translation_voters A rocks vote (every k-th), so the votes cost no n^2.
  const size_t stride = std::max<size_t>(1, a.size() / kTuning.translation_voters);
  std::vector<std::pair<std::uint64_t, Eigen::Vector2d>> votes;
  votes.reserve((a.size() / stride + 1) * b.size());
  for (size_t i = 0; i < a.size(); i += stride) {
    const Eigen::Vector2d p = lin * a[i];
    for (const auto& q : b) {
      const Eigen::Vector2d t = q - p;
      // Bins centred on multiples of `bin`, not starting there: an exact shift of 0 along an axis (a grid
      // moved along the other one) lands at +-1e-17 and was split between two bins, losing to lesser shifts.
      // Bin indices may be negative: pack them as unsigned (shifting a negative value is undefined).
      const auto kx = static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(t.x() / bin + 0.5)));
      const auto ky = static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(t.y() / bin + 0.5)));
      votes.emplace_back((kx << 32) ^ (ky & 0xffffffffull), t);
    }
  }
  std::stable_sort(votes.begin(), votes.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<Bin> bins;
  for (const auto& [key, t] : votes) {
    if (bins.empty() || bins.back().key != key) bins.push_back({0, Eigen::Vector2d(0, 0), key});
    ++bins.back().count;
    bins.back().sum += t;
  }
  const size_t n = std::min(top, bins.size());
  std::partial_sort(bins.begin(), bins.begin() + n, bins.end(),
                    [](const Bin& x, const Bin& y) { return x.count != y.count ? x.count > y.count : x.key < y.key; });
  std::vector<Eigen::Vector2d> out;
  for (size_t k = 0; k < n && bins[k].count >= 2; ++k) out.push_back(bins[k].sum / bins[k].count);
  return out;
}

}  // namespace ipd::detail
