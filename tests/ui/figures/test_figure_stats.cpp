// The study-wide figures (table --ci, compare, distribution, breakdown) on a study whose numbers are known
// by hand, read back from the PDF as text.
#include <gtest/gtest.h>

#include <regex>
#include <tuple>

#include "core/demo/demo_study.h"
#include "tests/support/figure_test_study.h"
#include "tests/support/pdf_text.h"
#include "tests/support/test_support.h"
#include "ui/figures/figure_charts.h"
#include "ui/figures/figure_export.h"
#include "ui/figures/figure_stats.h"

namespace ipd {
namespace {

// Three domains with the same three rocks; det (trained on real) finds each rock exactly in real, shifted
// by 0.05 (IoU 0.6) in s1 and by 0.10 (IoU 1/3) in s2, in both scenes. So IPD(real, s1) = 0.4,
// IPD(real, s2) = 2/3 and ΔIPD = IPD(real, s1) - IPD(real, s2) = -0.2667 in every scene (interval a point).
void write_three_domain_study_figure_stats(const test::TempDir& d) {
  test::write_text(d / "study.yaml", "domains: [real, s1, s2]\nmodels: {det: {trained_on: real}}\n");
  const char* gt = "0 0.20 0.30 0.2 0.2\n0 0.70 0.25 0.2 0.2\n0 0.45 0.75 0.2 0.2\n";
  for (const std::string scene : {"a", "b"})
    for (const auto& [dom, dx] : {std::pair<std::string, double>{"real", 0}, {"s1", 0.05}, {"s2", 0.10}}) {
      test::write_text(d / (dom + "/labels/" + scene + ".txt"), gt);
      char pred[256];
      std::snprintf(pred, sizeof pred, "0 %.2f 0.30 0.2 0.2 0.9\n0 %.2f 0.25 0.2 0.2 0.8\n0 %.2f 0.75 0.2 0.2 0.7\n",
                    0.20 + dx, 0.70 + dx, 0.45 + dx);
      test::write_text(d / (dom + "/predictions/det/" + scene + ".txt"), pred);
    }
}

using test::pdf_words;

TEST(FigureStats, CompareShowsTheDeltaAndItsTest) {
  test::TempDir d;
  write_three_domain_study_figure_stats(d);
  const auto r =
      test::run_ipd("figure compare " + d.path() + " --bootstrap 200 --permutations 200 --out " + d / "c.pdf");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string text = pdf_words(d / "c.pdf");
  EXPECT_NE(text.find("IPD(real, s1) \u2212 IPD(real, s2)"), std::string::npos) << text;
  EXPECT_NE(text.find("det (real) \u22120.267, p = "), std::string::npos) << text;
  // 2 scenes: all 2^2 swap patterns fit in 200, so the p-value is exact and the footnote must say so.
  EXPECT_NE(text.find("test, exact (every swap pattern) over the 2 scenes"), std::string::npos) << text;
  const auto few =
      test::run_ipd("figure compare " + d.path() + " --bootstrap 200 --permutations 3 --out " + d / "c3.pdf");
  ASSERT_EQ(few.exit_code, 0) << few.err;
  EXPECT_NE(pdf_words(d / "c3.pdf").find("test (3 permutations) over the 2 scenes"), std::string::npos)
      << pdf_words(d / "c3.pdf");
  // No permutations: no p-value, and the footnote says no test was run (not "0 permutations" of a test).
  const auto none =
      test::run_ipd("figure compare " + d.path() + " --bootstrap 200 --permutations 0 --out " + d / "c0.pdf");
  ASSERT_EQ(none.exit_code, 0) << none.err;
  EXPECT_NE(pdf_words(d / "c0.pdf").find("No permutation test was run"), std::string::npos) << pdf_words(d / "c0.pdf");
}

TEST(FigureStats, TableWithIntervalsDistributionAndBreakdown) {
  test::TempDir d;
  write_three_domain_study_figure_stats(d);
  auto r = test::run_ipd("figure table " + d.path() + " --ci --bootstrap 100 --out " + d / "t.pdf");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::string text = pdf_words(d / "t.pdf");
  // Both scenes alike: the interval is the point.
  EXPECT_NE(text.find("0.4000 [0.400, 0.400]"), std::string::npos) << text;
  EXPECT_NE(text.find("0.6667 [0.667, 0.667]"), std::string::npos) << text;
  r = test::run_ipd("figure distribution " + d.path() + " --out " + d / "d.pdf");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  text = pdf_words(d / "d.pdf");
  EXPECT_NE(text.find("|real \u2212 s2|"), std::string::npos) << text;
  EXPECT_NE(text.find("scene IPD"), std::string::npos) << text;
  r = test::run_ipd("figure breakdown " + d.path() + " --by size --bins 1 --bootstrap 50 --b s2 --out " + d / "b.pdf");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  text = pdf_words(d / "b.pdf");
  EXPECT_NE(text.find("6 pairs"), std::string::npos) << text;  // 3 rocks x 2 scenes in the one bin
  r = test::run_ipd("figure breakdown " + d.path() + " --by colour --out " + d / "x.pdf");
  EXPECT_EQ(r.exit_code, 2);
}

// --ci is a flag with an optional level: it never takes the STUDY after it for a level, whatever follows
// (`figure table --ci STUDY --out F` failed with "--ci: Value STUDY not in range"), and the level can be
// given as --ci=L or --ci L in either order.
TEST(FigureStats, CiParsesTheSameWayInEveryOrder) {
  test::TempDir d;
  write_three_domain_study_figure_stats(d);
  const std::string s = d.path(), out = " --bootstrap 100 --out " + d / "t.pdf";
  for (const std::string& args :
       {"--ci " + s + out, s + " --ci" + out, "--ci 0.9 " + s + out, "--ci=0.9 " + s + out, s + out + " --ci"}) {
    const auto r = test::run_ipd("figure table " + args);
    ASSERT_EQ(r.exit_code, 0) << args << ": " << r.err;
    EXPECT_NE(pdf_words(d / "t.pdf").find("0.4000 [0.400, 0.400]"), std::string::npos) << args;
  }
  for (const std::string& args : {"--ci 0.9 " + s, s + " --ci 0.9", "--ci=0.9 " + s, s + " --ci=0.9 --bootstrap 100"}) {
    const auto r = test::run_ipd("table --format latex " + args);
    ASSERT_EQ(r.exit_code, 0) << args << ": " << r.err;
    EXPECT_NE(r.out.find("90% scene-bootstrap percentile interval"), std::string::npos) << args << ": " << r.out;
  }
  const auto latex = test::run_ipd("table --format latex --ci " + s);
  EXPECT_NE(latex.out.find("95% scene-bootstrap percentile interval"), std::string::npos) << latex.out;
  const auto bad = test::run_ipd("table " + s + " --ci=2");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--ci: Value 2 not in range 0.500000 to 0.999900"), std::string::npos) << bad.err;
}

void expect_ticks(const std::vector<double>& got, const std::vector<double>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < got.size(); ++i) EXPECT_NEAR(got[i], want[i], 1e-12) << i;
}

// A one-scene study's figures say there is no interval or test instead of drawing [x, x] and p = 1.
TEST(FigureStats, OneSceneFiguresSayNoIntervalNoTest) {
  test::TempDir d;
  test::write_small_demo_study(d, 1);
  auto r = test::run_ipd("figure table " + d.path() + " --ci --out " + d / "t.pdf");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::string text = pdf_words(d / "t.pdf");
  EXPECT_NE(text.find("1 scene: no interval"), std::string::npos) << text;
  EXPECT_EQ(text.find("["), std::string::npos) << text;
  EXPECT_EQ(text.find("Brackets"), std::string::npos) << text;
  r = test::run_ipd("figure compare " + d.path() + " --out " + d / "c.pdf");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  text = pdf_words(d / "c.pdf");
  EXPECT_NE(text.find("1 scene: no test"), std::string::npos) << text;
  EXPECT_NE(text.find("1 scene present in all three domains: no interval, no test (they need at least 2)."),
            std::string::npos)
      << text;
  EXPECT_EQ(text.find("p = "), std::string::npos) << text;
  EXPECT_EQ(text.find("scene-bootstrap"), std::string::npos) << text;  // the title promises no interval
}

std::vector<std::string> chart_texts(const ui::DisplayList& fig) {
  std::vector<std::string> out;
  for (const auto& t : fig.texts()) out.push_back(t.text);
  return out;
}
bool has_text(const std::vector<std::string>& texts, const std::string& s) {
  return std::find(texts.begin(), texts.end(), s) != texts.end();
}

// The breakdown's IPD axis starts at 0 (IPD >= 0): rows 0.14 [0.065, 0.243] and 0.015 [0.008, 0.02] pad the
// range by 5% (0.01175) to -0.0037, which put a tick at -0.05 before. Now no tick lies below 0, and the
// axis itself starts at 0: the "0.00" label is centred on the axis' left end, the row labels' edge + 0.6
// font sizes; a padded axis (a difference) puts 0 further right.
TEST(FigureStats, AnIpdAxisStartsAtZero) {
  ui::DotWhiskerChart ch;
  ch.title = "t", ch.axis_label = "IPD";
  ch.rows = {{"a", 0.14, 0.065, 0.243, ""}, {"b", 0.015, 0.008, 0.02, ""}};
  ch.non_negative = true;
  const ui::FontMetrics metrics(ui::default_font_file());
  ui::FigureOptions o;
  ui::DisplayList fig(metrics);
  ui::draw_dot_whisker_chart(fig, ch, o);
  const auto zero_at = [](const ui::DisplayList& f) {
    for (const auto& t : f.texts())
      if (t.text == "0.00") return (t.box.x0 + t.box.x1) / 2;
    return -1.0;
  };
  double label_right = 0;
  for (const auto& t : fig.texts())
    if (t.text == "a" || t.text == "b") label_right = std::max(label_right, t.box.x1);
  for (const auto& t : chart_texts(fig)) EXPECT_NE(t.rfind("\u2212", 0), 0u) << t;
  EXPECT_NEAR(zero_at(fig), label_right + 0.6 * 8, 0.01);
  ch.non_negative = false;
  ui::DisplayList padded(metrics);
  ui::draw_dot_whisker_chart(padded, ch, o);
  EXPECT_GT(zero_at(padded), zero_at(fig) + 0.5);
}

// An IPD axis starts at 0 even when every value lies far from it (a breakdown's bins at 0.22 to 0.28): the
// "0.00" tick sits at the axis' left end (row labels' edge + 0.6 font sizes) and the estimates lie in the
// right part of the axis, as lengths from 0.
TEST(FigureStats, AnIpdAxisStartsAtZeroWhenTheDataLieFarFromIt) {
  ui::DotWhiskerChart ch;
  ch.title = "t", ch.axis_label = "IPD";
  ch.rows = {{"a", 0.25, 0.22, 0.28, ""}, {"b", 0.24, 0.23, 0.26, ""}};
  ch.non_negative = true;
  const ui::FontMetrics metrics(ui::default_font_file());
  ui::FigureOptions o;
  ui::DisplayList fig(metrics);
  ui::draw_dot_whisker_chart(fig, ch, o);
  double label_right = 0, zero_x = -1, tick_020_x = -1;
  for (const auto& t : fig.texts()) {
    if (t.text == "a" || t.text == "b") label_right = std::max(label_right, t.box.x1);
    if (t.text == "0.00" || t.text == "0.0") zero_x = (t.box.x0 + t.box.x1) / 2;
    if (t.text == "0.20" || t.text == "0.2") tick_020_x = (t.box.x0 + t.box.x1) / 2;
  }
  EXPECT_NEAR(zero_x, label_right + 0.6 * 8, 0.01) << ::testing::PrintToString(chart_texts(fig));
  ASSERT_GT(tick_020_x, 0) << ::testing::PrintToString(chart_texts(fig));
  // The axis runs from 0 to 0.28 + 5% of 0.28 = 0.294 (or its last tick): 0.20 lies past two thirds of it.
  const double axis_w = tick_020_x - zero_x;
  EXPECT_GT(axis_w, 0.5 * (o.width_pt() - zero_x));
}

// Padding never adds a whole tick step: ΔIPD from -0.0955 to 0 padded by 5% reaches -0.1003, and the axis
// ran to -0.2 (ticks -0.2, -0.1, 0.0) in a single column; now it ends just past the tick -0.1.
TEST(FigureStats, AxisPaddingDoesNotAddATickStep) {
  ui::DotWhiskerChart ch;
  ch.title = "t", ch.axis_label = "\u0394IPD";
  ch.zero_line = true;
  ch.rows = {{"det-real (real)", -0.0799, -0.0955, -0.064, "\u22120.080, p = 0.031"},
             {"det-principled (principled)", -0.0591, -0.075, -0.047, "\u22120.059, p = 0.031"},
             {"det-hapke (hapke)", -0.0537, -0.081, -0.030, "\u22120.054, p = 0.031"}};
  const ui::FontMetrics metrics(ui::default_font_file());
  ui::FigureOptions o;
  ui::DisplayList fig(metrics);
  ui::draw_dot_whisker_chart(fig, ch, o);
  const auto texts = chart_texts(fig);
  EXPECT_TRUE(has_text(texts, "\u22120.10")) << ::testing::PrintToString(texts);
  for (const auto& t : texts) EXPECT_EQ(t.find("0.2"), std::string::npos) << t;
}

// Two worst scenes at the same value are one place on the page: one name for both, not two stacked names
// a reader cannot tell apart.
TEST(FigureStats, WorstScenesAtOneSpotShareOneName) {
  ui::DistributionChart ch;
  ch.title = "t", ch.axis_label = "scene IPD";
  ui::BoxRow r;
  r.label = "|real - synth|";
  r.values = {0.02, 0.05, 0.1, 0.1};
  r.min = 0.02, r.q1 = 0.04, r.median = 0.075, r.q3 = 0.1, r.max = 0.1;
  r.worst = {{"scene_01", 0.1}, {"scene_02", 0.1}, {"scene_03", 0.02}};
  ch.rows = {r};
  const ui::FontMetrics metrics(ui::default_font_file());
  ui::FigureOptions o;
  o.width_in = ui::kDoubleColumnIn;
  ui::DisplayList fig(metrics);
  ui::draw_distribution_chart(fig, ch, o);
  const auto texts = chart_texts(fig);
  EXPECT_TRUE(has_text(texts, "scene_01, scene_02"));
  EXPECT_TRUE(has_text(texts, "scene_03"));
  EXPECT_FALSE(has_text(texts, "scene_01"));
}

// The distribution figure shows what the table shows: a domain pair without the model's training domain is "–"
// there (as in the paper), so it gets no box either.
TEST(FigureStats, DistributionLeavesOutPairsWithoutTheTrainingDomain) {
  CrossTable t;
  t.models = {{"det-real", "real"}};
  for (const auto& [a, b, involved] : {std::tuple<const char*, const char*, bool>{"real", "principled", true},
                                       {"real", "hapke", true},
                                       {"principled", "hapke", false}}) {
    TableCell c;
    c.model = "det-real", c.trained_on = "real", c.a = a, c.b = b;
    c.involves_training_domain = involved;
    SceneIpd s;
    s.stem = "scene_01", s.pairs = 2, s.sum_abs_diff = 0.1;
    c.per_scene = {s};
    t.cells.push_back(c);
  }
  const ui::DistributionChart ch = ui::distribution_chart(t, "det-real", 1);
  ASSERT_EQ(ch.rows.size(), 2u);
  EXPECT_EQ(ch.rows[0].label, "|real \u2212 principled|");
  EXPECT_EQ(ch.rows[1].label, "|real \u2212 hapke|");
  EXPECT_EQ(ch.rows[1].values, std::vector<double>{0.05});
}

// A table or distribution exported at --conf 0.5 (or the studio's slider) did not say so, while the pairs
// figure's caption does ("conf ≥ 0.3"): every study figure whose numbers depend on it says it under the figure.
TEST(FigureStats, AThresholdOnThePredictionsIsSaidUnderTheFigure) {
  test::TempDir d;
  test::write_two_rock_study(d);
  const std::string said = "Predictions with conf \u2265 0.5.";
  for (const std::string kind : {"table", "distribution", "breakdown"}) {
    SCOPED_TRACE(kind);
    ASSERT_EQ(test::run_ipd("figure " + kind + " " + d.path() + " --conf 0.5 --out " + d / "f.pdf").exit_code, 0);
    EXPECT_NE(test::pdf_words(d / "f.pdf").find(said), std::string::npos) << test::pdf_words(d / "f.pdf");
    ASSERT_EQ(test::run_ipd("figure " + kind + " " + d.path() + " --out " + d / "g.pdf").exit_code, 0);
    EXPECT_EQ(test::pdf_words(d / "g.pdf").find("Predictions with conf"), std::string::npos);
  }
  Session s = Session::open(d.path());
  s.set_conf_threshold(0.5);
  ui::ExportRequest req;
  req.kind = "table";
  req.path = d / "studio.pdf";
  ASSERT_EQ(ui::export_figure(s, req), "exported " + req.path);
  EXPECT_NE(test::pdf_words(req.path).find(said), std::string::npos) << test::pdf_words(req.path);
}

TEST(FigureStats, NiceTicks) {
  // 0.13 / 6 = 0.0217 -> step 0.025 (the next of 1, 2, 2.5, 5 x 10^k).
  expect_ticks(ui::nice_ticks(0, 0.13, 6), {0, 0.025, 0.05, 0.075, 0.1, 0.125});
  expect_ticks(ui::nice_ticks(-0.15, 0, 3), {-0.15, -0.1, -0.05, 0});
  expect_ticks(ui::nice_ticks(3, 17, 2), {0, 10});
}

}  // namespace
}  // namespace ipd
