// The registration trace (ipd-studio's replay) and the confidence / ambiguity measure.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/registration/registration.h"
#include "ui/gui/studio_layout.h"

namespace ipd {
namespace {

// 16 well separated rocks of varied size; B = a known affine of A minus rocks 0 and 1, rows reversed.
struct Scene {
  std::vector<Box> a, b;
  Affine2 b_from_a;
};
Scene scene() {
  std::mt19937 g(5);
  auto u = [&](double lo, double hi) { return lo + (hi - lo) * (g() / 4294967296.0); };
  Scene s;
  while (s.a.size() < 16) {
    Box b;
    b.cx = u(0.1, 0.9), b.cy = u(0.1, 0.9), b.w = u(0.02, 0.06), b.h = u(0.02, 0.06);
    bool ok = true;
    for (const auto& o : s.a) ok = ok && std::hypot(o.cx - b.cx, o.cy - b.cy) > 0.1;
    if (ok) s.a.push_back(b);
  }
  const double r = 6 * M_PI / 180;
  s.b_from_a << 1.04 * std::cos(r), -std::sin(r), 0.02, std::sin(r), 0.98 * std::cos(r), -0.01;
  for (int k = 15; k >= 2; --k) s.b.push_back(transform_box(s.b_from_a, s.a[k]));
  return s;
}

RegistrationOptions traced(RegistrationMethod m) {
  RegistrationOptions o;
  o.method = m;
  o.record_trace = true;
  o.paper.samples = o.consensus.max_hypotheses = 200;
  return o;
}

TEST(RegistrationTrace, OffByDefaultAndRecordingChangesNothing) {
  const Scene s = scene();
  for (auto m : {RegistrationMethod::kPaper, RegistrationMethod::kConsensus, RegistrationMethod::kCpd}) {
    RegistrationOptions off = traced(m);
    off.record_trace = false;
    const auto r0 = register_rocks(s.a, s.b, off), r1 = register_rocks(s.a, s.b, traced(m));
    EXPECT_TRUE(r0.trace.steps.empty()) << to_string(m);
    EXPECT_TRUE(r0.trace.stop.empty());
    EXPECT_FALSE(r1.trace.steps.empty()) << to_string(m);
    EXPECT_EQ(r0.affine, r1.affine) << to_string(m);
    EXPECT_EQ(r0.pairs, r1.pairs);
    EXPECT_EQ(r0.samples, r1.samples);
    EXPECT_EQ(r0.em_iterations, r1.em_iterations);
    EXPECT_EQ(r0.confidence, r1.confidence);
  }
}

TEST(RegistrationTrace, PaperRecordsEveryHypothesisWithItsTriples) {
  const Scene s = scene();
  const auto r = register_rocks(s.a, s.b, traced(RegistrationMethod::kPaper));
  ASSERT_EQ(static_cast<int>(r.trace.steps.size()), r.hypotheses);
  double best = INFINITY;
  int bests = 0;
  for (const auto& st : r.trace.steps) {
    ASSERT_EQ(st.kind, TraceStepKind::kHypothesis);
    ASSERT_EQ(st.a_sample.size(), 3u);
    ASSERT_EQ(st.b_sample.size(), 3u);
    // The exact affine of the sample maps each of its A rocks onto its B partner, in the recorded order.
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d d = apply(st.b_from_a, s.a[st.a_sample[k]].centre()) - s.b[st.b_sample[k]].centre();
      ASSERT_LT(d.norm(), 1e-9);
    }
    // Scores are mean nearest-neighbour distances: lower is better, best-so-far never rises.
    EXPECT_EQ(st.new_best, st.fit < best);
    best = std::min(best, st.fit);
    EXPECT_DOUBLE_EQ(st.best_fit, best);
    bests += st.new_best;
  }
  EXPECT_GE(bests, 1);
  EXPECT_NEAR(best, r.fit.value, 1e-12);
  const auto last =
      std::find_if(r.trace.steps.rbegin(), r.trace.steps.rend(), [](const auto& x) { return x.new_best; });
  EXPECT_TRUE(last->b_from_a.isApprox(r.affine, 1e-12));
  // 1,182 hypotheses here: counts print with thousands separators (ui::thousands formats the same way).
  EXPECT_GE(r.hypotheses, 1000);
  EXPECT_EQ(
      r.trace.stop.rfind("reached the trial limit (200 trials, " + ui::thousands(r.hypotheses) + " hypotheses, ", 0),
      0u)
      << r.trace.stop;
}

TEST(RegistrationTrace, ConsensusRecordsHypothesesRefinementsAndPolish) {
  const Scene s = scene();
  const auto r = register_rocks(s.a, s.b, traced(RegistrationMethod::kConsensus));
  const auto& st = r.trace.steps;
  ASSERT_GE(st.size(), 3u);
  EXPECT_EQ(st.front().kind, TraceStepKind::kHypothesis);
  EXPECT_TRUE(st.front().a_sample.empty());  // the identity comes first: built from no rocks
  EXPECT_EQ(st.back().kind, TraceStepKind::kPolish);
  EXPECT_TRUE(st.back().b_from_a.isApprox(r.affine, 1e-12));
  EXPECT_EQ(static_cast<int>(st.back().inliers_a.size()), r.inliers);
  int hypotheses = 0, refinements = 0;
  double best = -INFINITY;
  for (size_t k = 0; k + 1 < st.size(); ++k) {
    hypotheses += st[k].kind == TraceStepKind::kHypothesis;
    refinements += st[k].kind == TraceStepKind::kRefinement;
    if (st[k].kind == TraceStepKind::kRefinement) {
      EXPECT_EQ(st[k - 1].kind, TraceStepKind::kHypothesis);
    }
    if (!st[k].a_sample.empty()) {  // a triple: rock i and two neighbours, each matched to a B rock
      ASSERT_EQ(st[k].a_sample.size(), 3u);
      ASSERT_EQ(st[k].b_sample.size(), 3u);
      for (int j = 0; j < 3; ++j) {
        const Eigen::Vector2d d =
            apply(st[k].b_from_a, s.a[st[k].a_sample[j]].centre()) - s.b[st[k].b_sample[j]].centre();
        if (st[k].kind == TraceStepKind::kHypothesis) {
          ASSERT_LT(d.norm(), 1e-9);
        }
      }
    }
    EXPECT_EQ(st[k].new_best, st[k].fit > best) << k;
    best = std::max(best, st[k].fit);
    EXPECT_DOUBLE_EQ(st[k].best_fit, best) << k;
  }
  EXPECT_EQ(hypotheses, r.hypotheses);
  EXPECT_GE(refinements, 1);
  EXPECT_DOUBLE_EQ(best, r.fit.value);
  EXPECT_EQ(r.trace.stop.rfind(to_string(r.stop), 0), 0u) << r.trace.stop;
}

TEST(RegistrationTrace, CpdRecordsOneStepPerIteration) {
  const Scene s = scene();
  RegistrationOptions o = traced(RegistrationMethod::kCpd);
  o.cpd.iterations = 7;
  const auto r = register_rocks(s.a, s.b, o);
  // Seven EM steps leave the fit short of a shifted placement (refined) that fits better: that placement is the
  // answer, recorded as the final fit after the iterations.
  EXPECT_EQ(r.ambiguity, Ambiguity::kBeaten);
  ASSERT_EQ(static_cast<int>(r.trace.steps.size()), r.em_iterations + 1);
  EXPECT_EQ(r.em_iterations, 7);
  EXPECT_EQ(r.samples, 0);
  for (size_t k = 0; k + 1 < r.trace.steps.size(); ++k) EXPECT_EQ(r.trace.steps[k].kind, TraceStepKind::kIteration);
  EXPECT_EQ(r.trace.steps.back().kind, TraceStepKind::kPolish);
  EXPECT_TRUE(r.trace.steps.back().b_from_a.isApprox(r.affine, 1e-12));
  EXPECT_DOUBLE_EQ(r.trace.steps.back().fit, r.fit.value);
  EXPECT_EQ(r.fit.measure, FitMeasure::kMixtureWidth);
  // Counts in full with separators (the studio shows this line: no "1.57e+03").
  EXPECT_EQ(r.trace.stop,
            "reached the trial limit (7 EM iterations, 1,568 of 1,045,000 point evaluations: the bound for this many "
            "rocks)");
}

TEST(RegistrationTrace, StopsRecordingAtTheCap) {
  RegistrationTrace t;
  EXPECT_EQ(t.max_steps, 5000);
  t.max_steps = 2;
  EXPECT_TRUE(t.add({}));
  EXPECT_TRUE(t.add({}));
  EXPECT_FALSE(t.add({}));
  EXPECT_TRUE(t.truncated);
  EXPECT_EQ(t.steps.size(), 2u);
}

// A 3 x 3 block of identical rocks seen inside a 5 x 5 grid of them: nine placements explain it equally well.
// `height`: the boxes' height (0.064 makes them square in a 960 x 600 picture).
void symmetric_grid(std::vector<Box>* a, std::vector<Box>* b, double height = 0.04) {
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 5; ++x) {
      Box r;
      r.cx = 0.1 + 0.2 * x, r.cy = 0.1 + 0.2 * y, r.w = 0.04, r.h = height;
      a->push_back(r);
      if (x >= 1 && x <= 3 && y >= 1 && y <= 3) {
        r.cx += 0.01;
        b->push_back(r);
      }
    }
}

TEST(RegistrationConfidence, SymmetricGridIsAmbiguous) {
  std::vector<Box> a, b;
  symmetric_grid(&a, &b);
  for (auto m : {RegistrationMethod::kConsensus, RegistrationMethod::kPaper}) {
    RegistrationOptions o;
    o.method = m;
    const auto r = register_rocks(a, b, o);
    EXPECT_TRUE(r.ambiguous) << to_string(m) << " confidence " << r.confidence;
    EXPECT_LT(r.confidence, 0.2) << to_string(m);
  }
}

// cpd scores no rival of its own; its confidence compares its alignment with the placements most rock pairs
// agree on (it reported 1.0 for everything, even 2 of 17 rocks paired). The symmetric grid is ambiguous for it
// too; twelve scattered rocks shifted by 2% are not.
TEST(RegistrationConfidence, CpdMeasuresItsConfidenceAgainstRivalPlacements) {
  RegistrationOptions o;
  o.method = RegistrationMethod::kCpd;
  // At 960 x 600 (square boxes) EM settles on a fit shrunk by half that pairs all nine rocks wrongly, and the
  // unmoved camera fits them as well: only that rival flags it (with cpd's own shifts alone: 0.33).
  for (double aspect : {1.0, 960.0 / 600.0}) {
    std::vector<Box> grid_a, grid_b;
    symmetric_grid(&grid_a, &grid_b, 0.04 * aspect);
    for (auto* side : {&grid_a, &grid_b})  // to 4 decimals, as a label file holds them
      for (Box& r : *side)
        for (double* v : {&r.cx, &r.cy, &r.w, &r.h}) *v = std::round(*v * 1e4) / 1e4;
    o.aspect = aspect;
    const auto grid = register_rocks(grid_a, grid_b, o);
    EXPECT_TRUE(grid.ambiguous) << "aspect " << aspect << ", confidence " << grid.confidence;
    EXPECT_LT(grid.confidence, 0.2) << "aspect " << aspect;
  }
  o.aspect = 1.0;

  std::vector<Box> a, b;
  const double spots[12][2] = {{0.12, 0.2}, {0.3, 0.75}, {0.45, 0.3}, {0.6, 0.85}, {0.8, 0.15},  {0.2, 0.5},
                               {0.7, 0.5},  {0.9, 0.7},  {0.35, 0.1}, {0.55, 0.6}, {0.15, 0.85}, {0.85, 0.4}};
  for (int k = 0; k < 12; ++k) {
    Box r;
    r.cx = spots[k][0], r.cy = spots[k][1], r.w = 0.03 + 0.004 * k, r.h = 0.05 - 0.002 * k;
    a.push_back(r);
    r.cx += 0.02, r.cy -= 0.01;
    b.push_back(r);
  }
  const auto clean = register_rocks(a, b, o);
  EXPECT_EQ(clean.pairs.size(), 12u);
  EXPECT_GT(clean.confidence, 0.5);
  EXPECT_FALSE(clean.ambiguous);
}

// A 6 x 4 grid and its last five columns, unmoved: shifting by one column fits as many rocks, so it is
// ambiguous at any aspect ratio. At 960 x 600 the one-column shift is exactly 0 vertically, which sat on a
// translation-vote bin edge (votes at +-1e-17 split in two) and the rival went unseen: confidence 0.25.
TEST(RegistrationConfidence, AGridMovedAlongOneAxisIsAmbiguousAtAnyAspect) {
  std::vector<Box> a, b;
  for (int x = 0; x < 6; ++x)
    for (int y = 0; y < 4; ++y) {
      Box r;
      r.cx = 0.15 + 0.14 * x, r.cy = 0.2 + 0.2 * y, r.w = 0.05, r.h = 0.08;
      a.push_back(r);
      if (x >= 1) b.push_back(r);
    }
  for (double aspect : {1.0, 1.6, 1936.0 / 1216.0}) {
    RegistrationOptions o;
    o.aspect = aspect;
    const auto r = register_rocks(a, b, o);
    EXPECT_TRUE(r.ambiguous) << "aspect " << aspect << ", confidence " << r.confidence;
    EXPECT_EQ(r.pairs.size(), 20u) << "aspect " << aspect;
  }
}

TEST(RegistrationConfidence, ADistinctiveLayoutIsNotAmbiguous) {
  const Scene s = scene();
  const auto r = register_rocks(s.a, s.b, {});
  EXPECT_FALSE(r.ambiguous);
  EXPECT_GT(r.confidence, 0.5);
  EXPECT_TRUE(r.affine.isApprox(s.b_from_a, 1e-6)) << r.affine;
}

TEST(RegistrationMethods, OneTableForNamesParsingAndMessages) {
  const auto& table = registration_methods();
  ASSERT_EQ(table.size(), 3u);
  EXPECT_EQ(table.front().method, RegistrationOptions().method);  // the default comes first
  EXPECT_EQ(method_names(), (std::vector<std::string>{"consensus", "paper", "cpd"}));
  EXPECT_EQ(method_choices(), "consensus, paper or cpd");
  for (const auto& info : table) {
    RegistrationMethod m = RegistrationMethod::kCpd;
    ASSERT_TRUE(parse_method(info.name, &m));
    EXPECT_EQ(m, info.method);
    EXPECT_STREQ(to_string(m), info.name);
    EXPECT_NE(methods_help().find(std::string(info.name) + (m == table.front().method ? " (default): " : ": ") +
                                  info.description),
              std::string::npos);
  }
  RegistrationMethod m = RegistrationMethod::kCpd;
  EXPECT_FALSE(parse_method("Consensus", &m));
  EXPECT_FALSE(parse_method("", &m));
  EXPECT_EQ(m, RegistrationMethod::kCpd);  // untouched on failure
}

TEST(RobustLoop, ComputeNumTrialsAsColmap) {
  // log(1 - 0.99) / log(1 - 0.5^3) = 34.49 -> 35
  EXPECT_EQ(compute_num_trials(5, 10, 3, 0.99, 1000), 35);
  EXPECT_EQ(compute_num_trials(10, 10, 3, 0.99, 1000), 1);     // every point an inlier
  EXPECT_EQ(compute_num_trials(0, 10, 3, 0.99, 1000), 1000);   // none: the cap
  EXPECT_EQ(compute_num_trials(1, 100, 3, 0.99, 1000), 1000);  // 4.6 million: the cap
  EXPECT_EQ(compute_num_trials(5, 10, 3, 1.0, 1000), 1000);
  // log(0.05) / log(1 - 0.8^2) = 2.93 -> 3
  EXPECT_EQ(compute_num_trials(8, 10, 2, 0.95, 1000), 3);
}

}  // namespace
}  // namespace ipd
