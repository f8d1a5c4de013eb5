// ipd-studio's statistics charts and cross table, laid out and drawn on a recording canvas whose text is
// 6 pt per character and 10 pt per line, so every position below is computed by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "ui/figures/score_curve.h"
#include "ui/figures/stats_charts.h"
#include "ui/gui/stats_panels.h"
#include "ui/gui/table_layout.h"

namespace ipd::ui {
namespace {

struct Recorder : Canvas {
  struct Op {
    std::string kind;
    PtRect r;
    std::vector<Pt> points;
    Colour colour;
    double width = 0;
    std::string text;
  };
  std::vector<Op> ops;
  void rect(const PtRect& r, Colour c, double w) override { ops.push_back({"rect", r, {}, c, w, ""}); }
  void fill_rect(const PtRect& r, Colour c) override { ops.push_back({"fill", r, {}, c, 0, ""}); }
  void line(Pt a, Pt b, Colour c, double w) override { ops.push_back({"line", {}, {a, b}, c, w, ""}); }
  void polyline(const std::vector<Pt>& p, Colour c, double w, bool) override {
    ops.push_back({"polyline", {}, p, c, w, ""});
  }
  void circle(Pt, double, Colour, double) override {}
  void fill_circle(Pt, double, Colour) override {}
  void text(Pt at, Anchor a, const TextStyle& st, const std::string& s) override {
    const Pt m = measure(st, s);
    ops.push_back({"text", text_box(at, a, m.x, m.y), {}, st.colour, 0, s});
  }
  void image(const FigurePicture&, const PtRect&) override {}
  void push_clip(const PtRect&) override {}
  void pop_clip() override {}
  Pt measure(const TextStyle&, const std::string& s) override { return {6.0 * s.size(), 10}; }
};

const ChartColours kColours{rgb(1, 0, 0), rgb(2, 0, 0), rgb(3, 0, 0), rgb(4, 0, 0),
                            rgb(5, 0, 0), rgb(6, 0, 0), rgb(7, 0, 0)};
bool same(Colour a, Colour b) { return a.r == b.r && a.g == b.g && a.b == b.b && a.a == b.a; }

void expect_rect(const PtRect& r, double x0, double y0, double x1, double y1) {
  EXPECT_NEAR(r.x0, x0, 1e-9);
  EXPECT_NEAR(r.y0, y0, 1e-9);
  EXPECT_NEAR(r.x1, x1, 1e-9);
  EXPECT_NEAR(r.y1, y1, 1e-9);
}

TEST(StatsCharts, CountTicksAreRoundIntegers) {
  EXPECT_EQ(count_ticks(4, 3), (std::vector<double>{0, 2, 4}));
  EXPECT_EQ(count_ticks(7, 3), (std::vector<double>{0, 5, 10}));
  EXPECT_EQ(count_ticks(1, 5), (std::vector<double>{0, 1}));
  EXPECT_EQ(count_ticks(23, 4), (std::vector<double>{0, 10, 20, 30}));
}

// One scene: its bin is the only bar, full height. The bar stays drawn in the bar colour and the
// highlight is a bracket around it, 1.5 pt clear of it, never a fill over it.
TEST(StatsCharts, TheCurrentScenesLoneBarIsOutlinedNotCovered) {
  Recorder c;
  const TextStyle st;
  //   edge labels "0.020", "0.025": 30 pt; top pad max(5, 1.5 + 2 + 0.5) = 5; below: tick 3 + 1 + line 10;
  //   plot height 100 - 5 - 14 = 81 (room for 6 intervals of 1.2 lines) -> count ticks 0, 1 (6 pt) and a
  //   gutter of 6 + 3 + 3 = 12 < 30 / 2.
  const HistogramChart ch = layout_histogram(c, st, {0.02, 0.005, {1}, 0.0200}, {0, 0, 300, 100});
  expect_rect(ch.plot, 15, 5, 285, 86);
  ASSERT_EQ(ch.bars.size(), 1u);
  //   one slot of 270 pt; the bar no wider than 3 lines (30 pt), centred at 150.
  expect_rect(ch.bars[0].bar, 135, 5, 165, 86);
  expect_rect(ch.bars[0].slot, 15, 5, 285, 86);
  EXPECT_TRUE(ch.bars[0].current);
  ASSERT_EQ(ch.count_axis.size(), 2u);
  EXPECT_EQ(ch.count_axis[1].text, "1");
  EXPECT_DOUBLE_EQ(ch.count_axis[1].at, 5);
  ASSERT_EQ(ch.edge_axis.size(), 2u);
  EXPECT_EQ(ch.edge_axis[0].text, "0.020");
  EXPECT_EQ(ch.edge_axis[1].text, "0.025");
  EXPECT_DOUBLE_EQ(ch.edge_axis[1].at, 285);

  draw_histogram(c, st, ch, kColours, -1);
  int bars = 0, outlines = 0;
  for (const auto& op : c.ops) {
    if (op.kind == "fill") {
      EXPECT_TRUE(same(op.colour, kColours.bar));  // nothing is filled in the highlight colour
      expect_rect(op.r, 135, 5, 165, 86);
      ++bars;
    }
    if (same(op.colour, kColours.current)) {
      ASSERT_EQ(op.kind, "polyline");
      ++outlines;
      // Stroke centre 1.5 + 1 pt outside the bar: (132.5, 86) up to y 2.5, across to 167.5, down to 86.
      ASSERT_EQ(op.points.size(), 4u);
      EXPECT_DOUBLE_EQ(op.points[0].x, 132.5);
      EXPECT_DOUBLE_EQ(op.points[1].y, 2.5);
      EXPECT_DOUBLE_EQ(op.points[2].x, 167.5);
      EXPECT_DOUBLE_EQ(op.width, 2);
      // The stroke's inner edge clears the bar: left 133.5 < 135, top 3.5 < 5, right 166.5 > 165.
      EXPECT_LT(op.points[0].x + op.width / 2, 135);
      EXPECT_LT(op.points[1].y + op.width / 2, 5);
      EXPECT_GT(op.points[2].x - op.width / 2, 165);
    }
  }
  EXPECT_EQ(bars, 1);
  EXPECT_EQ(outlines, 1);
}

// Several bins: empty bins draw nothing, the hovered bar is lighter, edge labels thin out when they would touch.
TEST(StatsCharts, HistogramBarsStandOnTheCountAxis) {
  Recorder c;
  //   edge labels "0.00".."0.06" (24 pt: half 12) and a gutter of 6 + 3 + 3 = 12: plot x 12 .. 108.
  const HistogramChart ch = layout_histogram(c, {}, {0.0, 0.01, {4, 0, 2, 1, 0, 3}, 0.035}, {0, 0, 120, 100});
  expect_rect(ch.plot, 12, 5, 108, 86);
  ASSERT_EQ(ch.bars.size(), 6u);
  //   count ticks for 4 with at most 6 intervals: 0..4 by 1; the 2-count bar is half the plot's height.
  EXPECT_EQ(ch.count_axis.back().text, "4");
  EXPECT_DOUBLE_EQ(ch.bars[2].bar.y0, 86 - 81 * 2 / 4.0);
  EXPECT_TRUE(ch.bars[3].current);
  EXPECT_FALSE(ch.bars[2].current);
  //   slots of 16 pt; labels of 24 pt need 31.2 pt apart: every second edge.
  ASSERT_EQ(ch.edge_axis.size(), 4u);
  EXPECT_EQ(ch.edge_axis[1].text, "0.02");
  EXPECT_DOUBLE_EQ(ch.edge_axis[1].at, 12 + 2 * 16);
  draw_histogram(c, {}, ch, kColours, 5);
  int fills = 0, hot = 0;
  for (const auto& op : c.ops)
    if (op.kind == "fill") ++fills, hot += same(op.colour, kColours.bar_hot);
  EXPECT_EQ(fills, 4);
  EXPECT_EQ(hot, 1);
}

// 3000 scenes, two of them in the first bin: that bin's bar is 2 pt tall, not 81 * 2 / 4000 = 0.04 pt
// (it drew nothing and looked empty).
TEST(StatsCharts, ANonEmptyBinAlwaysShowsATwoPointBar) {
  Recorder c;
  const HistogramChart ch = layout_histogram(c, {}, {0.0, 0.1, {2, 2998, 0}, 0.15}, {0, 0, 300, 100});
  ASSERT_EQ(ch.bars.size(), 3u);
  EXPECT_DOUBLE_EQ(ch.bars[0].bar.y1, ch.plot.y1);
  EXPECT_DOUBLE_EQ(ch.bars[0].bar.y0, ch.plot.y1 - 2);
  EXPECT_DOUBLE_EQ(ch.bars[2].bar.y0, ch.plot.y1);  // empty stays empty
  draw_histogram(c, {}, ch, kColours, -1);
  int fills = 0;
  for (const auto& op : c.ops) fills += op.kind == "fill";
  EXPECT_EQ(fills, 2);
}

// One scene with IPD 0.0200: bins 0.015 | 0.020 | 0.025 | 0.030 and the bar centred at 0.020, on its tick
// (centred in its bin it read 0.0225).
TEST(StatsCharts, ALoneValuesBarSitsAtTheValue) {
  const HistogramBins h = histogram_bins({0.02}, 4);
  EXPECT_NEAR(h.width, 0.005, 1e-15);
  EXPECT_NEAR(h.start, 0.015, 1e-12);
  EXPECT_EQ(h.counts, (std::vector<int>{0, 1, 0}));
  EXPECT_DOUBLE_EQ(h.lone_value, 0.02);
  EXPECT_TRUE(std::isnan(histogram_bins({0.01, 0.02}, 4).lone_value));
  // Every IPD 0: bins of 0.01 from 0 (never below), the bar standing on the axis from x0.
  const HistogramBins zero = histogram_bins({0.0, 0.0}, 4);
  EXPECT_DOUBLE_EQ(zero.width, 0.01);
  EXPECT_DOUBLE_EQ(zero.start, 0);
  EXPECT_EQ(zero.counts, (std::vector<int>{2, 0, 0}));
  {
    Recorder z;
    //   labels "0.00".."0.03" (24 pt, half 12), gutter 12: plot x 12 .. 288; the bar (30 pt) from the axis.
    const HistogramChart zc =
        layout_histogram(z, {}, {zero.start, zero.width, zero.counts, 0.0, zero.lone_value}, {0, 0, 300, 100});
    expect_rect(zc.bars[0].bar, 12, 5, 42, 86);
  }
  Recorder c;
  //   edge labels "0.015".."0.030" (30 pt, half 15) > gutter 12: plot x 15 .. 285, slots of 90 pt; the value
  //   0.020 at 15 + 90 = 105, the bar 30 pt wide (3 lines) around it.
  const HistogramChart ch = layout_histogram(c, {}, {h.start, h.width, h.counts, 0.02, h.lone_value}, {0, 0, 300, 100});
  ASSERT_EQ(ch.bars.size(), 3u);
  expect_rect(ch.bars[1].bar, 90, 5, 120, 86);
  EXPECT_TRUE(ch.bars[1].current);
  ASSERT_EQ(ch.edge_axis.size(), 4u);
  EXPECT_EQ(ch.edge_axis[1].text, "0.020");
  EXPECT_DOUBLE_EQ(ch.edge_axis[1].at, 105);
}

// The size breakdown's bars on an IPD axis: ticks round, the last one past every bar and whisker.
TEST(StatsCharts, ValueBarsHaveAnIpdAxis) {
  Recorder c;
  const std::vector<ValueBarRow> rows = {{"small", 0.04, 0.022, 0.061}, {"large", 0.016, NAN, NAN}};
  //   rows 13 pt (1.3 lines), axis below: tick 3 + 1 + line 10.
  EXPECT_DOUBLE_EQ(value_bars_height(c, {}, rows.size()), 26 + 14);
  //   labels 30 pt + 6 -> bars from 36; ticks 0.02 apart up to 0.08 (past 0.061), the last label's half
  //   (12) inside the area: axis 36 .. 188, x(v) = 36 + v / 0.08 * 152.
  const ValueBarsChart ch = layout_value_bars(c, {}, rows, {0, 0, 200, 40});
  expect_rect(ch.plot, 36, 0, 188, 26);
  ASSERT_EQ(ch.value_axis.size(), 5u);
  EXPECT_EQ(ch.value_axis[4].text, "0.08");
  EXPECT_DOUBLE_EQ(ch.value_axis[2].at, 112);
  EXPECT_EQ(ch.value_axis[2].text, "0.04");
  expect_rect(ch.rows[0].bar, 36, 2, 112, 11);
  EXPECT_NEAR(ch.rows[0].whisker_x0, 36 + 0.275 * 152, 1e-9);
  EXPECT_NEAR(ch.rows[0].whisker_x1, 36 + 0.7625 * 152, 1e-9);
  expect_rect(ch.rows[1].bar, 36, 15, 36 + 0.2 * 152, 24);
  EXPECT_EQ(ch.rows[1].whisker_x0, ch.rows[1].whisker_x1);  // no interval, no whisker
  draw_value_bars(c, {}, ch, rows, kColours, -1);
  int tick_labels = 0;
  for (const auto& op : c.ops)
    if (op.kind == "text" && same(op.colour, kColours.tick_text)) {
      ++tick_labels;
      EXPECT_GE(op.r.y0, 26 + 3);  // below the bars and the tick marks
    }
  EXPECT_EQ(tick_labels, 5);
}

// The cross table is as tall as its rows: 5 rows of 15 + 2 x 2 pt and the bottom border; the scrollbar
// only when the columns (text + 2 x 4 pt padding + a border each, and the left border) are wider than the panel.
TEST(StatsCharts, CrossTableIsAsTallAsItsRows) {
  const TableMetrics m{15, 4, 2, 1, 14};
  const TableSize fits = cross_table_size({80, 70, 50}, 5, 300, m);
  EXPECT_FLOAT_EQ(fits.width, 1 + 89 + 79 + 59);
  EXPECT_FALSE(fits.scroll_x);
  EXPECT_FLOAT_EQ(fits.height, 5 * 19 + 1);
  const TableSize narrow = cross_table_size({80, 70, 50}, 5, 200, m);
  EXPECT_TRUE(narrow.scroll_x);
  EXPECT_FLOAT_EQ(narrow.height, 5 * 19 + 1 + 14);
}

// The studio's cross-table header splits |a - b| after the minus, so the second row does not start with a
// dash (it read "real" over "- principled", like a list).
TEST(StatsCharts, CrossTableHeaderSplitsAfterTheMinus) {
  EXPECT_EQ(cross_table_header("real", "principled"),
            std::make_pair(std::string("|real -"), std::string("principled|")));
}

// "higher is better" sat top right, where a rising best-so-far curve ends, and the curve ran through it. The
// label goes to the corner the curve leaves free, for both directions: no point of the curve (sampled along
// every segment) falls in the label's box.
// A recorded search of 5,000 steps: every label, the last step's "5,000" centred on the plot's right end
// included, stays inside the area the curve was given (6 pt a character here: "5,000" is 30 wide, so the plot
// ends 16 short of the area). The steps are counted from 1, as the replay's "step 1 of 5,000", with the
// replay's thousands separators.
TEST(StatsCharts, ScoreCurveLastStepLabelStaysInsideTheArea) {
  Recorder r;
  const TextStyle st{8, rgb(0, 0, 0), false};
  const std::vector<double> best(5000, 0.5);
  const ScoreCurve curve = layout_score_curve(r, st, {best, 10, FitMeasure::kMeanDistance}, {0, 0, 300, 100});
  draw_score_curve(r, st, curve, kColours);
  EXPECT_DOUBLE_EQ(curve.plot.x1, 284);
  ASSERT_FALSE(curve.step_axis.empty());
  EXPECT_EQ(curve.step_axis.back().text, "5,000");
  EXPECT_EQ(curve.step_axis.front().text, "1");
  EXPECT_DOUBLE_EQ(curve.step_axis.front().at, curve.plot.x0);
  int texts = 0;
  for (const auto& op : r.ops)
    if (op.kind == "text") {
      ++texts;
      EXPECT_GE(op.r.x0, 0) << op.text;
      EXPECT_LE(op.r.x1, 300) << op.text;
    }
  EXPECT_GT(texts, 3);
}

TEST(StatsCharts, ScoreCurveDirectionLabelIsClearOfTheCurve) {
  const std::vector<std::pair<FitMeasure, std::vector<double>>> cases = {
      {FitMeasure::kSoftInliers, {15.9, 16.9, 16.9, 16.9}}, {FitMeasure::kMeanDistance, {3.0, 2.0, 1.5, 1.5}}};
  for (const auto& [measure, best] : cases) {
    SCOPED_TRACE(score_direction(measure));
    Recorder r;
    const TextStyle st{8, rgb(0, 0, 0), false};
    const ScoreCurve curve = layout_score_curve(r, st, {best, 3, measure}, {0, 0, 300, 100});
    draw_score_curve(r, st, curve, kColours);
    const Recorder::Op* label = nullptr;
    const Recorder::Op* line = nullptr;
    for (const auto& op : r.ops) {
      if (op.kind == "text" && op.text == score_direction(measure)) label = &op;
      if (op.kind == "polyline") line = &op;
    }
    ASSERT_TRUE(label && line);
    EXPECT_LE(label->r.x1, curve.plot.x1);
    EXPECT_GE(label->r.y0, curve.plot.y0);
    EXPECT_LE(label->r.y1, curve.plot.y1);
    for (size_t k = 1; k < line->points.size(); ++k)
      for (int s = 0; s <= 100; ++s) {
        const Pt a = line->points[k - 1], b = line->points[k];
        const Pt p{a.x + (b.x - a.x) * s / 100, a.y + (b.y - a.y) * s / 100};
        EXPECT_FALSE(p.x >= label->r.x0 && p.x <= label->r.x1 && p.y >= label->r.y0 && p.y <= label->r.y1)
            << "segment " << k << " at (" << p.x << ", " << p.y << ")";
      }
  }
}

}  // namespace
}  // namespace ipd::ui
