#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "core/geometry/affine_estimator.h"
#include "core/geometry/point_grid.h"
#include "core/registration/consensus/consensus_search.h"  // core/src: internal
#include "core/registration/pairing.h"
#include "core/registration/registration.h"

namespace ipd {
namespace {

// A layout of n rocks with well separated centres in [0.1, 0.9]^2.
std::vector<Box> layout(int n, unsigned seed) {
  std::mt19937 g(seed);
  auto u = [&](double lo, double hi) { return lo + (hi - lo) * (g() / 4294967296.0); };
  std::vector<Box> out;
  while (static_cast<int>(out.size()) < n) {
    Box b;
    b.cx = u(0.1, 0.9), b.cy = u(0.1, 0.9), b.w = u(0.02, 0.05), b.h = u(0.02, 0.05);
    bool ok = true;
    for (const auto& o : out) ok = ok && std::hypot(o.cx - b.cx, o.cy - b.cy) > 0.08;
    if (ok) out.push_back(b);
  }
  return out;
}

Affine2 known_affine() {
  const double r = 4.0 * M_PI / 180;
  Affine2 m;
  m << 1.05 * std::cos(r), -std::sin(r) + 0.03, 0.02, std::sin(r), 0.97 * std::cos(r), -0.015;
  return m;
}

// B = known affine of A, rows permuted by `perm` (B[k] = moved A[perm[k]]).
std::vector<Box> moved(const std::vector<Box>& a, const Affine2& m, const std::vector<int>& perm) {
  std::vector<Box> b;
  for (int k : perm) b.push_back(transform_box(m, a[k]));
  return b;
}

RockPairs pairs_of(const std::vector<int>& perm) {
  RockPairs p;
  for (size_t k = 0; k < perm.size(); ++k) p.emplace_back(perm[k], static_cast<int>(k));
  std::sort(p.begin(), p.end());
  return p;
}

std::vector<int> shuffled(int n, unsigned seed) {
  std::vector<int> p(n);
  std::iota(p.begin(), p.end(), 0);
  std::mt19937 g(seed);
  for (int k = n - 1; k > 0; --k) std::swap(p[k], p[g() % (k + 1)]);
  return p;
}

TEST(AffineEstimator, ExactFromThreeAndConditioning) {
  const Affine2 m = known_affine();
  const Eigen::Vector2d src[3] = {{0, 0}, {1, 0}, {0, 1}};
  const Eigen::Vector2d dst[3] = {apply(m, src[0]), apply(m, src[1]), apply(m, src[2])};
  Affine2 got;
  ASSERT_TRUE(affine_from_three(src, dst, &got));
  EXPECT_TRUE(got.isApprox(m, 1e-12));
  const Eigen::Vector2d flat[3] = {{0, 0}, {1, 0}, {2, 1e-6}};  // near-collinear
  EXPECT_LT(triangle_conditioning(flat[0], flat[1], flat[2]), kMinTriangleConditioning);
  EXPECT_FALSE(affine_from_three(flat, dst, &got));
}

TEST(AffineEstimator, TrimmedLeastSquaresIsNotBentByOneWrongPair) {
  // 15 exact pairs under a known affine and one wrong hand pair half a picture away: plain least squares is
  // pulled off by the wrong pair, the trimmed fit recovers the affine exactly.
  const Affine2 m = known_affine();
  std::vector<Eigen::Vector2d> src, dst;
  for (int k = 0; k < 15; ++k) {
    src.push_back({0.05 + 0.06 * k, 0.1 + 0.8 * ((k * 7) % 15) / 15.0});
    dst.push_back(apply(m, src.back()));
  }
  src.push_back({0.3, 0.3});
  dst.push_back(apply(m, Eigen::Vector2d{0.8, 0.7}));
  Affine2 plain, trimmed;
  ASSERT_TRUE(affine_least_squares(src, dst, &plain));
  EXPECT_GT((plain - m).cwiseAbs().maxCoeff(), 1e-2);
  ASSERT_TRUE(affine_least_squares_trimmed(src, dst, &trimmed));
  EXPECT_LT((trimmed - m).cwiseAbs().maxCoeff(), 1e-9) << trimmed;
  // Without a wrong pair it is the plain fit; with fewer than three pairs it refuses, as least squares does.
  src.pop_back(), dst.pop_back();
  ASSERT_TRUE(affine_least_squares_trimmed(src, dst, &trimmed));
  EXPECT_LT((trimmed - m).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_FALSE(affine_least_squares_trimmed({src[0], src[1]}, {dst[0], dst[1]}, &trimmed));
}

TEST(AffineEstimator, PermutationEstimatorTriesAllSixOrders) {
  TriplePair s;
  s.src[0] = {0, 0}, s.src[1] = {1, 0}, s.src[2] = {0, 1};
  s.dst[0] = {2, 2}, s.dst[1] = {3, 2}, s.dst[2] = {2, 4};
  std::vector<Affine2> models;
  AffinePermutationEstimator().estimate(s, &models);
  EXPECT_EQ(models.size(), 6u);
}

TEST(PointGrid, NearestMatchesBruteForce) {
  std::mt19937 g(3);
  std::vector<Eigen::Vector2d> pts;
  for (int k = 0; k < 500; ++k) pts.emplace_back(g() / 4294967296.0, g() / 4294967296.0);
  const PointGrid grid(pts);
  for (int q = 0; q < 300; ++q) {
    const Eigen::Vector2d p(g() / 4294967296.0 * 3 - 1, g() / 4294967296.0 * 3 - 1);  // also outside the grid
    double d = 0;
    const int got = grid.nearest(p, &d);
    double best = INFINITY;
    for (const auto& x : pts) best = std::min(best, (x - p).squaredNorm());
    EXPECT_DOUBLE_EQ(d, best);
    EXPECT_DOUBLE_EQ((pts[got] - p).squaredNorm(), best);
  }
}

// With a bound, the query answers the nearest point strictly closer than it, or -1 (distance left at the
// bound) when none is; inside the bound it agrees with brute force. Small sets (brute force) and the grid both.
TEST(PointGrid, BoundedNearestIsTheNearestWithinTheBoundOrNone) {
  std::mt19937 g(4);
  for (int n : {10, 500}) {
    std::vector<Eigen::Vector2d> pts;
    for (int k = 0; k < n; ++k) pts.emplace_back(g() / 4294967296.0, g() / 4294967296.0);
    const PointGrid grid(pts);
    int found = 0, none = 0;
    for (int q = 0; q < 400; ++q) {
      const Eigen::Vector2d p(g() / 4294967296.0 * 2 - 0.5, g() / 4294967296.0 * 2 - 0.5);  // also outside
      const double below = n < 24 ? 0.04 : 0.001;  // about half the queries in the picture find a point
      double d = -1;
      const int got = grid.nearest(p, &d, below);
      double best = INFINITY;
      int want = -1;
      for (size_t k = 0; k < pts.size(); ++k)
        if ((pts[k] - p).squaredNorm() < best) best = (pts[k] - p).squaredNorm(), want = static_cast<int>(k);
      if (best < below) {
        ++found;
        EXPECT_EQ(got, want);
        EXPECT_DOUBLE_EQ(d, best);
      } else {
        ++none;
        EXPECT_EQ(got, -1) << "a point at distance^2 " << best << " is not below " << below;
        EXPECT_EQ(d, below);
      }
    }
    EXPECT_GT(found, 10) << n;  // both branches exercised
    EXPECT_GT(none, 10) << n;
  }
  // An exact tie with the bound does not count (strictly closer).
  const PointGrid one({Eigen::Vector2d(0.5, 0)});
  double d = 0;
  EXPECT_EQ(one.nearest(Eigen::Vector2d(0, 0), &d, 0.25), -1);
  EXPECT_EQ(one.nearest(Eigen::Vector2d(0, 0), &d, 0.2500001), 0);
  EXPECT_DOUBLE_EQ(d, 0.25);
}

// The grid's k nearest neighbours equal a brute-force sort by (distance, index), duplicates left out, on a
// random layout, a line (zero area) and a clump of coincident points.
TEST(ConsensusSearch, NearestNeighboursMatchBruteForce) {
  std::mt19937 g(9);
  std::uniform_real_distribution<double> u(-3, 3);
  std::vector<Eigen::Vector2d> random_layout, line, clump;
  for (int i = 0; i < 300; ++i) random_layout.emplace_back(u(g), u(g));
  for (int i = 0; i < 40; ++i) line.emplace_back(0.1 * i, 0.2 * i);
  for (int i = 0; i < 30; ++i) clump.emplace_back(i < 20 ? Eigen::Vector2d(1, 1) : Eigen::Vector2d(1 + 0.01 * i, 1));
  for (const auto* p : {&random_layout, &line, &clump})
    for (int k : {1, 5, 8, 50}) {
      const auto nn = detail::nearest_neighbours(*p, k);
      ASSERT_EQ(nn.size(), p->size());
      for (size_t i = 0; i < p->size(); ++i) {
        std::vector<std::pair<double, int>> d;
        for (size_t j = 0; j < p->size(); ++j)
          if (j != i) d.emplace_back(((*p)[j] - (*p)[i]).squaredNorm(), static_cast<int>(j));
        std::sort(d.begin(), d.end());
        std::vector<int> want;
        for (int t = 0; t < std::min<int>(k, static_cast<int>(d.size())); ++t)
          if (d[t].first > 0) want.push_back(d[t].second);
        EXPECT_EQ(nn[i], want) << "point " << i << " k " << k << " of " << p->size();
      }
    }
}

TEST(PointGrid, FarQueriesStayExact) {
  // Hypotheses can move rocks far outside B's picture; the search must stay exact there (and stop early).
  std::mt19937 g(5);
  std::vector<Eigen::Vector2d> pts;
  for (int k = 0; k < 2000; ++k) pts.emplace_back(g() / 4294967296.0, 0.5 * g() / 4294967296.0);
  const PointGrid grid(pts);
  for (int q = 0; q < 200; ++q) {
    const Eigen::Vector2d p(g() / 4294967296.0 * 200 - 100, g() / 4294967296.0 * 200 - 100);
    double d = 0;
    grid.nearest(p, &d);
    double best = INFINITY;
    for (const auto& x : pts) best = std::min(best, (x - p).squaredNorm());
    EXPECT_DOUBLE_EQ(d, best);
  }
}

// The pairing rule with near misses within 0.0125 of the width (sides within a factor 2) as well as overlaps.
PairingRule near_misses_too() {
  PairingRule r;
  r.noise_floor = 0.0125;
  return r;
}

TEST(Assignment, PerComponentPairingEqualsTheWholeAssignment) {
  // pair_aligned_boxes solves each group of boxes that may pair apart; the total weight (IoU, or a near miss's
  // weight) must equal the whole problem's optimum.
  std::mt19937 g(11);
  auto u = [&] { return g() / 4294967296.0; };
  std::vector<Box> a, b;
  for (int k = 0; k < 60; ++k) a.push_back({0, u(), u(), 0.03 + 0.1 * u(), 0.03 + 0.1 * u()});
  for (int k = 0; k < 50; ++k) b.push_back({0, u(), u(), 0.03 + 0.1 * u(), 0.03 + 0.1 * u()});
  std::vector<double> w(a.size() * b.size());
  for (size_t i = 0; i < a.size(); ++i)
    for (size_t j = 0; j < b.size(); ++j) w[i * b.size() + j] = pair_weight(a[i], b[j], near_misses_too());
  double whole = 0, parts = 0;
  for (const auto& [i, j] : max_weight_assignment(w, 60, 50, 0.0)) whole += w[i * b.size() + j];
  const RockPairs got = pair_aligned_boxes(identity_affine(), a, b, near_misses_too());
  for (const auto& [i, j] : got) parts += w[i * b.size() + j];
  EXPECT_GT(got.size(), 5u);
  EXPECT_NEAR(parts, whole, 1e-12);
  EXPECT_TRUE(std::is_sorted(got.begin(), got.end()));
}

TEST(Assignment, HungarianBeatsGreedy) {
  // Greedy would take (0,0)=0.9 and then (1,1)=0.1; optimal is (0,1)+(1,0) = 0.8+0.8.
  const std::vector<double> w = {0.9, 0.8, 0.8, 0.1};
  EXPECT_EQ(max_weight_assignment(w, 2, 2, 0.0), (RockPairs{{0, 1}, {1, 0}}));
  // Entries at or below the floor are never assigned.
  EXPECT_EQ(max_weight_assignment({0.0, 0.0, 0.0, 0.5}, 2, 2, 0.05), (RockPairs{{1, 1}}));
  EXPECT_EQ(max_weight_assignment({0.3, 0.6, 0.2}, 1, 3, 0.0), (RockPairs{{0, 1}}));
}

TEST(Assignment, SparseSolverFindsTheDenseOptimum) {
  // Random sparse weight tables (about one pair in four allowed, some at or below the floor), rectangular
  // both ways: the sparse solver's total weight equals the dense Hungarian's, one-to-one, floor respected.
  std::mt19937 g(5);
  auto u = [&] { return g() / 4294967296.0; };
  for (int trial = 0; trial < 200; ++trial) {
    const int rows = 1 + static_cast<int>(g() % 12), cols = 1 + static_cast<int>(g() % 12);
    std::vector<double> w(static_cast<size_t>(rows) * cols, 0.0);
    std::vector<WeightedEdge> edges;
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c)
        if (u() < 0.25) {
          const double x = trial % 3 == 0 ? 0.1 * (1 + g() % 4) : u();  // ties on every third table
          w[r * cols + c] = x;
          edges.push_back({r, c, x});
        }
    double dense = 0, sparse = 0;
    for (const auto& [r, c] : max_weight_assignment(w, rows, cols, 0.05)) dense += w[r * cols + c];
    const RockPairs got = sparse_max_weight_assignment(edges, rows, cols, 0.05);
    std::vector<char> row_used(rows), col_used(cols);
    for (const auto& [r, c] : got) {
      EXPECT_GT(w[r * cols + c], 0.05);
      EXPECT_FALSE(row_used[r]++);
      EXPECT_FALSE(col_used[c]++);
      sparse += w[r * cols + c];
    }
    EXPECT_NEAR(sparse, dense, 1e-12) << "table " << trial << ", " << rows << " x " << cols;
    EXPECT_TRUE(std::is_sorted(got.begin(), got.end()));
  }
  EXPECT_EQ(sparse_max_weight_assignment({{0, 0, 0.9}, {0, 1, 0.8}, {1, 0, 0.8}, {1, 1, 0.1}}, 2, 2, 0.0),
            (RockPairs{{0, 1}, {1, 0}}));
}

TEST(Assignment, APackedLayoutIsOneComponentSolvedSparsely) {
  // 700 boxes a side packed so densely that their overlaps chain into one component: beyond the dense
  // solver's work limit, pair_aligned_boxes solves it sparsely, with the whole problem's optimal total.
  std::mt19937 g(3);
  auto u = [&] { return g() / 4294967296.0; };
  std::vector<Box> a, b;
  for (int k = 0; k < 700; ++k) a.push_back({0, u(), u(), 0.06, 0.06});
  for (int k = 0; k < 700; ++k) b.push_back({0, u(), u(), 0.06, 0.06});
  std::vector<double> w(a.size() * b.size());
  for (size_t i = 0; i < a.size(); ++i)
    for (size_t j = 0; j < b.size(); ++j) w[i * b.size() + j] = pair_weight(a[i], b[j], near_misses_too());
  double whole = 0, parts = 0;
  for (const auto& [i, j] : max_weight_assignment(w, 700, 700, 0.0)) whole += w[i * b.size() + j];
  const RockPairs got = pair_aligned_boxes(identity_affine(), a, b, near_misses_too());
  for (const auto& [i, j] : got) parts += w[i * b.size() + j];
  EXPECT_GT(got.size(), 300u);
  EXPECT_NEAR(parts, whole, 1e-9);
}

TEST(RegistrationMethods, IdenticalLayoutsGetTheIdentityWithoutASearch) {
  // A twin rendered from the same labels: B holds A's boxes in another order. Every method returns the
  // identity and pairs each rock with its own copy, without a search; one box moved by a hair is searched.
  const auto a = layout(40, 3);
  const auto perm = shuffled(40, 9);
  std::vector<Box> b;
  for (int k : perm) b.push_back(a[k]);
  for (const RegistrationMethod m :
       {RegistrationMethod::kConsensus, RegistrationMethod::kPaper, RegistrationMethod::kCpd}) {
    SCOPED_TRACE(to_string(m));
    RegistrationOptions o;
    o.method = m;
    const RegistrationReport r = register_rocks(a, b, o);
    EXPECT_EQ(r.stop, StopReason::kIdenticalLayouts);
    EXPECT_EQ(r.affine, identity_affine());
    EXPECT_EQ(r.pairs, pairs_of(perm));
    EXPECT_EQ(r.samples, 0);
    EXPECT_EQ(r.em_iterations, 0);
    EXPECT_FALSE(r.fit.scored());  // nothing was searched: no fit to read as perfect
    EXPECT_EQ(r.confidence, 1.0);
    EXPECT_FALSE(r.ambiguous);
    std::vector<Box> nudged = b;
    nudged[7].cx += 1e-9;
    EXPECT_NE(register_rocks(a, nudged, o).stop, StopReason::kIdenticalLayouts);
  }
}

TEST(PaperRegistration, RecoversAKnownAffineOnACleanLayout) {
  const auto a = layout(8, 11);
  const auto perm = shuffled(8, 5);
  const auto b = moved(a, known_affine(), perm);
  RegistrationOptions o;
  o.method = RegistrationMethod::kPaper;
  o.paper.samples = 2000;
  const RegistrationReport r = register_rocks(a, b, o);
  EXPECT_TRUE(r.affine.isApprox(known_affine(), 1e-6)) << r.affine;
  EXPECT_EQ(r.pairs, pairs_of(perm));
  EXPECT_EQ(r.samples, 2000);  // the paper runs all K trials unless the fit is exact
  EXPECT_EQ(r.fit.measure, FitMeasure::kMeanDistance);
  EXPECT_NEAR(r.fit.value, 0.0, 1e-9);
  EXPECT_EQ(r.inliers, 8);
}

TEST(PaperRegistration, DeterministicForASeed) {
  const auto a = layout(12, 1);
  auto b = moved(a, known_affine(), shuffled(12, 2));
  b.pop_back();
  RegistrationOptions o;
  o.method = RegistrationMethod::kPaper;
  o.paper.samples = 50;
  o.seed = 9;
  const auto r1 = register_rocks(a, b, o), r2 = register_rocks(a, b, o);
  EXPECT_EQ(r1.affine, r2.affine);
  EXPECT_EQ(r1.pairs, r2.pairs);
}

TEST(PaperRegistration, DroppingModelsBelowTheRivalChangesNothing) {
  // Two unrelated layouts: most hypotheses score below the best distinct rival, and the scorer stops summing
  // them early. A recorded trace scores every model in full, so both runs must agree to the last bit.
  auto scatter = [](int n, unsigned seed) {
    std::mt19937 g(seed);
    std::vector<Box> out(n);
    for (Box& x : out) x.cx = 0.05 + 0.9 * (g() / 4294967296.0), x.cy = 0.05 + 0.9 * (g() / 4294967296.0);
    for (Box& x : out) x.w = x.h = 0.02;
    return out;
  };
  const auto a = scatter(300, 21), b = scatter(280, 22);
  RegistrationOptions o;
  o.method = RegistrationMethod::kPaper;
  o.seed = 4;
  const RegistrationReport fast = register_rocks(a, b, o);
  o.record_trace = true;
  const RegistrationReport full = register_rocks(a, b, o);
  EXPECT_EQ(fast.affine, full.affine);
  EXPECT_EQ(fast.fit.value, full.fit.value);
  EXPECT_EQ(fast.confidence, full.confidence);
  EXPECT_EQ(fast.pairs, full.pairs);
  EXPECT_EQ(fast.samples, full.samples);
  EXPECT_EQ(fast.hypotheses, full.hypotheses);
}

TEST(PaperRegistration, TooFewRocksFallsBackToIdentity) {
  const auto a = layout(2, 1);
  RegistrationOptions paper;
  paper.method = RegistrationMethod::kPaper;
  const RegistrationReport r = register_rocks(a, a, paper);
  EXPECT_EQ(r.stop, StopReason::kTooFewPoints);
  EXPECT_TRUE(r.affine.isApprox(identity_affine(), 1e-12));
  EXPECT_EQ(r.pairs, (RockPairs{{0, 0}, {1, 1}}));
}

TEST(ConsensusRegistration, RecoversAKnownAffineWithHiddenRocks) {
  const auto a = layout(20, 4);
  auto perm = shuffled(20, 8);
  perm.resize(17);  // three rocks of A are hidden in B
  auto b = moved(a, known_affine(), perm);
  std::vector<Box> a2 = a;
  a2.erase(a2.begin() + 19);  // and one rock of B is hidden in A
  RockPairs truth;
  for (size_t k = 0; k < perm.size(); ++k)
    if (perm[k] != 19) truth.emplace_back(perm[k], static_cast<int>(k));
  std::sort(truth.begin(), truth.end());
  const RegistrationReport r = register_rocks(a2, b, {});
  EXPECT_TRUE(r.affine.isApprox(known_affine(), 1e-6)) << r.affine;
  EXPECT_EQ(r.pairs, truth);
  EXPECT_EQ(r.inliers, 16);
}

TEST(RegistrationOptions, ValidateNamesTheProblem) {
  RegistrationOptions o;
  EXPECT_EQ(o.validate(), "");
  o.consensus.max_hypotheses = 0;
  EXPECT_EQ(o.validate(), "consensus.max_hypotheses must be at least 1, got 0");
  o = {};
  o.consensus.min_scale = 2, o.consensus.max_scale = 1;
  EXPECT_EQ(o.validate(), "scale bounds must satisfy 0 < min_scale <= max_scale, got [2, 1]");
  o = {};
  o.consensus.max_anisotropy = 0.5;
  EXPECT_EQ(o.validate(), "max_anisotropy must be a number >= 1, got 0.5");
  EXPECT_THROW(register_rocks({}, {}, o), std::invalid_argument);
  try {
    o.check();
    ADD_FAILURE() << "check() accepted what validate() rejects";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "registration options: max_anisotropy must be a number >= 1, got 0.5");
  }
}

// Unset is not zero: a set time budget, aspect, work budget or gate must be a usable number, and each method's
// own settings are checked by its own validate().
TEST(RegistrationOptions, SetOptionalsAndEachMethodsParamsAreChecked) {
  RegistrationOptions o;
  o.time_budget_ms = 0;
  EXPECT_EQ(o.validate(), "time_budget_ms must be > 0 when set (unset: no limit), got 0");
  o = {};
  o.aspect = -1;
  EXPECT_EQ(o.validate(), "aspect must be a positive number, got -1");
  o = {};
  o.work_budget = 0;
  EXPECT_EQ(o.validate(), "work_budget must be > 0 when set (unset: automatic), got 0");
  o = {};
  o.consensus.inlier_gate = 0;
  EXPECT_EQ(o.validate(), "inlier_gate must be > 0 when set (unset: from the rock spacing), got 0");
  o = {};
  o.paper.samples = 0;
  EXPECT_EQ(o.validate(), "paper.samples must be at least 1, got 0");
  o = {};
  o.paper.pair_gate = 0;
  EXPECT_EQ(o.validate(), "pair_gate must be > 0, got 0");
  o = {};
  o.cpd.iterations = 0;
  EXPECT_EQ(o.validate(), "cpd.iterations must be at least 1, got 0");
  o = {};
  o.cpd.outlier_weight = 1;
  EXPECT_EQ(o.validate(), "cpd.outlier_weight must be in [0, 1), got 1");
  o = {};
  o.min_pair_iou = 1;
  EXPECT_EQ(o.validate(), "min_pair_iou must be in [0, 1), got 1");
}

// --trials and study.yaml's registration.trials set the configured method's own budget.
TEST(RegistrationOptions, TrialsIsTheMethodsOwnBudget) {
  RegistrationOptions o;
  o.trials() = 7;
  EXPECT_EQ(o.consensus.max_hypotheses, 7);
  o.method = RegistrationMethod::kPaper;
  o.trials() = 8;
  EXPECT_EQ(o.paper.samples, 8);
  o.method = RegistrationMethod::kCpd;
  o.trials() = 9;
  EXPECT_EQ(o.cpd.iterations, 9);
  EXPECT_EQ(o.consensus.max_hypotheses, 7);
  EXPECT_EQ(o.paper.samples, 8);
  EXPECT_EQ(static_cast<const RegistrationOptions&>(o).trials(), 9);
}

// cpd holds a weight for every (A, B) rock pair: past 16 million pairs it refuses with the sizes, the limit and
// the method that takes such layouts, before allocating (20,000 x 20,000 would need 3.2 GB for the weights).
TEST(RegistrationMethods, CpdRefusesLayoutsOverItsPairLimitAndNamesTheAlternative) {
  std::vector<Box> a(4001), b(4001);
  for (int k = 0; k < 4001; ++k) {
    a[k].cx = (k % 64 + 0.5) / 64, a[k].cy = (k / 64 + 0.5) / 64, a[k].w = a[k].h = 0.01;
    b[k] = a[k];
    b[k].cx += 0.1 / 64;
  }
  RegistrationOptions o;
  o.method = RegistrationMethod::kCpd;
  try {
    register_rocks(a, b, o);
    ADD_FAILURE() << "4,001 x 4,001 rocks registered with cpd";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "--method cpd: 4001 x 4001 rocks is 16008001 rock pairs, over cpd's limit of 16000000 (it holds a "
                 "weight for every pair in memory); --method consensus registers layouts this large (or give cpd a "
                 "time budget: it then registers the largest rocks of each side)");
  }
}

// Each method scores its answer in its own unit and direction: paper's mean distance and cpd's mixture width are
// better lower, consensus' soft inlier count higher; every report prints the measure's name with the number.
TEST(Registration, EachMethodsFitIsReadInItsOwnMeasure) {
  EXPECT_EQ(fit_measure_of(RegistrationMethod::kPaper), FitMeasure::kMeanDistance);
  EXPECT_EQ(fit_measure_of(RegistrationMethod::kConsensus), FitMeasure::kSoftInliers);
  EXPECT_EQ(fit_measure_of(RegistrationMethod::kCpd), FitMeasure::kMixtureWidth);
  EXPECT_TRUE(lower_is_better(FitMeasure::kMeanDistance));
  EXPECT_TRUE(lower_is_better(FitMeasure::kMixtureWidth));
  EXPECT_FALSE(lower_is_better(FitMeasure::kSoftInliers));
  EXPECT_EQ(fit_text({FitMeasure::kMeanDistance, 0.000437}, 5), "mean distance 0.00044");
  EXPECT_EQ(fit_text({FitMeasure::kSoftInliers, 16.89721}, 4), "soft inliers 16.8972");
  EXPECT_EQ(fit_text({FitMeasure::kMixtureWidth, -0.0000001}, 4), "mixture width 0.0000");  // no "-0.0000"
  // An exact fit's width is tiny, not nothing: said as below the last decimal shown.
  EXPECT_EQ(fit_text({FitMeasure::kMixtureWidth, 3.2e-9}, 4), "mixture width below 0.0001");
  EXPECT_EQ(fit_text({FitMeasure::kMixtureWidth, 0.0}, 4), "mixture width 0.0000");
  EXPECT_EQ(fit_text({FitMeasure::kNotScored, 3.0}, 4), "not scored");
  EXPECT_EQ(std::string(fit_measure_key(FitMeasure::kMixtureWidth)), "mixture_width");
}

}  // namespace
}  // namespace ipd
