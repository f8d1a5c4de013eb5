// The time budget of one registration as a value: a start reading and a budget on a clock that can be
// replaced, so the searches' stop rule is tested with a fake clock instead of timed runs.
#pragma once

#include <algorithm>
#include <chrono>
#include <functional>
#include <optional>
#include <utility>

#include "core/registration/robust_loop.h"

namespace ipd {

// Milliseconds on a monotonic clock; tests pass a counter they set by hand.
using MsClock = std::function<double()>;

inline double steady_ms() {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The pure stop rule read before each sample is drawn: the trial cap first (it never depends on time, so results
// without a budget are the same on any machine), then the time budget (0: none). The budget is read before every
// sample, not every few: one sample on 5,000 rocks can cost more than the whole budget.
inline std::optional<StopReason> stop_before_sample(int trials, int max_trials, double elapsed_ms, double budget_ms) {
  if (trials >= max_trials) return StopReason::kMaxTrials;
  if (budget_ms > 0 && elapsed_ms >= budget_ms) return StopReason::kTimeBudget;
  return std::nullopt;
}

class Deadline {
 public:
  Deadline() = default;  // no budget: never passes
  explicit Deadline(double budget_ms, MsClock clock = steady_ms)
      : budget_ms_(budget_ms), clock_(std::move(clock)), start_(budget_ms_ > 0 ? clock_() : 0) {}

  double budget_ms() const { return budget_ms_; }
  bool has_budget() const { return budget_ms_ > 0; }
  // When passed() comes: the budget less what is kept back (0: no budget).
  double ends_at_ms() const { return budget_ms_ - reserve_ms_; }
  // 0 without a budget: the clock is then never read, so nothing can depend on it.
  double elapsed_ms() const { return budget_ms_ > 0 ? clock_() - start_ : 0; }
  bool passed() const { return budget_ms_ > 0 && elapsed_ms() >= budget_ms_ - reserve_ms_; }

  // The same deadline with `ms` of its budget kept back (at most half of it): passed() comes that much sooner, so
  // the stages before the last one end early enough to leave it its time; whole() is the last one's deadline.
  Deadline keeping_back(double ms) const {
    Deadline d = *this;
    d.reserve_ms_ = std::clamp(ms, 0.0, budget_ms_ / 2);
    return d;
  }
  Deadline whole() const {
    Deadline d = *this;
    d.reserve_ms_ = 0;
    return d;
  }

 private:
  double budget_ms_ = 0;
  double reserve_ms_ = 0;
  MsClock clock_;
  double start_ = 0;
};

// A sampler that proposes nothing more once the deadline has passed: the robust loop (which checks its trial
// cap before asking) then ends, and `spent` tells the method that it was the budget, not exhaustion.
template <typename Inner>
struct DeadlineSampler {
  Inner& inner;
  const Deadline& deadline;
  int max_trials;
  int drawn = 0;
  bool spent = false;

  template <typename Sample>
  bool next(Sample* s) {
    if (stop_before_sample(drawn, max_trials, deadline.elapsed_ms(), deadline.ends_at_ms()) ==
        StopReason::kTimeBudget) {
      spent = true;
      return false;
    }
    if (!inner.next(s)) {
      spent = deadline.passed();  // a sampler that read the deadline itself stopped on it (never without a budget)
      return false;
    }
    ++drawn;
    return true;
  }
  // The loop's stop reason, with exhaustion read as the budget when the budget caused it.
  StopReason stop(StopReason loop) const {
    return spent && loop == StopReason::kExhausted ? StopReason::kTimeBudget : loop;
  }
};

}  // namespace ipd
