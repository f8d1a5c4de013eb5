// Rules the engine, the studio, the figures and the CLI share: each is written once, and these cases are the
// ones where a second copy of a rule would give another answer.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>

#include "core/geometry/confidence_threshold.h"
#include "core/ipd/ipd.h"
#include "core/session/session.h"
#include "core/stats/detection_metrics.h"
#include "core/stats/statistics.h"
#include "tests/support/test_support.h"
#include "ui/canvas/canvas.h"
#include "ui/figures/figure_input.h"

namespace ipd {
namespace {

using test::box;

// The confidence threshold: conf >= T is kept; T <= 0 keeps every prediction, also one a rounding below 0
// (label files accept values up to 1e-3 outside [0, 1]).
TEST(OneRule, ConfidenceThresholdKeepsConfAtOrAboveAndEverythingAtZero) {
  EXPECT_TRUE(kept_at_threshold(box(0.5, 0.5, 0.1, 0.1, 0.5), 0.5));
  EXPECT_FALSE(kept_at_threshold(box(0.5, 0.5, 0.1, 0.1, 0.4999), 0.5));
  EXPECT_TRUE(kept_at_threshold(box(0.5, 0.5, 0.1, 0.1, -0.0005), 0.0));
  const std::vector<Box> kept =
      predictions_kept({box(0.1, 0.1, 0.1, 0.1, 0.3), box(0.2, 0.2, 0.1, 0.1, 0.7), box(0.3, 0.3, 0.1, 0.1, 0.5)}, 0.5);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_DOUBLE_EQ(kept[0].cx, 0.2);  // in their order
  EXPECT_DOUBLE_EQ(kept[1].cx, 0.3);
}

// The tiny study of test_ipd.cpp (pairs (0,1), (1,0); IPD 1/2 with perf real = {1, 1/3}, synth = {0, 1/3}),
// with real's second prediction at conf -0.0005: at threshold 0 it counts everywhere. A studio that dropped
// it would show perf real = {1, 0} and IPD (|1 - 1/3| + |0 - 0|) / 2 = 1/3.
void write_rounded_conf_study(const test::TempDir& d) {
  test::write_text(d / "real/labels/s1.txt", "0 0.2 0.2 0.1 0.1\n0 0.6 0.6 0.1 0.1\n");
  test::write_text(d / "synth/labels/s1.txt", "0 0.6 0.6 0.1 0.1\n0 0.2 0.2 0.1 0.1\n");
  test::write_text(d / "real/predictions/det/s1.txt", "0 0.2 0.2 0.1 0.1 0.9\n0 0.65 0.6 0.1 0.1 -0.0005\n");
  test::write_text(d / "synth/predictions/det/s1.txt", "0 0.25 0.2 0.1 0.1 0.8\n");
}

TEST(OneRule, EngineStudioFiguresAndMetricsKeepTheSamePredictions) {
  test::TempDir d;
  write_rounded_conf_study(d);
  const StudyLabels labels = load_labels(open_study(d.path()));
  ASSERT_TRUE(labels.errors.empty());
  EXPECT_EQ(labels.predictions_of("real", "det", "s1").boxes.size(), 2u);  // the engine keeps both
  EXPECT_NEAR(compute_cross_table(labels, {}).cells[0].ipd, 0.5, 1e-12);

  const Session s = Session::open(d.path());
  EXPECT_EQ(s.predictions(Side::kA, 0).size(), 2u);
  EXPECT_NEAR(s.performance(Side::kA, 0).value[1], 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(s.cell().ipd, 0.5, 1e-12);

  const ui::SceneFigureInput in = ui::scene_input_from_study(labels, "real", "synth", "det", "s1", 0.0, {});
  EXPECT_EQ(in.pred_a.size(), 2u);

  DetectionImage im;
  im.gt = labels.gt_of("real", "s1").boxes;
  im.detections = labels.predictions_of("real", "det", "s1").boxes;
  EXPECT_EQ(detection_metrics({im}, 0.0).detections, 2);
  EXPECT_EQ(detection_metrics({im}, 0.5).detections, 1);  // 0.9 only
}

// The studio's cross table and the engine's, cell by cell, on a study with everything that makes a cell
// special: hand pairs with an excluded rock (real | synth, scene s1), a domain whose predictions are all below
// the threshold (hapke, for det), a model with no prediction left anywhere (faint: no number, with the
// engine's reason) and a model with predictions in one domain only (solo: missing predictions).
void write_cells_study(const test::TempDir& d) {
  test::write_text(d / "study.yaml", "conf_threshold: 0.5\n");
  const char* rocks = "0 0.2 0.2 0.1 0.1\n0 0.6 0.6 0.1 0.1\n0 0.3 0.7 0.08 0.08\n0 0.75 0.25 0.06 0.06\n";
  for (const char* stem : {"s1", "s2"}) {
    const std::string st = stem;
    for (const char* domain : {"real", "synth", "hapke"})
      test::write_text(d / (std::string(domain) + "/labels/" + st + ".txt"), rocks);
    test::write_text(d / ("real/predictions/det/" + st + ".txt"), "0 0.2 0.2 0.1 0.1 0.9\n0 0.62 0.6 0.1 0.1 0.7\n");
    test::write_text(d / ("synth/predictions/det/" + st + ".txt"),
                     "0 0.25 0.2 0.1 0.1 0.8\n0 0.3 0.71 0.08 0.08 0.6\n0 0.75 0.25 0.06 0.06 0.4\n");
    test::write_text(d / ("hapke/predictions/det/" + st + ".txt"), "0 0.2 0.2 0.1 0.1 0.3\n");
    for (const char* domain : {"real", "synth", "hapke"})
      test::write_text(d / (std::string(domain) + "/predictions/faint/" + st + ".txt"), "0 0.2 0.2 0.1 0.1 0.2\n");
    test::write_text(d / ("real/predictions/solo/" + st + ".txt"), "0 0.2 0.2 0.1 0.1 0.9\n");
  }
  // s1 of real | synth by hand: rocks 0-2 paired crosswise for 1 and 2, synth's rock 3 excluded.
  test::write_text(
      d / "pairs/real__synth/s1.json",
      "{\"pairs\": [[0, 0], [1, 2], [2, 1], [3, 3]], \"excluded_b\": [3], \"rocks_a\": [[0, 0.2, 0.2, 0.1, "
      "0.1], [1, 0.6, 0.6, 0.1, 0.1], [2, 0.3, 0.7, 0.08, 0.08], [3, 0.75, 0.25, 0.06, 0.06]], \"rocks_b\": "
      "[[0, 0.2, 0.2, 0.1, 0.1], [1, 0.6, 0.6, 0.1, 0.1], [2, 0.3, 0.7, 0.08, 0.08], [3, 0.75, 0.25, 0.06, "
      "0.06]]}\n");
}

// After an edit the studio's cell takes the scene's old contribution away and adds the new one: still the
// engine's cell of the saved study, scene count included.
TEST(OneRule, AfterAnEditTheStudioCellIsTheEnginesCell) {
  test::TempDir d;
  write_cells_study(d);
  Session s = Session::open(d.path());
  run_save_job(s.apply(1, Edit::unpair(Side::kA, 0)));  // scene s2: rock 0 left unpaired
  const TableCell c = s.cell();
  const CrossTable t = compute_cross_table(load_labels(open_study(d.path())), {});
  const TableCell* e = t.cell(c.model, c.a, c.b);
  ASSERT_NE(e, nullptr);
  EXPECT_EQ(c.scenes, 2);
  EXPECT_EQ(c.scenes, e->scenes);
  EXPECT_EQ(c.pairs, e->pairs);
  EXPECT_EQ(c.unpaired_a, e->unpaired_a);
  EXPECT_NEAR(c.ipd, e->ipd, 1e-12);
}

TEST(OneRule, StudioCellsAreTheEngineCells) {
  test::TempDir d;
  write_cells_study(d);
  const CrossTable t = compute_cross_table(load_labels(open_study(d.path())), {});
  const Session s = Session::open(d.path());
  ASSERT_EQ(s.domain_pairs().size(), 3u);
  int numbers = 0, reasons = 0, missing = 0;
  for (size_t p = 0; p < s.domain_pairs().size(); ++p) {
    const auto& [a, b] = s.domain_pairs()[p];
    for (const std::string model : {"det", "faint", "solo"}) {
      SCOPED_TRACE(fmt::format("{} on {} | {}", model, a, b));
      const TableCell* e = t.cell(model, a, b);
      ASSERT_NE(e, nullptr);
      const TableCell c = s.cell_for(model, static_cast<int>(p));
      EXPECT_EQ(std::isnan(c.ipd), std::isnan(e->ipd));
      if (!std::isnan(e->ipd)) {
        EXPECT_NEAR(c.ipd, e->ipd, 1e-12);
      }
      EXPECT_EQ(c.involves_training_domain, e->involves_training_domain);
      EXPECT_EQ(c.missing_predictions, e->missing_predictions);
      EXPECT_EQ(c.no_value_reason, e->no_value_reason);  // also "no predictions of solo for ...": the same footnote
      if (e->missing_predictions) {
        ++missing;
        continue;
      }
      EXPECT_EQ(c.pairs, e->pairs);
      EXPECT_EQ(c.unpaired_a, e->unpaired_a);
      EXPECT_EQ(c.unpaired_b, e->unpaired_b);
      EXPECT_EQ(c.scenes, e->scenes);
      EXPECT_EQ(c.no_value_reason, e->no_value_reason);
      numbers += !std::isnan(e->ipd);
      reasons += !e->no_value_reason.empty();
    }
  }
  // Every kind of cell was compared: det's three numbers, faint's three reasons, solo's three missing cells.
  EXPECT_EQ(numbers, 3);
  EXPECT_EQ(reasons, 3);
  EXPECT_EQ(missing, 3);
  // The hand pairs count: real | synth of det pools s1's 3 counted pairs (synth's rock 3 excluded) and s2's 4.
  const TableCell* rs = t.cell("det", "real", "synth");
  ASSERT_NE(rs, nullptr);
  EXPECT_EQ(rs->pairs, 7);
}

// One bootstrap resample has no spread: the engine refuses it as the CLI does (`ipd table --bootstrap 1`
// reports this very sentence), instead of returning an interval of NaNs.
TEST(OneRule, OneBootstrapResampleIsRefusedByTheEngine) {
  BootstrapOptions b;
  b.resamples = 1;
  EXPECT_EQ(b.validate(),
            "the number of bootstrap resamples must be 0 (no intervals) or at least 2 (an interval needs two "
            "resamples), not 1");
  b.resamples = 0;
  EXPECT_EQ(b.validate(), "");
  b.resamples = 2;
  EXPECT_EQ(b.validate(), "");
  const std::vector<SceneSum> scenes = {{1.0, 2}, {3.0, 2}};
  b.resamples = 1;
  EXPECT_THROW(bootstrap_pooled_mean(scenes, b, "cell"), std::invalid_argument);
}

// The figures, `ipd figure` and the studio's window draw with one font file: the data look-up's (an installed
// or source-tree assets/fonts/DejaVuSans.ttf), else Debian's DejaVu Sans.
TEST(OneRule, OneFontFileForFiguresAndTheStudio) {
  const std::string font = ui::default_font_file();
  const std::string tail = "/fonts/DejaVuSans.ttf";
  EXPECT_TRUE(font == "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf" ||
              (font.size() > tail.size() && font.compare(font.size() - tail.size(), tail.size(), tail) == 0))
      << font;
  EXPECT_EQ(ui::font_file_problem(font), "");
}

}  // namespace
}  // namespace ipd
