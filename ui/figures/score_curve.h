// The registration replay's score curve: the best score so far over the search's steps, with a value axis,
// a step axis and which way is better, laid out and drawn on the figure canvas (the studio draws it through
// its ImGui canvas). Pure layout + drawing: no ImGui, no I/O.
#pragma once

#include <string>
#include <vector>

#include "core/registration/registration.h"
#include "ui/canvas/canvas.h"
#include "ui/figures/stats_charts.h"

namespace ipd::ui {

// "lower is better" (paper's mean distance, cpd's mixture width) or "higher is better" (consensus' soft inlier
// count), for the chart and its caption.
const char* score_direction(FitMeasure measure);

struct ScoreCurveInput {
  std::vector<double> best;  // best score so far after each step (finite values; others are skipped)
  int current = -1;          // the replay's step, marked by a vertical line (-1: none)
  FitMeasure measure = FitMeasure::kSoftInliers;  // the method's (fit_measure_of)
};

struct ScoreCurve {
  PtRect plot;                       // the curve's box; value axis along plot.x0, step axis along plot.y1
  std::vector<Pt> points;            // one per finite step
  std::vector<AxisTick> value_axis;  // at: y
  std::vector<AxisTick> step_axis;   // at: x; steps numbered from 1
  double current_x = -1;             // the marker's x (-1: none)
  // "lower is better" / "higher is better" in the right-hand corner the best-so-far curve leaves free: it
  // never gets worse, so it ends at the top for higher-is-better (the label goes bottom right) and at the
  // bottom for lower-is-better (top right).
  std::string direction;
  Pt direction_at;
  Anchor direction_anchor = Anchor::kTopRight;  // the label's corner at direction_at
};
ScoreCurve layout_score_curve(Canvas& c, const TextStyle& text, const ScoreCurveInput& in, const PtRect& area);
void draw_score_curve(Canvas& c, const TextStyle& text, const ScoreCurve& curve, const ChartColours& colours);

}  // namespace ipd::ui
