#include "core/geometry/point_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ipd {

PointGrid::PointGrid(std::vector<Eigen::Vector2d> points) : points_(std::move(points)) {
  if (points_.size() < kBruteForceBelow) return;
  double x1 = -INFINITY, y1 = -INFINITY;
  x0_ = y0_ = INFINITY;
  for (const auto& p : points_) {
    x0_ = std::min(x0_, p.x());
    y0_ = std::min(y0_, p.y());
    x1 = std::max(x1, p.x());
    y1 = std::max(y1, p.y());
  }
  const double wx = std::max(x1 - x0_, 1e-12), wy = std::max(y1 - y0_, 1e-12);
  // About one point per cell.
  cell_ = std::max(std::sqrt(wx * wy / static_cast<double>(points_.size())), std::max(wx, wy) / 1024.0);
  nx_ = std::clamp(static_cast<int>(wx / cell_) + 1, 1, 1024);
  ny_ = std::clamp(static_cast<int>(wy / cell_) + 1, 1, 1024);
  std::vector<int> count(static_cast<size_t>(nx_) * ny_ + 1, 0);
  std::vector<int> cell_index(points_.size());
  for (size_t i = 0; i < points_.size(); ++i) {
    const int c = cell_of(points_[i].y(), y0_, ny_) * nx_ + cell_of(points_[i].x(), x0_, nx_);
    cell_index[i] = c;
    ++count[c + 1];
  }
  for (size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
  cell_start_ = count;
  order_.resize(points_.size());
  for (size_t i = 0; i < points_.size(); ++i) order_[count[cell_index[i]]++] = static_cast<int>(i);
}

int PointGrid::cell_of(double v, double origin, int n) const {
  const double c = std::floor((v - origin) / cell_);
  if (!(c > 0)) return 0;  // also catches NaN
  if (c >= n - 1) return n - 1;
  return static_cast<int>(c);
}

int PointGrid::nearest(const Eigen::Vector2d& p, double* sq_dist, double below) const {
  int best = -1;
  double best_d = below;  // only strictly closer points are taken
  if (cell_start_.empty()) {
    for (size_t i = 0; i < points_.size(); ++i) {
      const double d = (points_[i] - p).squaredNorm();
      if (d < best_d) {
        best_d = d;
        best = static_cast<int>(i);
      }
    }
    if (sq_dist) *sq_dist = best_d;
    return best;
  }
  const int cx = cell_of(p.x(), x0_, nx_), cy = cell_of(p.y(), y0_, ny_);
  auto scan = [&](int c) {
    for (int k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
      const double d = (points_[order_[k]] - p).squaredNorm();
      if (d < best_d) {
        best_d = d;
        best = order_[k];
      }
    }
  };
  // How far p lies outside the grid along each axis: a query far outside (a wild hypothesis moves rocks
  // anywhere) must still stop after a ring or two instead of scanning the whole grid.
  const double gx1 = x0_ + nx_ * cell_, gy1 = y0_ + ny_ * cell_;
  const double out_x = std::max({0.0, x0_ - p.x(), p.x() - gx1}), out_y = std::max({0.0, y0_ - p.y(), p.y() - gy1});
  for (int r = 0;; ++r) {
    const int lx = cx - r, hx = cx + r, ly = cy - r, hy = cy + r;
    for (int y = std::max(ly, 0); y <= std::min(hy, ny_ - 1); ++y) {
      if (y == ly || y == hy) {
        for (int x = std::max(lx, 0); x <= std::min(hx, nx_ - 1); ++x) scan(y * nx_ + x);
      } else {  // interior cells were searched in earlier rings
        if (lx >= 0) scan(y * nx_ + lx);
        if (hx <= nx_ - 1 && hx != lx) scan(y * nx_ + hx);
      }
    }
    // Lower bound on the distance to any cell outside this ring, over the sides that still have cells.
    double bound2 = std::numeric_limits<double>::infinity();  // squared
    bool more = false;
    auto side = [&](double dx, double dy) {
      dx = std::max(0.0, dx), dy = std::max(0.0, dy);
      bound2 = std::min(bound2, dx * dx + dy * dy);
      more = true;
    };
    if (lx > 0) side(p.x() - (x0_ + lx * cell_), out_y);
    if (hx < nx_ - 1) side(x0_ + (hx + 1) * cell_ - p.x(), out_y);
    if (ly > 0) side(out_x, p.y() - (y0_ + ly * cell_));
    if (hy < ny_ - 1) side(out_x, y0_ + (hy + 1) * cell_ - p.y());
    if (!more) break;
    if (bound2 >= best_d) break;  // never while best_d is infinite: bound2 is finite when more is set
    if (!std::isfinite(p.x()) || !std::isfinite(p.y())) break;
  }
  if (sq_dist) *sq_dist = best_d;
  return best;
}

void PointGrid::within(const Eigen::Vector2d& p, double radius, std::vector<int>* out) const {
  out->clear();
  const double r2 = radius * radius;
  if (cell_start_.empty()) {
    for (size_t i = 0; i < points_.size(); ++i)
      if ((points_[i] - p).squaredNorm() <= r2) out->push_back(static_cast<int>(i));
    return;
  }
  const int lx = cell_of(p.x() - radius, x0_, nx_), hx = cell_of(p.x() + radius, x0_, nx_);
  const int ly = cell_of(p.y() - radius, y0_, ny_), hy = cell_of(p.y() + radius, y0_, ny_);
  for (int y = ly; y <= hy; ++y)
    for (int x = lx; x <= hx; ++x) {
      const int c = y * nx_ + x;
      for (int k = cell_start_[c]; k < cell_start_[c + 1]; ++k)
        if ((points_[order_[k]] - p).squaredNorm() <= r2) out->push_back(order_[k]);
    }
}

}  // namespace ipd
