#include "core/session/pair_density.h"

#include <algorithm>
#include <cmath>

namespace ipd {

PairDensity bin_pair_points(const std::vector<RockPairPoint>& points, PairAxis ax, PairAxis ay,
                            const ScatterRange& range, int cells_x, int cells_y, const std::vector<char>* marked) {
  PairDensity out;
  out.cells_x = std::max(1, cells_x);
  out.cells_y = std::max(1, cells_y);
  // Grid slot -> index into out.cells (-1: empty).
  std::vector<int> slot(static_cast<size_t>(out.cells_x) * out.cells_y, -1);
  const double sx = out.cells_x / (range.x1 - range.x0), sy = out.cells_y / (range.y1 - range.y0);
  for (size_t i = 0; i < points.size(); ++i) {
    const double x = axis_value(points[i], ax), y = axis_value(points[i], ay);
    if (!std::isfinite(x) || !std::isfinite(y)) continue;
    ++out.shown;
    // floor, then clamp: the range's upper end belongs to the last cell.
    const int cx = static_cast<int>(std::clamp(std::floor((x - range.x0) * sx), 0.0, out.cells_x - 1.0));
    const int cy = static_cast<int>(std::clamp(std::floor((y - range.y0) * sy), 0.0, out.cells_y - 1.0));
    int& s = slot[static_cast<size_t>(cy) * out.cells_x + cx];
    if (s < 0) {
      s = static_cast<int>(out.cells.size());
      DensityCell c;
      c.cx = cx, c.cy = cy, c.first = static_cast<int>(i);
      out.cells.push_back(c);
    }
    DensityCell& c = out.cells[s];
    ++c.count;
    if (marked && i < marked->size() && (*marked)[i]) ++c.selected;
    out.max_count = std::max(out.max_count, c.count);
  }
  return out;
}

double round_up_nicely(double largest) {
  if (!(largest > 0) || !std::isfinite(largest)) return 1;
  const double mag = std::pow(10.0, std::floor(std::log10(largest)));
  for (const double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (m * mag >= largest * (1 - 1e-12)) return m * mag;
  return 10 * mag;
}

std::pair<double, double> scatter_axis_range(const std::vector<RockPairPoint>& points, PairAxis axis) {
  if (axis != PairAxis::kSize && axis != PairAxis::kAbsDiff) return {0, 1};
  double hi = 0;
  for (const auto& p : points) {
    const double v = axis_value(p, axis);
    if (std::isfinite(v)) hi = std::max(hi, v);
  }
  return {0, round_up_nicely(hi)};
}

}  // namespace ipd
