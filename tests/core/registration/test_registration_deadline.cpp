// The time budget's stop rule, on a fake clock: which sample a budget ends the search before, without a timed
// run (the wall-clock bound itself is measured by `ipd bench`).
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/registration/deadline.h"
#include "core/registration/pairing.h"
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

// The share kept back for the final pairing ends the stages before it sooner (never more than half the budget);
// the pairing's own deadline is the whole budget.
TEST(StopRule, KeepingBackEndsTheStagesSoonerNotThePairing) {
  double now = 0;
  const Deadline whole(10.0, [&] { return now; });
  const Deadline stages = whole.keeping_back(3.0);
  EXPECT_DOUBLE_EQ(stages.ends_at_ms(), 7.0);
  now = 7.0;
  EXPECT_TRUE(stages.passed());
  EXPECT_FALSE(whole.passed());
  EXPECT_FALSE(stages.whole().passed());
  EXPECT_DOUBLE_EQ(whole.keeping_back(8.0).ends_at_ms(), 5.0);       // at most half the budget
  EXPECT_DOUBLE_EQ(Deadline().keeping_back(3.0).ends_at_ms(), 0.0);  // no budget: still none
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
  bool confirm_or_pick_for_refinement(int, int, double, double) { return false; }
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
  EXPECT_EQ(r.samples, 3);  // at 2, 3 and 4 ms a sample is drawn; at 5 ms the budget of 4.5 is spent
}

// A sampler that reads the deadline itself (consensus' expands hundreds of rock pairs per call) and stops on it:
// the search was ended by the budget, not by running out of hypotheses.
struct DeadlineReadingSampler {
  const Deadline& deadline;
  bool next(int* s) {
    *s = 0;
    return !deadline.passed();
  }
};

TEST(StopRule, ASamplerStoppedByTheDeadlineEndsOnTheBudget) {
  int reads = 0;  // the deadline's start, the wrapper's reading: still 0 ms; the inner sampler's: 1 s
  const Deadline d(5.0, [&] { return ++reads <= 2 ? 0.0 : 1000.0; });
  DeadlineReadingSampler inner{d};
  DeadlineSampler<DeadlineReadingSampler> sampler{inner, d, 1000};
  int s = 0;
  EXPECT_FALSE(sampler.next(&s));
  EXPECT_EQ(reads, 4);  // the wrapper read once more after the inner sampler said no
  EXPECT_EQ(sampler.stop(StopReason::kExhausted), StopReason::kTimeBudget);
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
  EXPECT_EQ(r.samples, 7);
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

// Passed at the first reading after the start: consensus is cut in its set-up (B's spacing), answers the identity
// and pairs greedily, and says both.
TEST(StopRule, ConsensusSpentInItsSetUpSaysSo) {
  const auto a = test::seven_rocks(0), b = test::seven_rocks(0.05);
  const detail::RegistrationFrame f(a, b, 1.0);
  const auto o = budget_of_5ms(RegistrationMethod::kConsensus);
  const auto out = detail::register_consensus(f, a, b, o, Deadline(5, clock_passing_after(1)));
  EXPECT_EQ(out.stop, StopReason::kTimeBudget);
  EXPECT_EQ(out.samples, 0);
  EXPECT_EQ(out.note,
            "time budget spent while setting up the search: identity used; time budget spent before the rocks were "
            "paired: paired greedily (heaviest overlap first), not by the optimal assignment");
  EXPECT_EQ(out.confidence, 0);
}

TEST(StopRule, PaperSpentBeforeItsFirstSampleSaysSo) {
  const auto a = test::seven_rocks(0), b = test::seven_rocks(0.05);
  const detail::RegistrationFrame f(a, b, 1.0);
  const auto out =
      detail::register_paper(f, budget_of_5ms(RegistrationMethod::kPaper), Deadline(5, clock_passing_after(1)));
  EXPECT_EQ(out.stop, StopReason::kTimeBudget);
  EXPECT_EQ(out.samples, 0);
  EXPECT_EQ(out.note, "time budget spent before a triple was scored: identity used");
}

// An answer the budget left unjudged (the identity before any hypothesis, EM's fit before its rivals) pairs the
// seven rocks, yet nothing was compared with it: every method flags it as such, never confident and never "a
// rival fits as well" (paper's identity read confidence 1 before).
TEST(StopRule, AnAnswerTheBudgetLeftUnjudgedIsFlaggedAsNeverCompared) {
  const auto a = test::seven_rocks(0), b = test::seven_rocks(0.05);
  for (auto m : {RegistrationMethod::kConsensus, RegistrationMethod::kPaper, RegistrationMethod::kCpd}) {
    const auto r = detail::register_rocks_until(a, b, budget_of_5ms(m), Deadline(5, clock_passing_after(1)));
    EXPECT_EQ(r.stop, StopReason::kTimeBudget) << to_string(m);
    EXPECT_FALSE(r.pairs.empty()) << to_string(m);
    EXPECT_EQ(r.ambiguity, Ambiguity::kUnchecked) << to_string(m);
    EXPECT_TRUE(r.ambiguous) << to_string(m);
    EXPECT_EQ(r.confidence, 0) << to_string(m);
  }
  EXPECT_STREQ(ambiguity_reason(Ambiguity::kUnchecked),
               "the time budget ended before the alignment used was compared with another, so nothing singles it "
               "out");
}

// Rocks shrunk to 0.3 of their layout where the bounds allow scales of 2 to 3 only (the identity is out of them
// too): no hypothesis is plausible, the identity is the answer, and it says why rather than "a rival fits as
// well".
TEST(StopRule, NoPlausibleAlignmentIsFlaggedAsSuch) {
  const auto a = test::seven_rocks(0);
  auto b = a;
  for (auto& box : b)
    box.cx = 0.5 + 0.3 * (box.cx - 0.5), box.cy = 0.5 + 0.3 * (box.cy - 0.5), box.w *= 0.3, box.h *= 0.3;
  RegistrationOptions o;
  o.consensus.min_scale = 2;
  o.consensus.max_scale = 3;
  const auto r = register_rocks(a, b, o);
  EXPECT_EQ(r.note.rfind("no plausible affine found: identity used", 0), 0u) << r.note;
  EXPECT_EQ(r.ambiguity, Ambiguity::kNoPlausible);
  EXPECT_EQ(r.confidence, 0);
  EXPECT_STREQ(ambiguity_reason(r.ambiguity),
               "no alignment within the scale, rotation and anisotropy bounds was found (the identity is used), so "
               "nothing singles it out");
}

// 300 rocks spread over the picture (over the coarse pass's 160), and the same rocks shifted by 1% of the width
// and labelled again (centres within 0.1% of the width), every tenth one missing.
struct ShiftedLayout {
  std::vector<Box> a, b;
};
ShiftedLayout shifted_layout() {
  detail::Rng rng(11);
  ShiftedLayout l;
  for (int k = 0; k < 300; ++k) {
    const double s = 0.01 + 0.01 * rng.uniform();
    l.a.push_back(test::box(0.05 + 0.9 * rng.uniform(), 0.05 + 0.9 * rng.uniform(), s, s));
    if (k % 10 == 9) continue;
    Box moved = l.a.back();
    moved.cx += 0.01 + 0.001 * (rng.uniform() - 0.5), moved.cy += 0.001 * (rng.uniform() - 0.5);
    l.b.push_back(moved);
  }
  return l;
}

// A clock that stands still for its first `still` readings, then jumps 1 s; it counts its readings.
struct CountingClock {
  std::shared_ptr<int> reads = std::make_shared<int>(0);
  MsClock passing_after(int still) const {
    auto r = reads;
    return [r, still] { return ++*r <= still ? 0.0 : 1000.0; };
  }
};

bool one_to_one(const RockPairs& pairs, size_t na, size_t nb) {
  std::vector<char> used_a(na, 0), used_b(nb, 0);
  for (const auto& [i, j] : pairs) {
    if (i < 0 || j < 0 || static_cast<size_t>(i) >= na || static_cast<size_t>(j) >= nb || used_a[i] || used_b[j])
      return false;
    used_a[i] = used_b[j] = 1;
  }
  return true;
}

// Whatever clock reading the budget ends on, each method stops with a sane answer (one-to-one pairs, a finite
// affine) and names the budget; every stage that reads the deadline is seen ending a run: the set-up, the search,
// the stages after it, the final pairing. When the clock never jumps, the pairs are those of no budget at all.
TEST(StopRule, EveryMethodStopsWherePassedWithASaneAnswer) {
  const ShiftedLayout l = shifted_layout();
  for (const RegistrationMethod m :
       {RegistrationMethod::kConsensus, RegistrationMethod::kPaper, RegistrationMethod::kCpd}) {
    RegistrationOptions o;
    o.method = m;
    const RegistrationReport unbudgeted = register_rocks(l.a, l.b, o);
    o.time_budget_ms = 5;
    std::set<std::string> notes;
    bool finished = false;
    for (int still = 1; still < 100000 && !finished; still = still < 40 ? still + 1 : still * 3 / 2) {
      const CountingClock clock;
      const RegistrationReport r = detail::register_rocks_until(l.a, l.b, o, Deadline(5, clock.passing_after(still)));
      SCOPED_TRACE(std::string(to_string(m)) + ", passed at reading " + std::to_string(still + 1) + ": " + r.note);
      EXPECT_TRUE(one_to_one(r.pairs, l.a.size(), l.b.size()));
      EXPECT_TRUE(r.affine.allFinite());
      finished = *clock.reads <= still;
      if (finished) {
        EXPECT_NE(r.stop, StopReason::kTimeBudget);
        EXPECT_EQ(r.pairs, unbudgeted.pairs);
      } else {
        EXPECT_EQ(r.stop, StopReason::kTimeBudget);
        // Paper's best so far needs no note: its stop reason names the budget.
        if (m != RegistrationMethod::kPaper) {
          EXPECT_FALSE(r.note.empty());
        }
        notes.insert(r.note);
      }
    }
    EXPECT_TRUE(finished) << to_string(m) << " never finished before the clock jumped";
    auto seen = [&](const std::string& words) {
      return std::any_of(notes.begin(), notes.end(),
                         [&](const std::string& n) { return n.find(words) != std::string::npos; });
    };
    if (m != RegistrationMethod::kPaper) {
      EXPECT_TRUE(seen("paired greedily")) << to_string(m);  // paper: mutual NN
    }
    if (m == RegistrationMethod::kConsensus) {
      EXPECT_TRUE(seen("time budget spent while setting up the search: identity used"));
      EXPECT_TRUE(seen("time budget spent while setting up the search: the alignment of the largest rocks used"));
      EXPECT_TRUE(seen("time budget spent: the search's best, without the rival placements, polish or second look"));
    }
    if (m == RegistrationMethod::kCpd) {
      EXPECT_TRUE(seen("time budget spent: EM's alignment, not judged against rival placements"));
    }
    if (m == RegistrationMethod::kPaper) {
      EXPECT_TRUE(seen("time budget spent before a triple was scored"));
    }
  }
}

// Spent before the rocks are paired, the pairing is greedy over the same allowed pairs: on scattered rocks, where
// each rock's box overlaps one other, that is the optimal assignment's answer.
TEST(StopRule, APairingLeftNoTimeIsGreedyAndSaysSo) {
  const ShiftedLayout l = shifted_layout();
  Affine2 shift = identity_affine();
  shift(0, 2) = 0.01;
  const PairingRule rule;
  bool greedy = false;
  EXPECT_EQ(pair_aligned_boxes_within(shift, l.a, l.b, rule, Deadline(5, [] { return 0.0; }), &greedy),
            pair_aligned_boxes(shift, l.a, l.b, rule));
  EXPECT_FALSE(greedy);
  const RockPairs pairs =
      pair_aligned_boxes_within(shift, l.a, l.b, rule, Deadline(5, CountingClock().passing_after(1)), &greedy);
  EXPECT_TRUE(greedy);
  EXPECT_EQ(pairs, pair_aligned_boxes(shift, l.a, l.b, rule));
  EXPECT_EQ(pairs.size(), 270u);
}

// Greedy takes the heaviest pair first: a rock overlapping two gets the better overlap, and the optimal
// assignment's better total is given up (hand-made: A0 overlaps B0 by 0.6 and B1 by 0.5, A1 only B0 by 0.4).
TEST(StopRule, GreedyPairingTakesTheHeaviestOverlapFirst) {
  const std::vector<Box> a = {test::box(0.5, 0.5, 0.1, 0.1), test::box(0.43, 0.5, 0.1, 0.1)};
  const std::vector<Box> b = {test::box(0.48, 0.5, 0.1, 0.1), test::box(0.535, 0.5, 0.1, 0.1)};
  const PairingRule rule;
  EXPECT_NEAR(iou(a[0], b[0]), 0.6667, 1e-4);
  EXPECT_NEAR(iou(a[0], b[1]), 0.4815, 1e-4);
  EXPECT_NEAR(iou(a[1], b[0]), 0.3333, 1e-4);
  EXPECT_EQ(pair_aligned_boxes(identity_affine(), a, b, rule), (RockPairs{{0, 1}, {1, 0}}));
  bool greedy = false;
  EXPECT_EQ(
      pair_aligned_boxes_within(identity_affine(), a, b, rule, Deadline(5, CountingClock().passing_after(1)), &greedy),
      (RockPairs{{0, 0}}));
  EXPECT_TRUE(greedy);
}

// Over its pair limit, cpd with a time budget registers the largest rocks of each side instead of refusing, and
// says so; without a budget it refuses (Registration.CpdRefusesMoreRockPairsThanItsLimit).
TEST(StopRule, CpdOverItsLimitWithABudgetRegistersTheLargestRocks) {
  std::vector<Box> a(4001), b(4001);
  for (int k = 0; k < 4001; ++k) {
    a[k] = test::box((k % 64 + 0.5) / 64, (k / 64 + 0.5) / 64, 0.01, 0.01);
    b[k] = a[k];
    b[k].cx += 0.1 / 64;
  }
  RegistrationOptions o;
  o.method = RegistrationMethod::kCpd;
  o.time_budget_ms = 10;
  const RegistrationReport r = detail::register_rocks_until(a, b, o, Deadline(10, CountingClock().passing_after(2)));
  EXPECT_EQ(r.stop, StopReason::kTimeBudget);
  EXPECT_EQ(r.note.rfind("4001 x 4001 rocks is over cpd's limit of 16,000,000 rock pairs: EM ran on the 141 and 141 "
                         "largest rocks (the time budget's subset), then every rock was paired",
                         0),
            0u);
  EXPECT_TRUE(one_to_one(r.pairs, a.size(), b.size()));
}

// A negative bound is a caller's mistake, not "no limit": the loop refuses it with the field and its range.
TEST(StopRule, RobustLoopOptionsNameTheBadField) {
  RobustLoopOptions lo;
  EXPECT_EQ(lo.validate(), "");
  lo.max_trials = -1;
  EXPECT_EQ(lo.validate(), "max_trials must be at least 0, got -1");
  lo.max_trials = 10;
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
