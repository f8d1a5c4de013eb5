// The time budget's stop rule, on a fake clock: which sample a budget ends the search before, without a timed
// run (the wall-clock bound itself is measured by `ipd bench`).
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <vector>

#include "core/registration/deadline.h"
#include "core/registration/registration_frame.h"  // core/src: internal
#include "core/registration/robust_loop.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

TEST(StopRule, TrialCapComesBeforeTheBudget) {
  EXPECT_EQ(stop_before_sample(10, 10, 99.0, 5.0), StopReason::kMaxTrials);
  EXPECT_EQ(stop_before_sample(3, 10, 5.0, 5.0), StopReason::kTimeBudget);  // the budget is spent at equality
  EXPECT_EQ(stop_before_sample(3, 10, 4.999, 5.0), std::nullopt);
  EXPECT_EQ(stop_before_sample(0, 10, 5.0, 5.0), StopReason::kTimeBudget);  // read before the first sample too
  EXPECT_EQ(stop_before_sample(3, 10, 1e9, 0.0), std::nullopt);             // 0: no budget
}

TEST(StopRule, DeadlineRunsFromItsStartOnTheGivenClock) {
  double now = 100.0;
  const Deadline d(5.0, [&] { return now; });
  EXPECT_DOUBLE_EQ(d.elapsed_ms(), 0.0);
  now = 104.5;
  EXPECT_DOUBLE_EQ(d.elapsed_ms(), 4.5);
  EXPECT_FALSE(d.passed());
  now = 105.0;
  EXPECT_TRUE(d.passed());
}

TEST(StopRule, NoBudgetNeverReadsTheClock) {
  int reads = 0;
  const Deadline d(0.0, [&] { return static_cast<double>(++reads); });
  EXPECT_FALSE(d.passed());
  EXPECT_DOUBLE_EQ(d.elapsed_ms(), 0.0);
  EXPECT_EQ(reads, 0);  // so a search without a budget cannot depend on time
}

// A search whose every sample costs 1 ms on the fake clock.
struct CountingSampler {
  double* now;
  bool next(int* s) {
    *now += 1.0;
    *s = 0;
    return true;
  }
};
struct OneModel {
  void estimate(const int& s, std::vector<int>* out) { out->push_back(s); }
};
struct FlatScorer {
  double score(const int&) { return 1.0; }
  bool worth_refining(int, int, double, double) { return false; }
  void refine(int, int*, double*) {}
  bool cannot_be_beaten(double) { return false; }
};

TEST(StopRule, LoopStopsBeforeTheSampleThatWouldPassTheBudget) {
  double now = 0;
  const Deadline d(4.5, [&] { return now; });
  now = 2.0;  // set-up before the loop counts against the budget
  CountingSampler inner{&now};
  DeadlineSampler<CountingSampler> sampler{inner, d, 1000};
  OneModel estimator;
  FlatScorer scorer;
  RobustLoopOptions lo;
  lo.max_trials = 1000;
  const auto r = run_robust_loop<int, int>(sampler, estimator, scorer, lo);
  EXPECT_EQ(sampler.stop(r.stop), StopReason::kTimeBudget);
  EXPECT_EQ(r.trials, 3);  // at 2, 3 and 4 ms a sample is drawn; at 5 ms the budget of 4.5 is spent
}

TEST(StopRule, TheTrialCapStillEndsATimedLoop) {
  double now = 0;
  const Deadline d(1e9, [&] { return now; });
  CountingSampler inner{&now};
  DeadlineSampler<CountingSampler> sampler{inner, d, 7};
  OneModel estimator;
  FlatScorer scorer;
  RobustLoopOptions lo;
  lo.max_trials = 7;
  const auto r = run_robust_loop<int, int>(sampler, estimator, scorer, lo);
  EXPECT_EQ(sampler.stop(r.stop), StopReason::kMaxTrials);
  EXPECT_EQ(r.trials, 7);
}

// A clock that stands still for its first `still` readings (the deadline's start is one), then jumps 1 s.
MsClock clock_passing_after(int still) {
  auto reads = std::make_shared<int>(0);
  return [reads, still] { return ++*reads <= still ? 0.0 : 1000.0; };
}

RegistrationOptions budget_of_5ms(RegistrationMethod m) {
  RegistrationOptions o;
  o.method = m;
  o.time_budget_ms = 5;
  return o;
}

TEST(StopRule, ConsensusSpentBeforeItsFirstSampleSaysSo) {
  const auto a = test::seven_rocks(0), b = test::seven_rocks(0.05);
  const detail::RegistrationFrame f(a, b, 1.0);
  const auto o = budget_of_5ms(RegistrationMethod::kConsensus);
  const auto out = detail::register_consensus(f, a, b, o, Deadline(5, clock_passing_after(1)));
  EXPECT_EQ(out.stop, StopReason::kTimeBudget);
  EXPECT_EQ(out.trials, 0);
  EXPECT_EQ(out.note, "time budget spent before a plausible affine was found: identity used");
}

TEST(StopRule, ConsensusSpentDuringTheSearchKeepsItsBestUnpolished) {
  const auto a = test::seven_rocks(0), b = test::seven_rocks(0.05);
  const detail::RegistrationFrame f(a, b, 1.0);
  const auto o = budget_of_5ms(RegistrationMethod::kConsensus);
  const auto out = detail::register_consensus(f, a, b, o, Deadline(5, clock_passing_after(2)));
  EXPECT_EQ(out.stop, StopReason::kTimeBudget);
  // The first sample is confirmed at once on seven rocks; the budget is then spent before the stages after
  // the search, which it ends.
  EXPECT_EQ(out.trials, 1);
  EXPECT_EQ(out.note, "time budget spent: the search's best, without the rival placements, polish or second look");
}

TEST(StopRule, CpdReadsTheBudgetBeforeEachEmStep) {
  const auto a = test::seven_rocks(0), b = test::seven_rocks(0.05);
  const detail::RegistrationFrame f(a, b, 1.0);
  const auto o = budget_of_5ms(RegistrationMethod::kCpd);
  const auto out = detail::register_cpd(f, a, b, o, Deadline(5, clock_passing_after(3)));
  EXPECT_EQ(out.stop, StopReason::kTimeBudget);
  EXPECT_EQ(out.trials, 2);
  EXPECT_EQ(out.note, "time budget spent: EM's alignment, not judged against rival placements");
}

TEST(StopRule, PaperSpentBeforeItsFirstSampleSaysSo) {
  const auto a = test::seven_rocks(0), b = test::seven_rocks(0.05);
  const detail::RegistrationFrame f(a, b, 1.0);
  const auto out =
      detail::register_paper(f, budget_of_5ms(RegistrationMethod::kPaper), Deadline(5, clock_passing_after(1)));
  EXPECT_EQ(out.stop, StopReason::kTimeBudget);
  EXPECT_EQ(out.trials, 0);
  EXPECT_EQ(out.note, "time budget spent before a triple was scored: identity used");
}

// A negative budget is a caller's mistake, not "no limit": the loop refuses it with the field and its range.
TEST(StopRule, RobustLoopOptionsNameTheBadField) {
  RobustLoopOptions lo;
  EXPECT_EQ(lo.validate(), "");
  lo.max_trials = -1;
  EXPECT_EQ(lo.validate(), "max_trials must be at least 0, got -1");
  lo.max_trials = 10;
  lo.time_budget_ms = -5;
  EXPECT_EQ(lo.validate(), "time_budget_ms must be a number >= 0 (0: no limit), got -5");
  lo.time_budget_ms = 0;
  lo.max_work = -1;
  EXPECT_EQ(lo.validate(), "max_work must be >= 0 (0: no limit), got -1");
  lo.max_work = 0;
  lo.work_per_model = -2;
  EXPECT_EQ(lo.validate(), "work_per_model must be a number >= 0, got -2");
  double now = 0;
  CountingSampler inner{&now};
  const Deadline d(1e9, [&] { return now; });
  DeadlineSampler<CountingSampler> sampler{inner, d, 7};
  OneModel estimator;
  FlatScorer scorer;
  try {
    run_robust_loop<int, int>(sampler, estimator, scorer, lo);
    FAIL() << "the loop ran with a negative work_per_model";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "robust loop options: work_per_model must be a number >= 0, got -2");
  }
}

}  // namespace
}  // namespace ipd
