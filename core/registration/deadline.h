// The time budget of one registration as a value: a start reading and a budget on a clock that can be
// replaced, so the searches' stop rules are tested with a fake clock instead of timed runs.
#pragma once

#include <chrono>
#include <functional>

namespace ipd {

// Milliseconds on a monotonic clock; tests pass a counter they advance by hand.
using MsClock = std::function<double()>;

inline double steady_ms() {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

class Deadline {
 public:
  Deadline() = default;  // no budget: never passes
  Deadline(double budget_ms, MsClock clock = steady_ms)
      : budget_ms_(budget_ms), clock_(std::move(clock)), start_(budget_ms_ > 0 ? clock_() : 0) {}

  double budget_ms() const { return budget_ms_; }
  // 0 without a budget: the clock is then never read, so nothing can depend on it.
  double elapsed_ms() const { return budget_ms_ > 0 ? clock_() - start_ : 0; }
  bool passed() const { return budget_ms_ > 0 && elapsed_ms() >= budget_ms_; }

 private:
  double budget_ms_ = 0;
  MsClock clock_;
  double start_ = 0;
};

}  // namespace ipd
