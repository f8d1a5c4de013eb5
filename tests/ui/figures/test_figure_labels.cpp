// Labels in the scene figures read as their own target's (drawn in points with a DisplayList): a rock
// number never sits on another rock's box, a confidence on no GT box but the one its prediction matches,
// a registration number is nearer its own marker than any other. Impossible ones are left out and counted.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <algorithm>
#include <cmath>

#include "core/demo/demo_study.h"
#include "core/session/audit.h"
#include "core/study/study.h"
#include "tests/support/test_support.h"
#include "ui/figures/figure_input.h"
#include "ui/figures/figure_scene.h"

namespace ipd {
namespace {

bool over(const ui::PtRect& a, const ui::PtRect& b) { return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1; }

// Normalised box -> page rectangle in a panel showing the whole picture.
ui::PtRect on_page(const ui::PtRect& panel, const Box& b) {
  return {panel.x0 + b.x0() * panel.width(), panel.y0 + b.y0() * panel.height(), panel.x0 + b.x1() * panel.width(),
          panel.y0 + b.y1() * panel.height()};
}

std::vector<ui::DisplayList::TextItem> texts_named(const ui::DisplayList& fig, const std::string& s) {
  std::vector<ui::DisplayList::TextItem> out;
  for (const auto& t : fig.texts())
    if (t.text == s) out.push_back(t);
  return out;
}

// Whether the figure's text, wrapped lines joined by spaces, holds `s`.
bool contains_figure_labels(const ui::DisplayList& fig, const std::string& s) {
  std::string all;
  for (const auto& t : fig.texts()) all += t.text + " ";
  return all.find(s) != std::string::npos;
}

ui::SceneFigureInput tall_boxes_scene() {
  ui::SceneFigureInput in;
  in.stem = "s", in.a = "real", in.b = "synth", in.model = "det", in.method = "consensus";
  in.image_w = 1000, in.image_h = 1000;
  return in;
}

// One merged detection over two full-height GT boxes, left [0.33, 0.45] and right [0.45, 0.60]:
// IoU with the left 0.12/0.27 = 0.44, with the right 0.15/0.27 = 0.56, so it matches the right one. The
// page has no room above or below; the first inside corner (top left) lies on the left box and read as
// its confidence before: now the label takes the top right corner, inside the box it matches.
TEST(FigureLabels, AConfidenceLiesOnNoGtBoxButTheOneItsPredictionMatches) {
  ui::SceneFigureInput in = tall_boxes_scene();
  in.gt_a = {Box{0, 0.39, 0.5, 0.12, 1.0}, Box{0, 0.525, 0.5, 0.15, 1.0}};
  in.pred_a = {Box{0, 0.465, 0.5, 0.27, 1.0, 0.53}};
  ui::FigureOptions o;
  o.width_in = ui::kDoubleColumnIn;
  o.layers = ui::parse_layers("gt,pred,conf");
  const ui::FontMetrics metrics(ui::default_font_file());
  ui::DisplayList fig(metrics);
  const ui::PairsLayout l = ui::draw_pairs_figure(fig, in, o);
  const auto conf = texts_named(fig, "0.53");
  ASSERT_EQ(conf.size(), 1u);
  EXPECT_FALSE(over(conf[0].box, on_page(l.left, in.gt_a[0])));
  EXPECT_TRUE(over(conf[0].box, on_page(l.left, in.gt_a[1])));
  EXPECT_FALSE(contains_figure_labels(fig, "left out"));
}

// Rock 1 is a 5 pt wide full-height strip between rocks 2 and 3, touching both: its number fits inside
// no box of its own, and beside it lies on a neighbour (where it read as the neighbour's number before).
// With no spot and no leader clear of the neighbours it is left out, and the footnote counts it.
TEST(FigureLabels, ARockNumberNeverSitsOnAnotherRocksBox) {
  ui::SceneFigureInput in = tall_boxes_scene();
  in.gt_a = {Box{0, 0.41, 0.5, 0.02, 1.0}, Box{0, 0.35, 0.5, 0.10, 1.0}, Box{0, 0.47, 0.5, 0.10, 1.0}};
  ui::FigureOptions o;
  o.layers = ui::parse_layers("gt,indices,legend");
  const ui::FontMetrics metrics(ui::default_font_file());
  ui::DisplayList fig(metrics);
  const ui::PairsLayout l = ui::draw_pairs_figure(fig, in, o);
  EXPECT_TRUE(texts_named(fig, "1").empty());
  for (const std::string name : {"2", "3"}) {
    const auto t = texts_named(fig, name);
    ASSERT_EQ(t.size(), 1u) << name;
    for (size_t k = 0; k < in.gt_a.size(); ++k)
      if (std::to_string(k + 1) != name) {
        EXPECT_FALSE(over(t[0].box, on_page(l.left, in.gt_a[k]))) << name << " on " << k + 1;
      }
  }
  EXPECT_TRUE(contains_figure_labels(
      fig, "1 rock number left out: no free spot clear of the other rocks' boxes (try --crop or --column double)"));
}

// Registration figure, single column (panel 120 pt, dot 0.88 pt, ring 2.46 pt): an unpaired rock's dot
// 0.5 pt right of and 7.5 pt above the labelled one sits where the number "1" went (above its ring), so
// "1" read as that dot's. Now the number keeps 2 pt from every other marker: nearer its own.
TEST(FigureLabels, ARegistrationNumberIsNearerItsOwnMarkerThanAnyOther) {
  ui::SceneFigureInput in = tall_boxes_scene();
  const double dx = 0.5 / 120, dy = 7.5 / 120;
  in.gt_a = {Box{0, 0.5, 0.5, 0.05, 0.05}, Box{0, 0.5 + dx, 0.5 - dy, 0.05, 0.05}};
  in.gt_b = {Box{0, 0.5, 0.5, 0.05, 0.05}};
  in.pairs = {{0, 0}};
  ui::FigureOptions o;
  o.layers = ui::parse_layers("gt,pairs,indices");
  const ui::FontMetrics metrics(ui::default_font_file());
  ui::DisplayList fig(metrics);
  ui::draw_registration_figure(fig, in, o);
  const auto labels = texts_named(fig, "1");
  ASSERT_EQ(labels.size(), 2u);  // before and after (identity affine: the same picture twice)
  // Panels: 120 pt wide from x = 4 and x = 128 (4 pt gap), their top 0.15 font sizes below the caption.
  const auto caption = texts_named(fig, "before registration");
  ASSERT_EQ(caption.size(), 1u);
  const double top = caption[0].box.y1 + 0.15 * 8;
  for (const auto& t : labels) {
    const double x0 = t.box.x0 < 126 ? 4 : 128;
    const double cx = (t.box.x0 + t.box.x1) / 2, cy = (t.box.y0 + t.box.y1) / 2;
    const double own = std::hypot(cx - (x0 + 60), cy - (top + 60));
    const double other = std::hypot(cx - (x0 + 60 + 0.5), cy - (top + 60 - 7.5));
    EXPECT_LT(own, other) << "label at " << cx << ", " << cy;
  }
}

// A rock excluded by hand is drawn struck through; the legend says what the stroke means, only then.
TEST(FigureLabels, TheExcludedRockStrokeHasALegendEntry) {
  ui::SceneFigureInput in = tall_boxes_scene();
  in.gt_a = {Box{0, 0.3, 0.5, 0.1, 0.1}};
  in.gt_b = {Box{0, 0.3, 0.5, 0.1, 0.1}};
  in.pairs = {{0, 0}};
  const ui::FontMetrics metrics(ui::default_font_file());
  ui::FigureOptions o;
  o.width_in = ui::kDoubleColumnIn;
  ui::DisplayList plain(metrics);
  ui::draw_pairs_figure(plain, in, o);
  EXPECT_FALSE(contains_figure_labels(plain, "excluded from the IPD (by hand)"));
  in.excluded_a = {0};
  ui::DisplayList struck(metrics);
  ui::draw_pairs_figure(struck, in, o);
  EXPECT_TRUE(contains_figure_labels(struck, "excluded from the IPD (by hand)"));
}

// The ownership rule on a dense generated scene (60 rocks a side, labels only), double column with every
// layer: every shown rock number lies on no GT box but its own, every shown confidence on no GT box but
// the one its prediction matches (highest IoU), and the footnotes count the rest.
TEST(FigureLabels, EveryLabelOfADenseSceneIsOwned) {
  test::TempDir d;
  DemoStudyOptions demo;
  demo.scenes = 1;
  demo.min_rocks = demo.max_rocks = 60;
  demo.labels_only = true;
  write_demo_study(d.path(), demo);
  const StudyLabels labels = load_labels(open_study(d.path()));
  const std::string stem = labels.gt.begin()->second.begin()->first;
  const ui::SceneFigureInput in = ui::scene_input_from_study(labels, "real", "principled", "det-real", stem, 0, {});
  ui::FigureOptions o;
  o.width_in = ui::kDoubleColumnIn;
  o.layers = ui::parse_layers("gt,pred,conf,indices,pairs,legend");
  const ui::FontMetrics metrics(ui::default_font_file());
  ui::DisplayList fig(metrics);
  const ui::PairsLayout l = ui::draw_pairs_figure(fig, in, o);
  int numbers = 0, confidences = 0;
  for (int side = 0; side < 2; ++side) {
    const ui::PtRect& panel = side == 0 ? l.left : l.right;
    const auto& gt = side == 0 ? in.gt_a : in.gt_b;
    const auto& pred = side == 0 ? in.pred_a : in.pred_b;
    const std::vector<int> number = pair_numbers(in.pairs, gt.size(), side == 0);
    for (const auto& t : fig.texts()) {
      if (!over(t.box, panel) || t.text.empty() || t.text == "no picture") continue;
      const bool conf = t.text.size() == 4 && t.text.compare(0, 2, "0.") == 0;
      std::vector<size_t> owners;  // the GT boxes this label may lie on
      if (conf) {
        ++confidences;
        for (const Box& p : pred) {
          if (fmt::format("{:.2f}", p.conf) != t.text) continue;
          int matched = -1;
          double best = 0;
          for (size_t j = 0; j < gt.size(); ++j)
            if (iou(gt[j], p) > best) best = iou(gt[j], p), matched = int(j);
          if (matched >= 0) owners.push_back(size_t(matched));
        }
      } else {
        ++numbers;
        for (size_t k = 0; k < gt.size(); ++k)
          if ((number[k] > 0 ? std::to_string(number[k]) : "x" + std::to_string(k + 1)) == t.text) owners.push_back(k);
      }
      for (size_t k = 0; k < gt.size(); ++k) {
        if (std::find(owners.begin(), owners.end(), k) != owners.end()) continue;
        EXPECT_FALSE(over(t.box, on_page(panel, gt[k])))
            << (conf ? "confidence " : "number ") << t.text << " lies on GT box " << k + 1 << " (side " << side << ")";
      }
    }
  }
  EXPECT_GT(numbers, 60);      // most of the 2 x 60 numbers are shown
  EXPECT_GT(confidences, 20);  // and a good share of the confidences
}

}  // namespace
}  // namespace ipd
