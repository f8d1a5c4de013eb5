// The Rock pairs scatter as a grid of small cells: a 10,000-scene study has 300,000 counted pairs, far more
// than a plot has room for, so the view draws one square per occupied cell (shaded by how many pairs fall in
// it) instead of one per pair. Binned once when the points, the axes, the plot's size or the selection
// change; a frame then costs the occupied cells, never the pairs. Pure: no drawing.
#pragma once

#include <utility>
#include <vector>

#include "core/session/rock_pair_points.h"

namespace ipd {

// A scatter's data ranges: x in [x0, x1], y in [y0, y1] (x1 > x0, y1 > y0).
struct ScatterRange {
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
};

struct DensityCell {
  int cx = 0, cy = 0;  // column from the left, row from the bottom
  int count = 0;       // pairs in the cell
  int selected = 0;    // of them marked (the selection's pairs)
  int first = -1;      // the lowest point index in the cell (hover and click name this pair)
};

struct PairDensity {
  int cells_x = 0, cells_y = 0;
  std::vector<DensityCell> cells;  // occupied cells only, by first point index
  int max_count = 0;
  int shown = 0;  // points with finite values on both axes (the others have no place on the plot)
};

// Bins `points` on axes (ax, ay) into cells_x x cells_y cells over `range`; a value outside the range goes to
// the edge cell. `box` (may be null): counts the points inside it per cell.
PairDensity bin_pair_points(const std::vector<RockPairPoint>& points, PairAxis ax, PairAxis ay,
                            const ScatterRange& range, int cells_x, int cells_y, const std::vector<char>* marked);

// An axis's range for the scatter: [0, 1] for the values that live there (performance, confidence,
// position), [0, a round number at or above the largest value] for |diff| and size (1 when none is above 0).
std::pair<double, double> scatter_axis_range(const std::vector<RockPairPoint>& points, PairAxis axis);

// The axis's round upper end: 1, 2, 2.5 or 5 x 10^k, the smallest at or above `largest` (1 for <= 0).
double round_up_nicely(double largest);

}  // namespace ipd
