// Exact nearest-neighbour queries on a fixed 2-D point set: a uniform grid with ring search, brute force
// for small sets. Registration scores every hypothesis with it, so it must be cheap.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

namespace ipd {

class PointGrid {
 public:
  PointGrid() = default;
  explicit PointGrid(std::vector<Eigen::Vector2d> points);

  // Index of the nearest point and its squared distance; -1 when the set is empty. With `below`: only points
  // closer than sqrt(below) count (-1 and *sq_dist = below when none is), and the search stops at that
  // radius: a registration gate needs no partner further out, and a wrong hypothesis maps many rocks into
  // empty space where the unbounded search would widen ring after ring.
  int nearest(const Eigen::Vector2d& p, double* sq_dist, double below = INFINITY) const;
  // Indices of points within `radius` of p.
  void within(const Eigen::Vector2d& p, double radius, std::vector<int>* out) const;

  const std::vector<Eigen::Vector2d>& points() const { return points_; }
  size_t size() const { return points_.size(); }

 private:
  static constexpr size_t kBruteForceBelow = 24;
  std::vector<Eigen::Vector2d> points_;
  double x0_ = 0, y0_ = 0, cell_ = 1;
  int nx_ = 0, ny_ = 0;
  std::vector<int> cell_start_;  // CSR layout: points of cell c are order_[cell_start_[c] .. cell_start_[c+1])
  std::vector<int> order_;
  int cell_of(double v, double origin, int n) const;
};

}  // namespace ipd
