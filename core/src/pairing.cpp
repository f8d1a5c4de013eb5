#include "ipd/pairing.h"

#include <algorithm>
#include <limits>

#include "ipd/point_grid.h"

namespace ipd {

RockPairs mutual_nearest_pairs(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b,
                               double gate) {
  RockPairs pairs;
  if (a.empty() || b.empty()) return pairs;
  const PointGrid ga(a), gb(b);
  const double g2 = gate * gate;
  for (size_t i = 0; i < a.size(); ++i) {
    double d = 0;
    const int j = gb.nearest(a[i], &d);
    if (j < 0 || d > g2) continue;
    if (ga.nearest(b[j], nullptr) == static_cast<int>(i)) pairs.emplace_back(static_cast<int>(i), j);
  }
  return pairs;
}

RockPairs max_weight_assignment(const std::vector<double>& weights, int rows, int cols, double min_weight) {
  RockPairs pairs;
  if (rows == 0 || cols == 0) return pairs;
  // Rectangular Hungarian (potentials method, e-maxx), 1-based, with n <= m: the shorter side is the rows, so
  // 10,000 vs 17 rocks costs 17^2 * 10,000 steps instead of padding to a 10,000^2 square.
  const bool transposed = rows > cols;
  const int n = transposed ? cols : rows, m = transposed ? rows : cols;
  auto weight = [&](int r, int c) -> double {  // 0-based, in the solver's orientation
    return transposed ? weights[static_cast<size_t>(c) * cols + r] : weights[static_cast<size_t>(r) * cols + c];
  };
  auto cost = [&](int i, int j) -> double {  // 1-based; weights at or below min_weight are worth nothing
    const double w = weight(i - 1, j - 1);
    return w > min_weight ? -w : 0.0;
  };
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> u(n + 1, 0), v(m + 1, 0), minv(m + 1);
  std::vector<int> p(m + 1, 0), way(m + 1, 0);
  std::vector<char> used(m + 1);
  for (int i = 1; i <= n; ++i) {
    p[0] = i;
    int j0 = 0;
    std::fill(minv.begin(), minv.end(), inf);
    std::fill(used.begin(), used.end(), 0);
    do {
      used[j0] = 1;
      const int i0 = p[j0];
      double delta = inf;
      int j1 = 0;
      for (int j = 1; j <= m; ++j) {
        if (used[j]) continue;
        const double cur = cost(i0, j) - u[i0] - v[j];
        if (cur < minv[j]) {
          minv[j] = cur;
          way[j] = j0;
        }
        if (minv[j] < delta) {
          delta = minv[j];
          j1 = j;
        }
      }
      for (int j = 0; j <= m; ++j) {
        if (used[j]) {
          u[p[j]] += delta;
          v[j] -= delta;
        } else {
          minv[j] -= delta;
        }
      }
      j0 = j1;
    } while (p[j0] != 0);
    do {
      const int j1 = way[j0];
      p[j0] = p[j1];
      j0 = j1;
    } while (j0);
  }
  for (int j = 1; j <= m; ++j) {
    const int i = p[j];
    if (i < 1 || weight(i - 1, j - 1) <= min_weight) continue;
    if (transposed) pairs.emplace_back(j - 1, i - 1);
    else pairs.emplace_back(i - 1, j - 1);
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace ipd

namespace ipd {
RockPairs pair_by_aligned_iou(const Affine2& a_to_b, const std::vector<Box>& a, const std::vector<Box>& b,
                              double min_iou) {
  std::vector<double> w(a.size() * b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    const Box moved = transform_box(a_to_b, a[i]);
    for (size_t j = 0; j < b.size(); ++j) w[i * b.size() + j] = iou(moved, b[j]);
  }
  return max_weight_assignment(w, static_cast<int>(a.size()), static_cast<int>(b.size()), min_iou);
}
}  // namespace ipd
