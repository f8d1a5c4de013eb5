// The confidence threshold T, one rule for the engine, the studio, the figures and the detection metrics.
#pragma once

#include <vector>

#include "core/geometry/geometry.h"

namespace ipd {

// A prediction counts at threshold T when its conf >= T (one at exactly T is kept); T <= 0 keeps every
// prediction, even one whose conf is a rounding below 0 (label files allow values a tolerance outside [0, 1]).
inline bool kept_at_threshold(const Box& prediction, double threshold) {
  return threshold <= 0 || prediction.conf >= threshold;
}

// The predictions kept at threshold T, in their order.
inline std::vector<Box> predictions_kept(const std::vector<Box>& predictions, double threshold) {
  std::vector<Box> kept;
  for (const Box& p : predictions)
    if (kept_at_threshold(p, threshold)) kept.push_back(p);
  return kept;
}

}  // namespace ipd
