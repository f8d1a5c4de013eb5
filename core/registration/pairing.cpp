#include "core/registration/pairing.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

#include "core/geometry/point_grid.h"
#include "core/registration/deadline.h"

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
    if (transposed)
      pairs.emplace_back(j - 1, i - 1);
    else
      pairs.emplace_back(i - 1, j - 1);
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

RockPairs sparse_max_weight_assignment(const std::vector<WeightedEdge>& edges, int rows, int cols, double min_weight) {
  RockPairs pairs;
  if (rows == 0 || cols == 0) return pairs;
  // Columns 0..cols-1 are B's; column cols + r is row r's own "unassigned" column (cost 0, only r reaches
  // it). Costs are -weight; reduced costs cost - u[row] - v[col] stay >= 0 on every edge of a row already
  // placed, and free columns keep v = 0, so each new row's cheapest augmenting path is a Dijkstra search.
  std::vector<int> first(rows + 1, 0);
  for (const WeightedEdge& e : edges)
    if (e.weight > min_weight) ++first[e.row + 1];
  for (int r = 0; r < rows; ++r) first[r + 1] += first[r];
  std::vector<std::pair<int, double>> adj(first[rows]);  // (column, cost), grouped by row
  {
    std::vector<int> at(first.begin(), first.end() - 1);
    for (const WeightedEdge& e : edges)
      if (e.weight > min_weight) adj[at[e.row]++] = {e.col, -e.weight};
  }
  const int ncols = cols + rows;
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> u(rows, 0), v(ncols, 0), dist(ncols, inf);
  std::vector<int> row_of(ncols, -1), col_of(rows, -1), pred(ncols, -1), touched;
  std::vector<char> done(ncols, 0);
  using Item = std::pair<double, int>;  // (distance, column): ties go to the lower column, deterministically
  for (int i0 = 0; i0 < rows; ++i0) {
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
    touched.clear();
    auto relax = [&](int row, double base) {
      auto reach = [&](int c, double cost) {
        if (done[c]) return;  // settled (a rounding-level negative reduced cost must not re-open it)
        const double d = base + cost - u[row] - v[c];
        if (d < dist[c]) {
          if (dist[c] == inf) touched.push_back(c);
          dist[c] = d, pred[c] = row;
          heap.push({d, c});
        }
      };
      for (int k = first[row]; k < first[row + 1]; ++k) reach(adj[k].first, adj[k].second);
      reach(cols + row, 0.0);
    };
    relax(i0, 0.0);
    int end = -1;
    double total = 0;
    std::vector<int> finalized;
    while (!heap.empty()) {
      const auto [d, c] = heap.top();
      heap.pop();
      if (done[c] || d > dist[c]) continue;
      done[c] = 1;
      if (row_of[c] < 0) {
        end = c, total = d;
        break;
      }
      finalized.push_back(c);
      relax(row_of[c], d);
    }
    // Potentials: every column settled before the free one moves by its slack, which keeps the matched
    // edges at reduced cost 0 and every other edge at >= 0.
    for (int c : finalized) {
      const double delta = total - dist[c];
      v[c] -= delta;
      u[row_of[c]] += delta;
    }
    u[i0] += total;
    for (int c = end; c >= 0;) {  // augment along the predecessors
      const int r = pred[c], previous = col_of[r];
      row_of[c] = r, col_of[r] = c;
      c = r == i0 ? -1 : previous;
    }
    for (int c : touched) dist[c] = inf, done[c] = 0, pred[c] = -1;
  }
  for (int r = 0; r < rows; ++r)
    if (col_of[r] >= 0 && col_of[r] < cols) pairs.emplace_back(r, col_of[r]);
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace ipd

namespace ipd {
// Above this much dense-solver work (min(rows, cols)^2 x max(rows, cols), ~0.1 s) a component is solved
// sparsely: its rows x cols matrix would take gigabytes and minutes for thousands of packed rocks.
constexpr double kDenseAssignmentWork = 1e8;

PairingRule pairing_rule(const RegistrationOptions& o) {
  return {o.min_pair_iou, o.pair_noise_floor, o.pair_max_size_ratio, o.aspect_ratio()};
}

double pair_weight(const Box& moved_a, const Box& b, const PairingRule& rule) {
  if (moved_a.cls != b.cls) return 0;  // a rock pairs only with a rock of its class
  const double overlap = iou(moved_a, b);
  if (overlap > rule.min_iou) return overlap;
  const double small = std::min(moved_a.area(), b.area()), large = std::max(moved_a.area(), b.area());
  if (!(small > 0) || large > rule.max_size_ratio * rule.max_size_ratio * small) return 0;
  const double d = std::hypot(moved_a.cx - b.cx, (moved_a.cy - b.cy) / rule.aspect);  // in widths
  if (!(d < rule.noise_floor)) return 0;
  // Scaled by min_iou so every overlap outweighs it (a floor keeps near misses alive when min_iou is 0).
  return std::max(rule.min_iou, 1e-6) * (1 - d / rule.noise_floor);
}

namespace {

struct Edge {
  int i, j;
  double w;
};

// Every (A, B) pair the rule allows, found by sweeping B sorted by left edge: each moved A box only looks at B
// boxes that can overlap it in x or have their centre within the noise floor.
std::vector<Edge> sweep_edges(const std::vector<Box>& moved, const std::vector<Box>& b, const PairingRule& rule) {
  const int n = static_cast<int>(moved.size()), m = static_cast<int>(b.size());
  std::vector<int> b_by_x0(m);
  for (int j = 0; j < m; ++j) b_by_x0[j] = j;
  std::sort(b_by_x0.begin(), b_by_x0.end(), [&](int x, int y) { return b[x].x0() < b[y].x0(); });
  double widest_b = 0;
  for (const Box& bx : b) widest_b = std::max(widest_b, bx.w);
  std::vector<Edge> edges;
  for (int i = 0; i < n; ++i) {
    const double lo = std::min(moved[i].x0(), moved[i].cx - rule.noise_floor) - widest_b,
                 hi = std::max(moved[i].x1(), moved[i].cx + rule.noise_floor);
    auto it = std::lower_bound(b_by_x0.begin(), b_by_x0.end(), lo, [&](int j, double v) { return b[j].x0() < v; });
    for (; it != b_by_x0.end() && b[*it].x0() <= hi; ++it) {
      const double w = pair_weight(moved[i], b[*it], rule);
      if (w > 0) edges.push_back({i, *it, w});
    }
  }
  return edges;
}

// The same edges from a grid over B's centres, in a time that does not grow with the widest box: each moved A
// box asks the grid for centres close enough to overlap it (or within the noise floor); the few B boxes far
// larger than the typical one are tried against every A box instead of widening every query.
std::vector<Edge> grid_edges(const std::vector<Box>& moved, const std::vector<Box>& b, const PairingRule& rule) {
  const int n = static_cast<int>(moved.size()), m = static_cast<int>(b.size());
  std::vector<double> half(m);
  for (int j = 0; j < m; ++j) half[j] = 0.5 * std::sqrt(b[j].w * b[j].w + b[j].h * b[j].h);
  std::vector<double> sorted = half;
  std::nth_element(sorted.begin(), sorted.begin() + m / 2, sorted.end());
  const double large = 4 * sorted[m / 2];
  std::vector<Eigen::Vector2d> centres;
  std::vector<int> index_of, larger;
  double reach_b = 0;  // the largest half-diagonal among the boxes in the grid
  for (int j = 0; j < m; ++j) {
    if (half[j] > large) {
      larger.push_back(j);
      continue;
    }
    centres.emplace_back(b[j].cx, b[j].cy);
    index_of.push_back(j);
    reach_b = std::max(reach_b, half[j]);
  }
  const PointGrid grid(centres);
  // Centres of a near miss are within the floor in pixels: noise_floor widths across, noise_floor x aspect down.
  const double floor_reach = std::hypot(rule.noise_floor, rule.noise_floor * rule.aspect);
  std::vector<Edge> edges;
  std::vector<int> near;
  for (int i = 0; i < n; ++i) {
    const double half_a = 0.5 * std::sqrt(moved[i].w * moved[i].w + moved[i].h * moved[i].h);
    const double reach = std::max(half_a + reach_b, floor_reach);
    grid.within(Eigen::Vector2d(moved[i].cx, moved[i].cy), reach, &near);
    for (int& k : near) k = index_of[k];
    if (!larger.empty()) {
      near.insert(near.end(), larger.begin(), larger.end());
      std::sort(near.begin(), near.end());
    }
    for (int j : near) {
      const double w = pair_weight(moved[i], b[j], rule);
      if (w > 0) edges.push_back({i, j, w});
    }
  }
  return edges;
}

// The heaviest allowed pair first, each rock taken once (ties by A, then B index): at least half the optimal
// total weight. A pair whose two rocks have no other allowed pair is taken whatever the order, so only the rest
// are sorted (on scattered rocks, most pairs are alone).
void pair_greedily(std::vector<Edge> edges, int n, int m, RockPairs* pairs) {
  std::vector<int> degree_a(n, 0), degree_b(m, 0);
  for (const Edge& e : edges) ++degree_a[e.i], ++degree_b[e.j];
  std::vector<Edge> contested;
  for (const Edge& e : edges) {
    if (degree_a[e.i] == 1 && degree_b[e.j] == 1)
      pairs->emplace_back(e.i, e.j);
    else
      contested.push_back(e);
  }
  std::sort(contested.begin(), contested.end(), [](const Edge& x, const Edge& y) {
    return x.w != y.w ? x.w > y.w : x.i != y.i ? x.i < y.i : x.j < y.j;
  });
  std::vector<char> used_a(n, 0), used_b(m, 0);
  for (const Edge& e : contested) {
    if (used_a[e.i] || used_b[e.j]) continue;
    used_a[e.i] = used_b[e.j] = 1;
    pairs->emplace_back(e.i, e.j);
  }
}

// The optimal one-to-one assignment over `edges`, component by component (see pair_aligned_boxes). With a
// deadline, components not solved when it passes are paired greedily instead, and *greedy says so.
RockPairs solve_components(const std::vector<Edge>& edges, int n, int m, const Deadline* deadline, bool* greedy) {
  // Union-find over A (0..n-1) and B (n..n+m-1).
  std::vector<int> parent(n + m);
  for (int k = 0; k < n + m; ++k) parent[k] = k;
  auto find = [&](int k) {
    while (parent[k] != k) k = parent[k] = parent[parent[k]];
    return k;
  };
  for (const Edge& e : edges) parent[find(e.i)] = find(n + e.j);
  // Edges grouped by component (sorted by root, then by position: each group keeps the order the whole
  // problem would see), without a list per rock: most components are one A rock and one B rock.
  std::vector<std::pair<int, int>> by_root(edges.size());
  for (size_t k = 0; k < edges.size(); ++k) by_root[k] = {find(edges[k].i), static_cast<int>(k)};
  std::sort(by_root.begin(), by_root.end());
  RockPairs pairs;
  std::vector<int> local_a(n, -1), local_b(m, -1), rows, cols;
  std::vector<double> w;
  int solved = 0;
  for (size_t lo = 0; lo < by_root.size();) {
    // The deadline is read every 64 components: most are one pair, and a clock read costs about as much.
    if (deadline != nullptr && (solved++ & 63) == 0 && deadline->passed()) {
      std::vector<Edge> rest;
      for (size_t q = lo; q < by_root.size(); ++q) rest.push_back(edges[by_root[q].second]);
      pair_greedily(std::move(rest), n, m, &pairs);
      *greedy = true;
      break;
    }
    size_t hi = lo + 1;
    while (hi < by_root.size() && by_root[hi].first == by_root[lo].first) ++hi;
    if (hi - lo == 1) {  // one A rock, one B rock: the pair itself (the rule allows it)
      const Edge& e = edges[by_root[lo].second];
      pairs.emplace_back(e.i, e.j);
      lo = hi;
      continue;
    }
    rows.clear(), cols.clear();  // global indices, in increasing order as the whole problem would see them
    for (size_t q = lo; q < hi; ++q) {
      const Edge& e = edges[by_root[q].second];
      if (local_a[e.i] < 0) local_a[e.i] = 0, rows.push_back(e.i);
      if (local_b[e.j] < 0) local_b[e.j] = 0, cols.push_back(e.j);
    }
    std::sort(rows.begin(), rows.end());
    std::sort(cols.begin(), cols.end());
    for (size_t r = 0; r < rows.size(); ++r) local_a[rows[r]] = static_cast<int>(r);
    for (size_t c = 0; c < cols.size(); ++c) local_b[cols[c]] = static_cast<int>(c);
    const double nr = static_cast<double>(rows.size()), nc = static_cast<double>(cols.size());
    if (std::min(nr, nc) * std::min(nr, nc) * std::max(nr, nc) > kDenseAssignmentWork) {
      // One giant overlap component (densely packed boxes): the sparse solver, same optimum.
      std::vector<WeightedEdge> local;
      local.reserve(hi - lo);
      for (size_t q = lo; q < hi; ++q) {
        const Edge& e = edges[by_root[q].second];
        local.push_back({local_a[e.i], local_b[e.j], e.w});
      }
      for (const auto& [r, c] :
           sparse_max_weight_assignment(local, static_cast<int>(rows.size()), static_cast<int>(cols.size()), 0.0))
        pairs.emplace_back(rows[r], cols[c]);
      lo = hi;
      continue;
    }
    w.assign(rows.size() * cols.size(), 0.0);
    for (size_t q = lo; q < hi; ++q) {
      const Edge& e = edges[by_root[q].second];
      w[local_a[e.i] * cols.size() + local_b[e.j]] = e.w;
    }
    for (const auto& [r, c] :
         max_weight_assignment(w, static_cast<int>(rows.size()), static_cast<int>(cols.size()), 0.0))
      pairs.emplace_back(rows[r], cols[c]);
    lo = hi;
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

std::vector<Box> moved_boxes(const Affine2& a_to_b, const std::vector<Box>& a) {
  std::vector<Box> moved(a.size());
  for (size_t i = 0; i < a.size(); ++i) moved[i] = transform_box(a_to_b, a[i]);
  return moved;
}

}  // namespace

RockPairs pair_aligned_boxes(const Affine2& a_to_b, const std::vector<Box>& a, const std::vector<Box>& b,
                             const PairingRule& rule) {
  // Boxes overlap only their neighbours, so the overlap graph falls apart into small connected components,
  // and the optimal assignment is the union of each component's optimum (no allowed pair crosses two). Solving
  // per component keeps thousands of rocks a side near-linear instead of one cubic assignment.
  const std::vector<Box> moved = moved_boxes(a_to_b, a);
  return solve_components(sweep_edges(moved, b, rule), static_cast<int>(a.size()), static_cast<int>(b.size()), nullptr,
                          nullptr);
}

RockPairs pair_aligned_boxes_within(const Affine2& a_to_b, const std::vector<Box>& a, const std::vector<Box>& b,
                                    const PairingRule& rule, const Deadline& deadline, bool* greedy) {
  *greedy = false;
  const int n = static_cast<int>(a.size()), m = static_cast<int>(b.size());
  if (n == 0 || m == 0) return {};
  // Read before the first component: a deadline already passed pairs everything greedily.
  return solve_components(grid_edges(moved_boxes(a_to_b, a), b, rule), n, m, &deadline, greedy);
}
}  // namespace ipd
