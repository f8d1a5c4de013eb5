// `ipd figure sweep`: the chart of a ranking along the parameter its variants differ in, its refusals when the
// variants don't share their parameters, and print sizes (no text under 7 pt).
#include <gtest/gtest.h>

#include "ui/canvas/canvas.h"
#include "ui/figures/figure_sweep.h"

namespace ipd {
namespace {

RankedCandidate candidate(const std::string& name, std::vector<std::pair<std::string, double>> params, double ipd,
                          int rank, bool group) {
  RankedCandidate c;
  c.domain = name;
  c.params = std::move(params);
  c.ipd = ipd;
  c.ci_low = ipd - 0.01;
  c.ci_high = ipd + 0.01;
  c.rank = rank;
  c.in_best_group = group;
  return c;
}

Ranking three_settings() {
  Ranking k;
  k.model = "det-real";
  k.ref = "real";
  k.tests = 2;
  k.ranked = {candidate("w050", {{"w", 0.5}, {"b", 0.2}}, 0.03, 1, true),
              candidate("w030", {{"w", 0.3}, {"b", 0.2}}, 0.04, 2, true),
              candidate("w090", {{"w", 0.9}, {"b", 0.2}}, 0.09, 3, false)};
  return k;
}

TEST(SweepFigure, OneVaryingParameterIsALineInItsOrder) {
  const ui::SweepChart c = ui::sweep_chart(three_settings());
  EXPECT_EQ(c.parameters, std::vector<std::string>{"w"});  // b is the same in all
  ASSERT_EQ(c.points.size(), 3u);
  EXPECT_EQ(c.points[0].domain, "w030");
  EXPECT_EQ(c.points[1].domain, "w050");
  EXPECT_TRUE(c.points[1].best);
  EXPECT_FALSE(c.points[2].in_group);
  EXPECT_EQ(c.title, "IPD(real, variant) for det-real along w");
}

TEST(SweepFigure, VariantsWithOtherParametersAreRefusedByName) {
  Ranking k = three_settings();
  k.ranked[2].params = {{"albedo", 0.9}};
  try {
    ui::sweep_chart(k);
    FAIL() << "different parameter sets were plotted";
  } catch (const StudyError& e) {
    EXPECT_EQ(std::string(e.what()),
              "the variants have different parameters: w050 has {w, b}, w090 has {albedo}; a sweep plots variants "
              "that share their parameter names (choose the variants with --candidates)");
    // The studio's Rank window has no --candidates: it says nothing of choosing.
    try {
      ui::sweep_chart(k, "");
      FAIL() << "different parameter sets were plotted";
    } catch (const StudyError& e) {
      EXPECT_EQ(std::string(e.what()),
                "the variants have different parameters: w050 has {w, b}, w090 has {albedo}; a sweep plots variants "
                "that share their parameter names");
    }
  }
  k.ranked[2].params = {{"w", 0.9}, {"b", 0.4}, {"c", 1}};
  k.ranked[1].params = {{"w", 0.3}, {"b", 0.2}, {"c", 2}};
  k.ranked[0].params = {{"w", 0.5}, {"b", 0.2}, {"c", 1}};
  try {
    ui::sweep_chart(k);
    FAIL() << "three varying parameters were plotted";
  } catch (const StudyError& e) {
    EXPECT_EQ(std::string(e.what()),
              "3 parameters vary (w, b, c): a sweep plots one (a line) or two (a heat map); choose the variants with "
              "--candidates");
  }
}

TEST(SweepFigure, NoTextUnderSevenPointsInEitherForm) {
  const ui::FontMetrics metrics(ui::default_font_file());
  Ranking k = three_settings();
  for (int form = 0; form < 2; ++form) {
    if (form == 1) k.ranked[2].params = {{"w", 0.9}, {"b", 0.4}};  // two vary: the heat map
    ui::DisplayList fig(metrics);
    ui::FigureOptions o;
    ui::draw_sweep_chart(fig, ui::sweep_chart(k), o);
    ASSERT_FALSE(fig.texts().empty());
    for (const auto& t : fig.texts()) EXPECT_GE(t.size_pt, 7.0) << t.text;
    EXPECT_LE(fig.width_pt, ui::kSingleColumnIn * 72 + 0.01);
  }
}

// The value axis' title sits above the axis and its top tick label ("0.10" here: ticks 0, 0.02, ... 0.10
// over IPDs up to 0.09 + 0.01) is centred on the axis' end: the two boxes keep a clear gap (0.3 font sizes =
// 2.4 pt at 8 pt), at both column widths.
TEST(SweepFigure, AxisTitleClearsTheTopTickLabel) {
  const ui::FontMetrics metrics(ui::default_font_file());
  for (const double width : {ui::kSingleColumnIn, ui::kDoubleColumnIn}) {
    ui::DisplayList fig(metrics);
    ui::FigureOptions o;
    o.width_in = width;
    ui::draw_sweep_chart(fig, ui::sweep_chart(three_settings()), o);
    const std::vector<ui::DisplayList::TextItem> texts = fig.texts();
    const ui::DisplayList::TextItem *title = nullptr, *top_tick = nullptr;
    for (const auto& t : texts) {
      if (t.text == "IPD (lower is better)") title = &t;
      // The tick labels are the texts right of the page's left margin and left of the axis, "0.00" to "0.10".
      if (t.text.size() == 4 && t.text.rfind("0.", 0) == 0 && t.box.x0 < 30 &&
          (!top_tick || t.box.y0 < top_tick->box.y0))
        top_tick = &t;
    }
    ASSERT_TRUE(title && top_tick);
    EXPECT_EQ(top_tick->text, "0.10");
    EXPECT_GE(top_tick->box.y0 - title->box.y1, 2.4 - 1e-9) << width;
  }
}

}  // namespace
}  // namespace ipd
