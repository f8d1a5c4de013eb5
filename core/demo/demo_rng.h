// The generated studies' random numbers (ipd demo, ipd demo --variants): the same study for a seed everywhere.
#pragma once

#include <cstdint>
#include <random>

namespace ipd {

// Deterministic across standard libraries: mt19937_64's output is specified, the distributions are not.
struct DemoRng {
  std::mt19937_64 g;
  explicit DemoRng(std::uint64_t seed) : g(seed) {}
  double uniform(double lo, double hi) {
    return lo + (hi - lo) * (static_cast<double>(g() >> 11) / 9007199254740992.0);
  }
  int below(int n) { return static_cast<int>(g() % static_cast<std::uint64_t>(n)); }
};

}  // namespace ipd
