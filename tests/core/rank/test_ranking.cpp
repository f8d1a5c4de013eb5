// The ranking of renderer settings: Holm's correction by hand, and a generated study whose true best setting
// is known (core/demo/variant_study.h): the ranking finds it, keeps the settings within the noise in its group
// and leaves the far ones out, and its Holm p-values equal an independent computation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/demo/variant_study.h"
#include "core/ipd/ipd.h"
#include "core/rank/holm.h"
#include "core/rank/ranking.h"
#include "core/stats/study_statistics.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

TEST(Holm, StepDownAdjustmentByHand) {
  // Sorted: 0.005 x 4 = 0.02, 0.01 x 3 = 0.03, 0.03 x 2 = 0.06, 0.04 x 1 = 0.04 -> kept at 0.06 (step-down max).
  const std::vector<double> adjusted = holm_adjusted({0.01, 0.04, 0.03, 0.005});
  ASSERT_EQ(adjusted.size(), 4u);
  EXPECT_DOUBLE_EQ(adjusted[0], 0.03);
  EXPECT_DOUBLE_EQ(adjusted[1], 0.06);
  EXPECT_DOUBLE_EQ(adjusted[2], 0.06);
  EXPECT_DOUBLE_EQ(adjusted[3], 0.02);
}

TEST(Holm, UntestedStaysUntestedAndDoesNotCount) {
  // m = 2 (the NaN is no test): 0.2 x 2 = 0.4, 0.6 x 1 = 0.6.
  const std::vector<double> adjusted = holm_adjusted({std::nan(""), 0.2, 0.6});
  EXPECT_TRUE(std::isnan(adjusted[0]));
  EXPECT_DOUBLE_EQ(adjusted[1], 0.4);
  EXPECT_DOUBLE_EQ(adjusted[2], 0.6);
}

TEST(Holm, CappedAtOne) {
  const std::vector<double> adjusted = holm_adjusted({0.5, 0.7});
  EXPECT_DOUBLE_EQ(adjusted[0], 1.0);
  EXPECT_DOUBLE_EQ(adjusted[1], 1.0);
}

struct RankedVariants {
  StudyLabels labels;
  CrossTable table;
  Ranking ranking;
};

// The generated study ranked against `real` for det-real, only the (real, variant) pairs registered.
RankedVariants rank_variants(const std::string& dir, const VariantStudyOptions& v) {
  write_variant_study(dir, v);
  RankedVariants out{load_labels(open_study(dir)), {}, {}};
  TableOptions to;
  to.models = {"det-real"};
  to.only_pairs = ranked_pairs(resolve_rank_domains(out.labels.study, "real", {}));
  out.table = compute_cross_table(out.labels, to);
  BootstrapOptions b;
  add_confidence_intervals(&out.table, b);
  RankOptions ro;
  ro.model = "det-real";
  ro.domains = resolve_rank_domains(out.labels.study, "real", {});
  ro.compare.bootstrap = b;
  out.ranking = rank_candidates(out.labels, out.table, ro);
  return out;
}

TEST(Ranking, GeneratedStudyBestIsTheTrueBestAndItsGroupHoldsTheNearSettingsOnly) {
  test::TempDir d;
  VariantStudyOptions v;  // 9 variants at ambient 0, 0.125, ..., 1; the true best 0.375 (ambient-038)
  const RankedVariants r = rank_variants(d.path(), v);
  ASSERT_EQ(r.ranking.ranked.size(), 9u);
  EXPECT_EQ(r.ranking.best()->domain, "ambient-038");
  EXPECT_EQ(r.ranking.best()->domain, variant_domain(v, true_best_variant(v)));
  EXPECT_EQ(r.ranking.tests, 8);
  auto in_group = [&](const std::string& d) {
    for (const auto& c : r.ranking.ranked)
      if (c.domain == d) return c.in_best_group;
    ADD_FAILURE() << d << " not ranked";
    return false;
  };
  // 0.125 from the true ambient term: within the noise.
  EXPECT_TRUE(in_group("ambient-025"));
  EXPECT_TRUE(in_group("ambient-050"));
  // 0.375 and more: far off.
  for (const char* far : {"ambient-000", "ambient-075", "ambient-088", "ambient-100"})
    EXPECT_FALSE(in_group(far)) << far;
  // Only the (real, variant) pairs were registered: 9 pairs x 40 scenes, no variant-vs-variant pair.
  EXPECT_EQ(r.table.registrations, 9 * 40);
  // The ranking's IPD and interval are the table's cell, its Δ and p compare's.
  for (const auto& c : r.ranking.ranked) {
    const TableCell* cell = r.table.cell("det-real", "real", c.domain);
    EXPECT_EQ(c.ipd, cell->ipd);
    EXPECT_EQ(c.ci_low, cell->ci_low);
    if (!c.vs_best) continue;
    CompareOptions co;
    const RendererComparison cmp =
        compare_renderers(r.table, "det-real", "real", c.domain, r.ranking.best()->domain, co);
    EXPECT_EQ(c.vs_best->result.p_value, cmp.result.p_value);
    EXPECT_EQ(c.vs_best->result.delta.low, cmp.result.delta.low);
  }
}

// Per scene (Σ|diff|, pairs) of the cell (real, domain), by stem.
std::map<std::string, SceneSum> sums_of(const CrossTable& t, const std::string& domain) {
  std::map<std::string, SceneSum> out;
  for (const auto& s : t.cell("det-real", "real", domain)->per_scene) out[s.stem] = {s.sum_abs_diff, s.pairs};
  return out;
}

// The sign-flip p-value of Δ = IPD(real, a) − IPD(real, b), computed here from the per-scene sums: exactly over
// every swap pattern, or from `draws` random patterns of our own generator.
double independent_p(const std::map<std::string, SceneSum>& a, const std::map<std::string, SceneSum>& b, long draws) {
  std::vector<SceneSum> sa, sb;
  for (const auto& [stem, s] : a) {
    sa.push_back(s);
    sb.push_back(b.at(stem));
  }
  const size_t n = sa.size();
  auto delta = [&](auto swapped) {
    double xa = 0, xb = 0, na = 0, nb = 0;
    for (size_t i = 0; i < n; ++i) {
      const SceneSum& u = swapped(i) ? sb[i] : sa[i];
      const SceneSum& w = swapped(i) ? sa[i] : sb[i];
      xa += u.sum, na += u.count, xb += w.sum, nb += w.count;
    }
    return xa / na - xb / nb;
  };
  const double observed = std::abs(delta([](size_t) { return false; }));
  long extreme = 0;
  if (draws == 0) {
    for (std::uint64_t pattern = 0; pattern < (std::uint64_t{1} << n); ++pattern)
      extreme += std::abs(delta([&](size_t i) { return (pattern >> i) & 1u; })) >= observed - 1e-12;
    return static_cast<double>(extreme) / static_cast<double>(std::uint64_t{1} << n);
  }
  std::mt19937_64 g(12345);
  std::vector<bool> flip(n);
  for (long r = 0; r < draws; ++r) {
    for (size_t i = 0; i < n; ++i) flip[i] = g() & 1u;
    extreme += std::abs(delta([&](size_t i) { return flip[i]; })) >= observed - 1e-12;
  }
  return (1.0 + extreme) / (draws + 1.0);
}

// Holm, written the textbook way: sort (p, position), multiply the k-th smallest by m - k, keep the running max.
std::vector<double> independent_holm(const std::vector<double>& p) {
  std::vector<std::pair<double, size_t>> sorted;
  for (size_t i = 0; i < p.size(); ++i) sorted.emplace_back(p[i], i);
  std::sort(sorted.begin(), sorted.end());
  std::vector<double> out(p.size());
  double running = 0;
  for (size_t k = 0; k < sorted.size(); ++k) {
    running = std::max(running, std::min(1.0, static_cast<double>(sorted.size() - k) * sorted[k].first));
    out[sorted[k].second] = running;
  }
  return out;
}

TEST(Ranking, HolmPValuesOfTheExactTestEqualAnIndependentComputation) {
  test::TempDir d;
  VariantStudyOptions v;
  v.scenes = 8;  // 2^8 = 256 swap patterns <= 2,000 permutations: every p is exact
  v.seed = 3;
  const RankedVariants r = rank_variants(d.path(), v);
  const auto best = sums_of(r.table, r.ranking.best()->domain);
  std::vector<double> raw;
  for (size_t k = 1; k < r.ranking.ranked.size(); ++k) {
    ASSERT_TRUE(r.ranking.ranked[k].vs_best->result.exact_p);
    raw.push_back(independent_p(sums_of(r.table, r.ranking.ranked[k].domain), best, 0));
    EXPECT_NEAR(r.ranking.ranked[k].vs_best->result.p_value, raw.back(), 1e-12) << r.ranking.ranked[k].domain;
  }
  const std::vector<double> holm = independent_holm(raw);
  for (size_t k = 1; k < r.ranking.ranked.size(); ++k)
    EXPECT_NEAR(r.ranking.ranked[k].p_holm, holm[k - 1], 1e-12) << r.ranking.ranked[k].domain;
  // The smallest exact p of 8 scenes is 2/256; Holm over 8 comparisons multiplies it by 8.
  EXPECT_NEAR(*std::min_element(holm.begin(), holm.end()), 8 * 2.0 / 256, 1e-12);
  // So at 0.05 no candidate differs from the best after Holm's correction, although some raw p-values are below it:
  // the group is decided on the corrected p-value.
  EXPECT_LT(*std::min_element(raw.begin(), raw.end()), 0.05);
  for (const auto& c : r.ranking.ranked) EXPECT_TRUE(c.in_best_group) << c.domain;
}

TEST(Ranking, HolmPValuesOfThePermutationTestAgreeWithinMonteCarloError) {
  test::TempDir d;
  VariantStudyOptions v;  // 40 scenes: 2,000 random swap patterns
  const RankedVariants r = rank_variants(d.path(), v);
  const auto best = sums_of(r.table, r.ranking.best()->domain);
  std::vector<double> raw;
  for (size_t k = 1; k < r.ranking.ranked.size(); ++k)
    raw.push_back(independent_p(sums_of(r.table, r.ranking.ranked[k].domain), best, 20000));
  const std::vector<double> holm = independent_holm(raw);
  for (size_t k = 1; k < r.ranking.ranked.size(); ++k) {
    const double p = holm[k - 1];
    // Four standard errors of a 2,000-permutation p, times Holm's largest factor, plus its 1/(N + 1) floor.
    const double tolerance = 8 * 4 * std::sqrt(std::max(p, 1e-3) * (1 - std::min(p, 0.999)) / 2000) + 8.0 / 2001;
    EXPECT_NEAR(r.ranking.ranked[k].p_holm, p, tolerance) << r.ranking.ranked[k].domain;
  }
}

TEST(Ranking, UnknownDomainsAreNamedWithTheStudysDomains) {
  test::TempDir d;
  VariantStudyOptions v;
  v.variants = 2;
  v.scenes = 2;
  write_variant_study(d.path(), v);
  const Study s = open_study(d.path());
  try {
    resolve_rank_domains(s, "reel", {});
    FAIL() << "an unknown reference was accepted";
  } catch (const StudyError& e) {
    EXPECT_EQ(std::string(e.what()), d.path() +
                                         ": no domain 'reel' in this study (--ref; the study's domains: real, "
                                         "ambient-000, ambient-100)");
  }
  try {
    resolve_rank_domains(s, "real", {"ambient-000", "real"});
    FAIL() << "the reference was accepted as a candidate";
  } catch (const StudyError& e) {
    EXPECT_EQ(std::string(e.what()), d.path() + ": 'real' is the reference (--ref) and cannot also be a candidate");
  }
  EXPECT_EQ(resolve_rank_domains(s, "", {}).candidates, (std::vector<std::string>{"ambient-000", "ambient-100"}));
}

}  // namespace
}  // namespace ipd
