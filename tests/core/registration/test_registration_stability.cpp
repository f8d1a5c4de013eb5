// Numerical stability of registration: invariance to coordinate scale, offset and row order; defined,
// finite results for degenerate inputs; determinism; a real POLAR-Sim case with a known answer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <random>

#include "app/bench/registration_benchmark.h"
#include "core/registration/registration.h"

namespace ipd {
namespace {

const RegistrationMethod kAllMethods[] = {RegistrationMethod::kConsensus, RegistrationMethod::kPaper,
                                          RegistrationMethod::kCpd};

// A realistic case: 18 rocks, 3 hidden on each side, rotation 4 degrees, scale 1.05/0.96, centre noise.
struct Case {
  std::vector<Box> a, b;
  RockPairs truth;
};
Case realistic_case() {
  std::mt19937 g(21);
  auto u = [&](double lo, double hi) { return lo + (hi - lo) * (g() / 4294967296.0); };
  std::vector<Box> all;
  while (all.size() < 18) {
    Box b;
    b.cx = u(0.1, 0.9), b.cy = u(0.1, 0.9), b.w = u(0.02, 0.06), b.h = u(0.02, 0.06);
    bool ok = true;
    for (const auto& o : all) ok = ok && std::hypot(o.cx - b.cx, o.cy - b.cy) > 0.09;
    if (ok) all.push_back(b);
  }
  const double r = 4 * M_PI / 180;
  Affine2 m;
  m << 1.05 * std::cos(r), -0.96 * std::sin(r), 0.03, 1.05 * std::sin(r), 0.96 * std::cos(r), -0.02;
  Case c;
  std::vector<int> a_index(18, -1);
  for (int k = 0; k < 18; ++k)
    if (k % 6 != 0) a_index[k] = static_cast<int>(c.a.size()), c.a.push_back(all[k]);  // 0, 6, 12 hidden in A
  for (int k = 17; k >= 0; --k) {  // B in reverse order, 1, 7, 13 hidden
    if (k % 6 == 1) continue;
    Box moved = transform_box(m, all[k]);
    moved.cx += u(-0.002, 0.002);
    moved.cy += u(-0.002, 0.002);
    if (a_index[k] >= 0) c.truth.emplace_back(a_index[k], static_cast<int>(c.b.size()));
    c.b.push_back(moved);
  }
  std::sort(c.truth.begin(), c.truth.end());
  return c;
}

std::vector<Box> scaled(std::vector<Box> v, double s, double shift) {
  for (auto& b : v) b.cx = b.cx * s + shift, b.cy = b.cy * s + shift, b.w *= s, b.h *= s;
  return v;
}

bool finite(const RegistrationReport& r) { return r.affine.allFinite() && std::isfinite(r.fit.value); }

TEST(RegistrationStability, ConsensusFindsTheTruePairsOfARealisticCase) {
  const Case c = realistic_case();
  const RegistrationReport r = register_rocks(c.a, c.b, {});
  EXPECT_EQ(r.pairs, c.truth);
  EXPECT_EQ(r.stop, StopReason::kCannotBeBeaten) << to_string(r.stop);
}

TEST(RegistrationStability, SamePairsWhenCoordinatesAreScaledOrShifted) {
  const Case c = realistic_case();
  for (auto method : kAllMethods) {
    RegistrationOptions o;
    o.method = method;
    o.paper.samples = o.consensus.max_hypotheses = 300;
    const RockPairs base = register_rocks(c.a, c.b, o).pairs;
    if (method == RegistrationMethod::kConsensus) {
      EXPECT_EQ(base, c.truth);
    }
    for (const auto& [s, shift] : {std::pair{1e-3, 0.0}, {1e4, 0.0}, {1.0, 1e5}, {1e-3, 1e5}}) {
      const auto r = register_rocks(scaled(c.a, s, shift), scaled(c.b, s, shift), o);
      EXPECT_TRUE(finite(r));
      EXPECT_EQ(r.pairs, base) << to_string(method) << " scale " << s << " shift " << shift;
    }
  }
}

TEST(RegistrationStability, SamePairsWhenRowsAreShuffled) {
  const Case c = realistic_case();
  std::vector<int> pa(c.a.size()), pb(c.b.size());
  std::iota(pa.begin(), pa.end(), 0);
  std::iota(pb.begin(), pb.end(), 0);
  std::mt19937 g(4);
  std::shuffle(pa.begin(), pa.end(), g);
  std::shuffle(pb.begin(), pb.end(), g);
  std::vector<Box> a2, b2;
  for (int k : pa) a2.push_back(c.a[k]);  // a2[k] = a[pa[k]]
  for (int k : pb) b2.push_back(c.b[k]);
  std::vector<int> inv_a(pa.size()), inv_b(pb.size());
  for (size_t k = 0; k < pa.size(); ++k) inv_a[pa[k]] = static_cast<int>(k);
  for (size_t k = 0; k < pb.size(); ++k) inv_b[pb[k]] = static_cast<int>(k);
  RockPairs expected;
  for (const auto& [i, j] : c.truth) expected.emplace_back(inv_a[i], inv_b[j]);
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(register_rocks(a2, b2, {}).pairs, expected);
  EXPECT_EQ(register_rocks(a2, c.b, {}).pairs.size(), c.truth.size());
}

TEST(RegistrationStability, DefinedResultsForDegenerateInputs) {
  Box one;
  one.cx = 0.5, one.cy = 0.5, one.w = 0.1, one.h = 0.1;
  std::vector<Box> same(6, one);  // all centres equal (duplicated rocks)
  std::vector<Box> line;
  for (int k = 0; k < 8; ++k) {
    Box b = one;
    b.cx = 0.1 + 0.1 * k, b.cy = 0.1 + 0.1 * k, b.w = b.h = 0.04;
    line.push_back(b);
  }
  const Case c = realistic_case();
  std::vector<Box> dup = c.a;
  dup.insert(dup.end(), c.a.begin(), c.a.begin() + 5);  // five rocks labelled twice
  const std::vector<std::pair<std::vector<Box>, std::vector<Box>>> inputs = {
      {{}, {}},     {{one}, {}},  {{}, {one}},  {{one}, {one}}, {{one, line[3]}, {one, line[3]}},
      {same, same}, {line, line}, {same, line}, {dup, c.b},     {c.a, dup}};
  for (auto method : kAllMethods) {
    for (size_t k = 0; k < inputs.size(); ++k) {
      RegistrationOptions o;
      o.method = method;
      o.paper.samples = o.consensus.max_hypotheses = 200;
      const auto r = register_rocks(inputs[k].first, inputs[k].second, o);
      EXPECT_TRUE(finite(r)) << to_string(method) << " input " << k << "\\n" << r.affine;
      EXPECT_LE(r.pairs.size(), std::min(inputs[k].first.size(), inputs[k].second.size()));
      std::vector<int> used_a, used_b;
      for (const auto& [i, j] : r.pairs) used_a.push_back(i), used_b.push_back(j);
      std::sort(used_a.begin(), used_a.end());
      std::sort(used_b.begin(), used_b.end());
      EXPECT_EQ(std::adjacent_find(used_a.begin(), used_a.end()), used_a.end()) << "a rock paired twice";
      EXPECT_EQ(std::adjacent_find(used_b.begin(), used_b.end()), used_b.end()) << "a rock paired twice";
    }
  }
  // Identical single rocks pair with each other; identical lines pair rock for rock.
  EXPECT_EQ(register_rocks({one}, {one}, {}).pairs, (RockPairs{{0, 0}}));
  RockPairs diag;
  for (int k = 0; k < 8; ++k) diag.emplace_back(k, k);
  EXPECT_EQ(register_rocks(line, line, {}).pairs, diag);
}

TEST(RegistrationStability, FiveHundredRocksPerSide) {
  std::mt19937 g(8);
  auto u = [&](double lo, double hi) { return lo + (hi - lo) * (g() / 4294967296.0); };
  std::vector<Box> a;
  for (int k = 0; k < 500; ++k) {
    Box b;
    b.cx = u(0, 1), b.cy = u(0, 1), b.w = u(0.004, 0.01), b.h = u(0.004, 0.01);
    a.push_back(b);
  }
  Affine2 shift;
  shift << 1, 0, 0.003, 0, 1, -0.002;
  std::vector<Box> b;
  for (const auto& x : a) b.push_back(transform_box(shift, x));
  for (auto method : kAllMethods) {
    RegistrationOptions o;
    o.method = method;
    o.paper.samples = o.consensus.max_hypotheses = 50;
    o.cpd.iterations = 20;
    const auto r = register_rocks(a, b, o);
    EXPECT_TRUE(finite(r)) << to_string(method);
    if (method == RegistrationMethod::kConsensus) {
      EXPECT_EQ(r.pairs.size(), 500u);
      EXPECT_TRUE(r.affine.isApprox(shift, 1e-9)) << r.affine;
    }
  }
}

// 500 rocks a side under the large tier's misalignment (up to 25 degrees, scale 0.7-1.4 per axis, shift up to
// a quarter of the picture): the consensus first aligns the 64 largest rocks of each side, then all of them.
// Its pairs reach at least 97% of the F1 the true affine's pairing gets (that ceiling is 0.76-0.85 here: the
// shift moves many rocks out of view). Without the coarse pass the first case scores F1 0.01.
TEST(RegistrationStability, FiveHundredRocksUnderALargeMisalignment) {
  for (std::uint64_t k = 0; k < 3; ++k) {
    const RegistrationCase c = make_case(synthetic_label_pair(500, 1000 + k), large_misalignment(), 7 + k);
    RegistrationOptions o;
    o.aspect = 1936.0 / 1216.0;
    const RegistrationReport r = register_rocks(c.a, c.b, o);
    const double ceiling = score_pairs(pairs_under_true_affine(c, o), c.truth).f1;
    EXPECT_GE(score_pairs(r.pairs, c.truth).f1, 0.97 * ceiling) << "case " << k << ", ceiling " << ceiling;
  }
}

TEST(RegistrationStability, DeterministicForASeedAndReportsWhy) {
  const Case c = realistic_case();
  for (auto method : kAllMethods) {
    RegistrationOptions o;
    o.method = method;
    o.seed = 77;
    const auto r1 = register_rocks(c.a, c.b, o), r2 = register_rocks(c.a, c.b, o);
    EXPECT_EQ(r1.affine, r2.affine) << to_string(method);
    EXPECT_EQ(r1.pairs, r2.pairs);
    EXPECT_EQ(r1.samples, r2.samples);
    EXPECT_EQ(r1.em_iterations, r2.em_iterations);
    // Each method counts in its own unit: cpd runs EM iterations, paper and consensus draw samples.
    const bool cpd = method == RegistrationMethod::kCpd;
    EXPECT_GT(cpd ? r1.em_iterations : r1.samples, 0);
    EXPECT_EQ(cpd ? r1.samples : r1.em_iterations, 0);
    EXPECT_EQ(r1.fit.measure, fit_measure_of(method));
    EXPECT_EQ(r1.fit.value, r2.fit.value);
    EXPECT_NE(r1.stop, StopReason::kNotRun);
  }
}

// Real labels: two annotations of one POLAR view under different sun, with a known affine applied.
TEST(RegistrationStability, PolarSimCasesWithKnownAnswer) {
  const std::string root = std::string(IPD_SHARED_DATA) + "/labels";
  if (!std::filesystem::is_directory(root)) GTEST_SKIP() << "POLAR-Sim labels not found at " << root << "; skipping";
  const auto pairs = polar_sim_label_pairs(root);
  ASSERT_GT(pairs.size(), 100u);
  double f1_small = 0, f1_large = 0, f1_unequal = 0;
  const int n = 60;
  RegistrationOptions o;
  o.aspect = 1936.0 / 1216.0;
  for (int k = 0; k < n; ++k) {
    const auto& p = pairs[(k * 7919u) % pairs.size()];
    const auto cs = make_case(p, small_misalignment(), 5000 + k), cl = make_case(p, large_misalignment(), 9000 + k);
    const auto cu = make_case(p, unequal_counts(), 7000 + k);
    f1_small += score_pairs(register_rocks(cs.a, cs.b, o).pairs, cs.truth).f1;
    f1_large += score_pairs(register_rocks(cl.a, cl.b, o).pairs, cl.truth).f1;
    f1_unequal += score_pairs(register_rocks(cu.a, cu.b, o).pairs, cu.truth).f1;
  }
  // The cases clip the moved side to the picture (rocks leave it). These 60 large-tier cases
  // are a hard draw: 0.900 before the gate floor, soft refinement and guarded polish, 0.919 with them, 0.922
  // with the final fit judged among polished, searched and least squares (the benchmark's 300 cases, seed 1:
  // 0.961, 0.968, 0.971). The bound leaves room for one case to flip on another machine's libm (a case here
  // moves the mean by up to 0.017 / 3): it catches losing the refinement changes, not the judged fit alone.
  EXPECT_GE(f1_small / n, 0.97) << f1_small / n;
  EXPECT_GE(f1_large / n, 0.915) << f1_large / n;
  EXPECT_GE(f1_unequal / n, 0.95) << f1_unequal / n;
}

TEST(RegistrationBenchmark, ScoresAndTransformError) {
  const PairScore s = score_pairs({{0, 0}, {1, 2}, {2, 1}}, {{0, 0}, {1, 2}, {3, 3}, {4, 4}});
  EXPECT_NEAR(s.precision, 2.0 / 3, 1e-12);
  EXPECT_NEAR(s.recall, 0.5, 1e-12);
  EXPECT_NEAR(s.f1, 2 * (2.0 / 3) * 0.5 / (2.0 / 3 + 0.5), 1e-12);
  Affine2 t = identity_affine();
  t(0, 2) = 0.01;  // 1% of the width to the right
  Box b;
  b.cx = b.cy = 0.5, b.w = b.h = 0.1;
  EXPECT_NEAR(transform_error(t, identity_affine(), {b, b}, 1.6), 0.01, 1e-12);
}

}  // namespace
}  // namespace ipd
