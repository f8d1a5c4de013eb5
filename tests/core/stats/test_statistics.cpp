// Bootstrap intervals, the paired comparison and breakdowns: values worked out by hand.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <cmath>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <regex>

#include "core/demo/demo_study.h"
#include "core/session/session_statistics.h"
#include "core/stats/statistics.h"
#include "core/stats/study_statistics.h"
#include "core/study/study.h"
#include "tests/support/figure_test_study.h"
#include "tests/support/stats_study.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

// Three scenes (Σ|diff|, pairs): (1.0, 2), (0.6, 3), (0.3, 1); pooled 1.9 / 6.
const std::vector<SceneSum> kThreeScenes = {{1.0, 2}, {0.6, 3}, {0.3, 1}};

TEST(Statistics, BootstrapWithInjectedDrawsWorkedByHand) {
  // Resamples {0,0,1} -> 2.6/7, {1,2,2} -> 1.2/5, {2,2,2} -> 0.9/3, {0,1,2} -> 1.9/6.
  // Sorted 0.24, 0.3, 0.31667, 0.37143; a 50% interval is the 25th and 75th percentile with linear
  // interpolation: 0.24 + 0.75 * 0.06 = 0.285 and 0.31667 + 0.25 * (0.37143 - 0.31667) = 0.330357.
  FixedIndexSource draws({{0, 0, 1}, {1, 2, 2}, {2, 2, 2}, {0, 1, 2}});
  BootstrapOptions o;
  o.resamples = 4;
  o.level = 0.5;
  const Interval ci = bootstrap_pooled_mean(kThreeScenes, o, draws);
  EXPECT_NEAR(ci.estimate, 1.9 / 6, 1e-15);
  EXPECT_NEAR(ci.low, 0.285, 1e-12);
  EXPECT_NEAR(ci.high, 0.33035714285714285, 1e-12);
  EXPECT_NEAR(ci.se, 0.054106324316717, 1e-12);  // sample standard deviation of the four
  EXPECT_EQ(ci.resamples, 4);
}

TEST(Statistics, ResamplesWithoutPairsAreLeftOut) {
  // {1,1,1} has no pairs (left out); {0,1,2} -> 0.7/2 = 0.35; {0,0,1} -> 1.0/2 = 0.5. A 95% interval of
  // the two: 0.35 + 0.025 * 0.15 = 0.35375 and 0.35 + 0.975 * 0.15 = 0.49625.
  const std::vector<SceneSum> scenes = {{0.5, 1}, {0, 0}, {0.2, 1}};
  FixedIndexSource draws({{1, 1, 1}, {0, 1, 2}, {0, 0, 1}});
  BootstrapOptions o;
  o.resamples = 3;
  const Interval ci = bootstrap_pooled_mean(scenes, o, draws);
  EXPECT_EQ(ci.resamples, 2);
  EXPECT_NEAR(ci.low, 0.35375, 1e-12);
  EXPECT_NEAR(ci.high, 0.49625, 1e-12);
  EXPECT_NEAR(ci.se, 0.15 / std::sqrt(2.0), 1e-12);
}

// One scene with pairs resamples to itself: [0.5, 0.5] would claim a certainty one scene cannot give, so
// there is no interval (and no comparison interval or test).
TEST(Statistics, OneSceneWithPairsHasNoIntervalAndNoTest) {
  FixedIndexSource draws({{1, 1}, {0, 1}, {0, 0}});
  BootstrapOptions o;
  o.resamples = 3;
  const Interval ci = bootstrap_pooled_mean({{0.5, 1}, {0, 0}}, o, draws);
  EXPECT_DOUBLE_EQ(ci.estimate, 0.5);
  EXPECT_FALSE(ci.has_interval());
  EXPECT_EQ(ci.resamples, 0);
  const std::vector<PairedScene> one(1, PairedScene{{0.1, 1}, {0.5, 1}, {0.1, 1}, {0.5, 1}});
  CompareOptions co;
  co.bootstrap.resamples = 10;
  const Comparison c = compare_paired(one, co, "det|real|a|b");
  EXPECT_NEAR(c.delta.estimate, -0.4, 1e-15);
  EXPECT_FALSE(c.delta.has_interval());
  EXPECT_TRUE(std::isnan(c.p_value));
  EXPECT_FALSE(c.exact_p);
  EXPECT_EQ(c.scenes, 1);
  RendererComparison rc;
  rc.model = "det", rc.ref = "real", rc.a = "a", rc.b = "b", rc.result = c;
  EXPECT_EQ(
      comparison_sentence(rc),
      "cannot tell whether a or b is closer to real for det: \u0394IPD = \u22120.4000, 1 scene: no interval, no test");
}

// The verdict needs the test and the interval both: when one alone tells the renderers apart, the sentence says which.
TEST(Statistics, ComparisonSentenceSaysWhichHalfOfTheVerdictIsMissing) {
  RendererComparison rc;
  rc.model = "det", rc.ref = "real", rc.a = "a", rc.b = "b";
  rc.result.delta.estimate = -0.02;
  rc.result.delta.low = -0.03;
  rc.result.delta.high = -0.01;
  rc.result.p_value = 0.0625;
  rc.result.exact_p = true;
  rc.result.scenes = 10000;
  EXPECT_EQ(comparison_sentence(rc),
            "no significant difference between a and b in closeness to real for det: \u0394IPD = \u22120.0200 "
            "[\u22120.030, \u22120.010], p = 0.062 (exact), 10,000 scenes; the interval excludes 0, but p is not below "
            "0.05");
  rc.result.delta.high = 0.01;
  rc.result.p_value = 0.01;
  rc.result.exact_p = false;
  EXPECT_EQ(comparison_sentence(rc),
            "no significant difference between a and b in closeness to real for det: \u0394IPD = \u22120.0200 "
            "[\u22120.030, 0.010], p = 0.01, 10,000 scenes; p is below 0.05, but the interval holds 0");
  rc.result.p_value = 0.5;
  EXPECT_EQ(comparison_sentence(rc, 0.05).find(";"), std::string::npos);
  // Five scenes: the exact test's smallest p is 2/32, so no interval can be joined by the test at 0.05.
  rc.result.delta.high = -0.01;
  rc.result.p_value = 0.0625;
  rc.result.exact_p = true;
  rc.result.scenes = 5;
  EXPECT_EQ(comparison_sentence(rc),
            "no significant difference between a and b in closeness to real for det: \u0394IPD = \u22120.0200 "
            "[\u22120.030, \u22120.010], p = 0.062 (exact), 5 scenes; the interval excludes 0, but with 5 scenes "
            "the exact test's p can't go below 0.062: more scenes are needed");
  // A 99% interval goes with the level 0.01.
  EXPECT_EQ(level_of_interval(0.99), 0.01);
  EXPECT_EQ(level_of_interval(0.95), 0.05);
}

TEST(Statistics, SeededDrawsDependOnSeedAndKeyOnly) {
  BootstrapOptions o;
  const Interval a = bootstrap_pooled_mean(kThreeScenes, o, "m|real|synth");
  const Interval b = bootstrap_pooled_mean(kThreeScenes, o, "m|real|synth");
  EXPECT_EQ(a.low, b.low);
  EXPECT_EQ(a.high, b.high);
  EXPECT_EQ(a.se, b.se);
  o.seed = 1;
  const Interval c = bootstrap_pooled_mean(kThreeScenes, o, "m|real|synth");
  EXPECT_NE(a.se, c.se);
  // Every resample lies between {1,1,1} = 0.6/3 and {0,0,0} = 1.0/2.
  EXPECT_GE(a.low, 0.2 - 1e-12);
  EXPECT_LE(a.high, 0.5 + 1e-12);
  EXPECT_LT(a.low, a.estimate);
  EXPECT_GT(a.high, a.estimate);
}

TEST(Statistics, KeyedBootstrapDrawsWhatTheSeededSourceDraws) {
  // The keyed overload generates its indices inline; it must be the documented stream exactly.
  std::vector<SceneSum> scenes;
  for (int k = 0; k < 37; ++k) scenes.push_back({0.01 * ((k * 7) % 11), k % 5});
  BootstrapOptions o;
  o.resamples = 500;
  o.seed = 9;
  SeededIndexSource source(9, "det|real|hapke");
  const Interval a = bootstrap_pooled_mean(scenes, o, source), b = bootstrap_pooled_mean(scenes, o, "det|real|hapke");
  EXPECT_EQ(a.resamples, b.resamples);
  EXPECT_DOUBLE_EQ(a.low, b.low);
  EXPECT_DOUBLE_EQ(a.high, b.high);
  EXPECT_DOUBLE_EQ(a.se, b.se);
}

TEST(Statistics, BadOptionsAreRefused) {
  BootstrapOptions o;
  o.level = 95;
  EXPECT_EQ(o.validate(), "the interval level must be between 0 and 1 (e.g. 0.95), not 95");
  EXPECT_THROW(bootstrap_pooled_mean(kThreeScenes, o, "k"), std::invalid_argument);
  FixedIndexSource too_short({{0, 1}});
  BootstrapOptions one;
  one.resamples = 1;
  EXPECT_THROW(bootstrap_pooled_mean(kThreeScenes, one, too_short), std::logic_error);
}

TEST(Statistics, PairedComparisonWorkedByHand) {
  // Scene 0: a (0.2, 2), b (0.8, 2); scene 1: a (0.1, 1), b (0.1, 1). Δ = 0.3/3 - 0.9/3 = -0.2.
  std::vector<PairedScene> scenes(2);
  scenes[0].a = {0.2, 2};
  scenes[0].b = {0.8, 2};
  scenes[1].a = {0.1, 1};
  scenes[1].b = {0.1, 1};
  scenes[0].common_a = {0.2, 2};
  scenes[0].common_b = {0.6, 2};
  // Bootstrap {0,0}: 0.4/4 - 1.6/4 = -0.3; {1,1}: 0; {0,1}: -0.2.
  FixedIndexSource boot({{0, 0}, {1, 1}, {0, 1}});
  // Permutations (1 = swap): {0,0} -> -0.2; {1,0} -> 0.9/3 - 0.3/3 = 0.2; {0,1} -> -0.2; {1,1} -> 0.2;
  // {0,0} again: all five reach |Δ| = 0.2, so p = (1 + 5) / (5 + 1) = 1.
  FixedIndexSource perm({{0, 0}, {1, 0}, {0, 1}, {1, 1}, {0, 0}});
  CompareOptions o;
  o.bootstrap.resamples = 3;
  o.bootstrap.level = 0.5;
  o.permutations = 5;
  const Comparison c = compare_paired(scenes, o, boot, perm);
  EXPECT_NEAR(c.ipd_a, 0.1, 1e-15);
  EXPECT_NEAR(c.ipd_b, 0.3, 1e-15);
  EXPECT_NEAR(c.delta.estimate, -0.2, 1e-15);
  EXPECT_NEAR(c.delta.low, -0.25, 1e-12);  // sorted -0.3, -0.2, 0: 25th percentile -0.25, 75th -0.1
  EXPECT_NEAR(c.delta.high, -0.1, 1e-12);
  EXPECT_DOUBLE_EQ(c.p_value, 1.0);
  EXPECT_NEAR(c.delta_common, (0.2 - 0.6) / 2, 1e-15);
  EXPECT_EQ(c.pairs_a, 3);
  EXPECT_EQ(c.pairs_b, 3);
  EXPECT_EQ(c.scenes, 2);

  // Now scene 1 also favours a strongly: b (0.9, 1). Δ = 0.3/3 - 1.7/3. Only no-swap and all-swap
  // permutations reach |Δ|: two of the four below, p = (1 + 2) / 5.
  scenes[1].b = {0.9, 1};
  FixedIndexSource boot2({{0, 1}, {1, 0}});  // two resamples: the fewest that give an interval
  FixedIndexSource perm2({{0, 0}, {1, 0}, {0, 1}, {1, 1}});
  o.bootstrap.resamples = 2;
  o.permutations = 4;
  const Comparison c2 = compare_paired(scenes, o, boot2, perm2);
  EXPECT_NEAR(c2.delta.estimate, (0.3 - 1.7) / 3, 1e-15);
  EXPECT_DOUBLE_EQ(c2.p_value, 3.0 / 5);
}

TEST(Statistics, FewScenesGetTheExactPermutationP) {
  // Three identical scenes, a at 0.1 and b at 0.5: swapping k of them gives Δ* = 0.4 (2k - 3) / 3, so only
  // k = 0 and k = 3 reach |Δ| = 0.4: exactly 2 of the 8 patterns, p = 0.25 whatever the seed.
  const std::vector<PairedScene> scenes(3, PairedScene{{0.1, 1}, {0.5, 1}, {0.1, 1}, {0.5, 1}});
  CompareOptions o;
  o.bootstrap.resamples = 10;
  for (std::uint64_t seed : {0u, 7u}) {
    o.bootstrap.seed = seed;
    const Comparison c = compare_paired(scenes, o, "det|real|a|b");
    EXPECT_TRUE(c.exact_p);
    EXPECT_EQ(c.permutations, 8);
    EXPECT_DOUBLE_EQ(c.p_value, 0.25);
  }
  o.permutations = 7;  // fewer than 2^3: sampled, (1 + #) / (N + 1)
  const Comparison sampled = compare_paired(scenes, o, "det|real|a|b");
  EXPECT_FALSE(sampled.exact_p);
  EXPECT_EQ(sampled.permutations, 7);
}

TEST(Statistics, QuantilesAndSpearmanWithTies) {
  EXPECT_DOUBLE_EQ(quantile({4, 1, 3, 2}, 0.5), 2.5);
  EXPECT_DOUBLE_EQ(quantile({4, 1, 3, 2}, 0.25), 1.75);
  EXPECT_TRUE(std::isnan(quantile({}, 0.5)));
  EXPECT_EQ(quantile_edges({1, 2, 3, 4, 5}, 4), (std::vector<double>{2, 3, 4}));
  // x ranks 1, 2.5, 2.5, 4; y ranks 1, 2, 3, 4 -> r = 4.5 / sqrt(4.5 * 5) (scipy.stats.spearmanr: 0.9486833)
  EXPECT_NEAR(spearman({1, 2, 2, 3}, {10, 20, 30, 40}), 0.9486832980505138, 1e-12);
  EXPECT_NEAR(spearman({1, 2, 3}, {3, 2, 1}), -1.0, 1e-15);
  EXPECT_TRUE(std::isnan(spearman({1, 1, 1}, {1, 2, 3})));
}

// ----- on a study -------------------------------------------------------------------------------------

CrossTable table_with_intervals(const std::string& root, int threads, std::uint64_t seed) {
  TableOptions t;
  t.threads = threads;
  CrossTable table = compute_cross_table(load_labels(open_study(root)), t);
  BootstrapOptions b;
  b.seed = seed;
  add_confidence_intervals(&table, b, threads);
  return table;
}

TEST(StudyStatistics, IntervalsAreTheSameForAnyThreadCountAndMoveWithTheSeed) {
  test::TempDir d;
  test::write_stats_study(d.path(), test::StatsStudyVariant::kDistinct);
  const CrossTable one = table_with_intervals(d.path(), 1, 0), two = table_with_intervals(d.path(), 2, 0);
  const CrossTable other_seed = table_with_intervals(d.path(), 2, 5);
  ASSERT_EQ(one.cells.size(), two.cells.size());
  int with_ci = 0;
  for (size_t k = 0; k < one.cells.size(); ++k) {
    const auto &x = one.cells[k], &y = two.cells[k], &z = other_seed.cells[k];
    if (std::isnan(x.ci_low)) continue;
    ++with_ci;
    EXPECT_EQ(x.ci_low, y.ci_low);
    EXPECT_EQ(x.ci_high, y.ci_high);
    EXPECT_EQ(x.se, y.se);
    EXPECT_LE(x.ci_low, x.ipd);
    EXPECT_GE(x.ci_high, x.ipd);
    if (x.ci_high > x.ci_low) {
      EXPECT_TRUE(x.ci_low != z.ci_low || x.ci_high != z.ci_high) << cell_key(x);
    }
  }
  EXPECT_GE(with_ci, 2);
}

TEST(StudyStatistics, CompareWhenBIsA) {
  test::TempDir d;
  test::write_stats_study(d.path(), test::StatsStudyVariant::kHapkeIsPrincipled);
  const CrossTable t = table_with_intervals(d.path(), 2, 0);
  const RendererComparison c = compare_renderers(t, "det", "real", "principled", "hapke", {});
  EXPECT_EQ(c.result.scenes, 12);
  EXPECT_GT(c.result.ipd_a, 0.01);
  EXPECT_EQ(c.result.delta.estimate, 0.0);
  EXPECT_EQ(c.result.delta.low, 0.0);
  EXPECT_EQ(c.result.delta.high, 0.0);
  EXPECT_EQ(c.result.p_value, 1.0);
  EXPECT_EQ(c.result.delta_common, 0.0);
  EXPECT_EQ(comparison_sentence(c).rfind("no significant difference between principled and hapke in closeness to "
                                         "real for det: ΔIPD = 0.0000 [0.000, 0.000], p = 1, 12 scenes",
                                         0),
            0u)
      << comparison_sentence(c);
}

// No permutations asked for: no p, so no verdict, even with an interval that excludes 0.
TEST(StudyStatistics, CompareWithoutATestGivesNoVerdict) {
  test::TempDir d;
  test::write_stats_study(d.path(), test::StatsStudyVariant::kPrincipledIsReal);
  const CrossTable t = table_with_intervals(d.path(), 2, 0);
  CompareOptions o;
  o.permutations = 0;
  const RendererComparison c = compare_renderers(t, "det", "real", "principled", "hapke", o);
  EXPECT_TRUE(std::isnan(c.result.p_value));
  ASSERT_LT(c.result.delta.high, 0);
  const std::string s = comparison_sentence(c);
  EXPECT_EQ(s.rfind("not tested whether principled or hapke is closer to real for det: ΔIPD = −", 0), 0u) << s;
  EXPECT_NE(s.find(", 12 scenes (no permutation test was run)"), std::string::npos) << s;
}

TEST(StudyStatistics, CompareWhenAIsTheReference) {
  test::TempDir d;
  test::write_stats_study(d.path(), test::StatsStudyVariant::kPrincipledIsReal);
  const CrossTable t = table_with_intervals(d.path(), 2, 0);
  EXPECT_EQ(t.cell("det", "real", "principled")->ipd, 0.0);
  const double ipd_hapke = t.cell("det", "real", "hapke")->ipd;
  ASSERT_GT(ipd_hapke, 0.05);
  const RendererComparison c = compare_renderers(t, "det", "real", "principled", "hapke", {});
  EXPECT_NEAR(c.result.delta.estimate, -ipd_hapke, 1e-15);
  EXPECT_LT(c.result.delta.high, 0);
  // Only "no swap" and "swap all" reach |Δ| among 2^12 sign patterns: p is about 1/1000.
  EXPECT_LT(c.result.p_value, 0.005);
  EXPECT_GE(c.result.p_value, 1.0 / 2001);
  EXPECT_EQ(comparison_sentence(c).rfind("principled is closer to real than hapke for det: ΔIPD = −", 0), 0u)
      << comparison_sentence(c);
  EXPECT_THROW(compare_renderers(t, "det", "real", "real", "hapke", {}), StudyError);
  EXPECT_THROW(compare_renderers(t, "nope", "real", "principled", "hapke", {}), StudyError);
}

TEST(StudyStatistics, BreakdownBinsAddUpToTheCell) {
  test::TempDir d;
  test::write_stats_study(d.path(), test::StatsStudyVariant::kDistinct);
  const StudyLabels labels = load_labels(open_study(d.path()));
  const CrossTable t = compute_cross_table(labels, {});
  const TableCell& cell = *t.cell("det", "real", "hapke");
  for (auto by : {BreakdownBy::kSize, BreakdownBy::kRegion, BreakdownBy::kConfidence}) {
    BreakdownOptions o;
    o.by = by;
    const CellBreakdown b = breakdown_cell(labels, cell, o);
    long pairs = 0;
    double sum = 0;
    for (const auto& bin : b.bins) {
      pairs += bin.pairs;
      if (bin.pairs > 0) sum += bin.ipd.estimate * bin.pairs;
    }
    EXPECT_EQ(pairs, cell.pairs) << to_string(by);
    EXPECT_NEAR(sum / pairs, cell.ipd, 1e-12) << to_string(by);
    if (by == BreakdownBy::kSize) {
      ASSERT_EQ(b.bins.size(), 4u);
      // quantile bins: about a quarter of the pairs each
      for (const auto& bin : b.bins) EXPECT_NEAR(bin.pairs, cell.pairs / 4.0, cell.pairs / 8.0) << bin.label;
      // the study makes small rocks harder to find in hapke: the smallest bin has the largest IPD
      EXPECT_GT(b.bins.front().ipd.estimate, b.bins.back().ipd.estimate);
      // Labels name the range with an en dash, in px², from the lowest to the highest size present.
      EXPECT_EQ(b.bins.front().label, fmt::format("{:.0f}\u2013{:.0f} px²", b.bins.front().low, b.bins.front().high));
      EXPECT_NE(b.bins.back().label.find("\u2013"), std::string::npos) << b.bins.back().label;
    }
    if (by == BreakdownBy::kRegion) {
      EXPECT_EQ(b.bins.size(), 9u);
    }
  }
}

}  // namespace
}  // namespace ipd

namespace ipd {
namespace {

TEST(StudyStatistics, SessionStatisticsMatchTheTableAndFollowEdits) {
  test::TempDir d;
  test::write_stats_study(d.path(), test::StatsStudyVariant::kDistinct);
  Session s = Session::open(d.path());
  ASSERT_TRUE(s.select_domains("real", "hapke"));
  SessionStatisticsRequest r;
  r.model = "det";
  r.pair = s.pair_index();
  r.ref = "real";
  r.a = "principled";
  r.b = "hapke";
  const SessionStatistics st = compute_session_statistics(s, r);
  const CrossTable t = table_with_intervals(d.path(), 1, 0);
  for (const auto& c : t.cells) {
    const TableCell* live = st.table.cell(c.model, c.a, c.b);
    ASSERT_NE(live, nullptr);
    EXPECT_NEAR(live->ipd, c.ipd, 1e-12) << cell_key(c);
    EXPECT_NEAR(live->ci_low, c.ci_low, 1e-12) << cell_key(c);
    EXPECT_NEAR(live->ci_high, c.ci_high, 1e-12) << cell_key(c);
  }
  ASSERT_EQ(st.scene_ipd.size(), 12u);
  EXPECT_EQ(st.scene_ipd[0].first, "s00");
  EXPECT_NEAR(st.scene_ipd[0].second, t.cell("det", "real", "hapke")->per_scene[0].ipd(), 1e-12);
  ASSERT_TRUE(st.size.has_value());
  EXPECT_EQ(st.size->bins.size(), 4u);
  ASSERT_TRUE(st.comparison.has_value());
  EXPECT_LT(st.comparison->result.delta.estimate, 0);  // principled is closer to real than hapke
  // An edit (unpair everything in scene 0) changes scene 0's IPD and the cell's interval.
  for (int k = 0; k < 10; ++k) s.apply(0, Edit::unpair(Side::kA, k));
  const SessionStatistics after = compute_session_statistics(s, r);
  EXPECT_EQ(after.scene_ipd.size(), 11u);
  EXPECT_NE(after.table.cell("det", "real", "hapke")->ci_low, st.table.cell("det", "real", "hapke")->ci_low);
}

}  // namespace
}  // namespace ipd

namespace ipd {
namespace {

TEST(StatsCli, SameOutputForAnyThreadCountAndTheDocumentedJson) {
  test::TempDir d;
  test::write_stats_study(d.path(), test::StatsStudyVariant::kDistinct);
  const std::string table = "table " + d.path() + " --format json";
  const auto one = test::run_ipd(table + " --threads 1"), two = test::run_ipd(table + " --threads 2");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_EQ(one.out, two.out);
  const auto other_seed = test::run_ipd(table + " --threads 2 --seed 1");
  EXPECT_NE(one.out, other_seed.out);
  const auto j = nlohmann::json::parse(one.out);
  EXPECT_TRUE(j["cells"][0]["ci_low"].is_number());
  EXPECT_EQ(j["cells"][0]["scene_ipd"]["scenes"], 12);
  EXPECT_EQ(j["cells"][0]["scene_ipd"]["worst"].size(), 5u);

  const auto cmp = test::run_ipd("compare " + d.path() + " --model det --ref real --a principled --b hapke  --json");
  ASSERT_EQ(cmp.exit_code, 0) << cmp.err;
  const auto c = nlohmann::json::parse(cmp.out);
  for (const char* key : {"model", "ref", "a", "b", "ipd_a", "ipd_b", "delta", "ci_low", "ci_high", "p_value", "scenes",
                          "pairs_a", "pairs_b", "delta_common"})
    EXPECT_TRUE(c.contains(key)) << key;
  EXPECT_NEAR(c["delta"].get<double>(), c["ipd_a"].get<double>() - c["ipd_b"].get<double>(), 1e-12);
  EXPECT_EQ(c["scenes"], 12);

  const auto bad = test::run_ipd("compare " + d.path() + " --ref real --a real --b hapke");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_EQ(bad.err, "error: compare needs three different domains, got --ref real --a real --b hapke\n");
  const auto latex = test::run_ipd("table " + d.path() + " --format latex --ci --booktabs --latex-wide");
  EXPECT_NE(latex.out.find("$|$real $-$ principled$|$"), std::string::npos) << latex.out;
  EXPECT_NE(latex.out.find("\\toprule"), std::string::npos);
  EXPECT_NE(latex.out.find("\\bottomrule"), std::string::npos);
  EXPECT_EQ(latex.out.find("\\hline"), std::string::npos);
  EXPECT_EQ(latex.out.find("\\|"), std::string::npos);  // no double bars
  EXPECT_NE(latex.out.find("} ["), std::string::npos);  // \textbf{x} [lo, hi]
}

// A one-scene study: the CLI says there is no interval and no test instead of printing [x, x] and
// "no significant difference" (an interval that excludes 0 beside p = 1).
TEST(StatsCli, OneSceneSaysNoIntervalAndNoTest) {
  test::TempDir d;
  test::write_small_demo_study(d, 1);
  const auto table = test::run_ipd("table " + d.path());
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_EQ(table.out.find('['), std::string::npos) << table.out;
  EXPECT_TRUE(std::regex_search(table.out, std::regex(R"(0\.\d{4} \(\d+ pairs; 1 scene: no interval\))"))) << table.out;
  const auto compare = test::run_ipd("compare " + d.path());
  ASSERT_EQ(compare.exit_code, 0) << compare.err;
  EXPECT_NE(compare.out.find("cannot tell whether principled or hapke is closer to real for det-real: \u0394IPD = "),
            std::string::npos)
      << compare.out;
  EXPECT_NE(compare.out.find(", 1 scene: no interval, no test\n"), std::string::npos) << compare.out;
  EXPECT_EQ(compare.out.find("significant"), std::string::npos) << compare.out;
  EXPECT_EQ(compare.out.find("= -"), std::string::npos) << compare.out;  // one minus sign: U+2212
  EXPECT_NE(compare.out.find("(intervals and tests need at least 2 scenes)"), std::string::npos) << compare.out;
}

// A 99% interval goes with a test at 0.01: six scenes' exact p (at least 2/64) can't reach it, and the sentence
// says so; at 95% the same p is below 0.05.
TEST(StatsCli, TheVerdictsLevelIsTheIntervals) {
  test::TempDir d;
  ASSERT_EQ(test::run_ipd("demo " + d.path()).exit_code, 0);
  const auto at95 = test::run_ipd("compare " + d.path() + " --model det-real");
  ASSERT_EQ(at95.exit_code, 0) << at95.err;
  EXPECT_EQ(at95.out.rfind("principled is closer to real than hapke for det-real: ", 0), 0u) << at95.out;
  const auto at99 = test::run_ipd("compare " + d.path() + " --model det-real --ci 0.99");
  ASSERT_EQ(at99.exit_code, 0) << at99.err;
  EXPECT_NE(at99.out.find("p = 0.031 (exact), 6 scenes; the interval excludes 0, but with 6 scenes the exact test's p "
                          "can't go below 0.031: more scenes are needed\n"),
            std::string::npos)
      << at99.out;
}

// A cell without rocks had four "nan–nan px²" bins of 0 pairs; it has none, and says so. By confidence, pairs
// none of whose rocks was found have only the "no detection" bin (no quantiles of nothing).
TEST(StudyStatistics, ABreakdownWithoutRockPairsHasNoBins) {
  test::TempDir d;
  test::write_text(d / "real/labels/s1.txt", "");
  test::write_text(d / "synth/labels/s1.txt", "");
  test::write_text(d / "real/predictions/det/s1.txt", "0 0.2 0.2 0.1 0.1 0.9\n");
  test::write_text(d / "synth/predictions/det/s1.txt", "0 0.2 0.2 0.1 0.1 0.9\n");
  StudyLabels labels = load_labels(open_study(d.path()));
  CrossTable t = compute_cross_table(labels, {});
  for (auto by : {BreakdownBy::kSize, BreakdownBy::kRegion, BreakdownBy::kConfidence}) {
    BreakdownOptions o;
    o.by = by;
    EXPECT_TRUE(breakdown_cell(labels, t.cells.at(0), o).bins.empty()) << to_string(by);
  }
  const auto r = test::run_ipd("breakdown --bootstrap 0 " + d.path());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.substr(0, r.out.find("\n\n")),
            "det (), |real - synth|, by size:\n  No rock pairs in this cell (no rocks, or none paired): nothing to "
            "bin.");
  // Two rocks paired, neither detected on the reference side: only "no detection".
  test::write_text(d / "real/labels/s1.txt", "0 0.2 0.2 0.1 0.1\n0 0.6 0.6 0.1 0.1\n");
  test::write_text(d / "synth/labels/s1.txt", "0 0.2 0.2 0.1 0.1\n0 0.6 0.6 0.1 0.1\n");
  test::write_text(d / "real/predictions/det/s1.txt", "0 0.9 0.9 0.05 0.05 0.9\n");
  labels = load_labels(open_study(d.path()));
  t = compute_cross_table(labels, {});
  BreakdownOptions o;
  o.by = BreakdownBy::kConfidence;
  const CellBreakdown b = breakdown_cell(labels, t.cells.at(0), o);
  ASSERT_EQ(b.bins.size(), 1u);
  EXPECT_EQ(b.bins[0].label, "no detection");
  EXPECT_EQ(b.bins[0].pairs, 2);
}

}  // namespace
}  // namespace ipd

namespace ipd {
namespace {

// A 40 x 20 JPEG whose EXIF says "turn 90 degrees clockwise to view" (orientation 6, as a phone held upright
// writes it): upright it is 20 x 40, as it is shown, measured and labelled (YOLOv5 reads it upright too).
TEST(StudyStatistics, APicturesSizeIsItsUprightSize) {
  test::TempDir d;
  std::vector<unsigned char> jpeg;
  ASSERT_TRUE(cv::imencode(".jpg", cv::Mat(20, 40, CV_8UC3, cv::Scalar(90, 90, 90)), jpeg));
  // APP1 "Exif": a little-endian TIFF header and one IFD entry, Orientation (0x0112), SHORT, 1 value: 6.
  const unsigned char exif[] = {0xff, 0xe1, 0x00, 0x22, 'E', 'x', 'i', 'f', 0, 0, 'I', 'I', 0x2a, 0, 8, 0, 0, 0,
                                1,    0,    0x12, 0x01, 3,   0,   1,   0,   0, 0, 6,   0,   0,    0, 0, 0, 0, 0};
  jpeg.insert(jpeg.begin() + 2, std::begin(exif), std::end(exif));
  test::write_text(d / "real/images/s1.jpg", std::string(jpeg.begin(), jpeg.end()));
  test::write_text(d / "real/labels/s1.txt", "0 0.5 0.5 0.1 0.1\n");
  test::write_text(d / "synth/labels/s1.txt", "0 0.5 0.5 0.1 0.1\n");
  const Study study = open_study(d.path());
  EXPECT_EQ(domain_image_size(study, "real"), std::make_pair(20, 40));
}

}  // namespace
}  // namespace ipd
