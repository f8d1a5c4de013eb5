#include "core/rank/holm.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace ipd {

std::vector<double> holm_adjusted(const std::vector<double>& p) {
  std::vector<double> out(p.size(), std::nan(""));
  std::vector<size_t> order;
  for (size_t k = 0; k < p.size(); ++k)
    if (!std::isnan(p[k])) order.push_back(k);
  std::stable_sort(order.begin(), order.end(), [&](size_t x, size_t y) { return p[x] < p[y]; });
  const double m = static_cast<double>(order.size());
  double running = 0;  // the step-down maximum keeps the adjusted values in the raw values' order
  for (size_t i = 0; i < order.size(); ++i) {
    running = std::max(running, std::min(1.0, (m - static_cast<double>(i)) * p[order[i]]));
    out[order[i]] = running;
  }
  return out;
}

}  // namespace ipd
