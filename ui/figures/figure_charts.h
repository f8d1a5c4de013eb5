// The statistics figures: dot-and-whisker rows (ΔIPD per model for `compare`, IPD per bin for `breakdown`)
// and box plots of per-scene IPD (`distribution`), with an IPD axis, drawn on the figure canvas.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "ui/canvas/canvas.h"
#include "ui/figures/figure_options.h"

namespace ipd::ui {

struct ChartRow {
  std::string label;                       // left of the row
  double estimate = 0, low = 0, high = 0;  // low/high NaN: no whisker
  std::string note;                        // right of the row (p-value, pairs)
};
struct DotWhiskerChart {
  std::string title, axis_label, footnote;
  std::vector<ChartRow> rows;
  bool zero_line = false;     // a reference line at 0 (ΔIPD)
  bool non_negative = false;  // the values cannot be negative (IPD): the axis starts at 0
};
void draw_dot_whisker_chart(DisplayList& out, const DotWhiskerChart& chart, const FigureOptions& options);

struct BoxRow {
  std::string label;
  std::vector<double> values;  // one per scene (dots)
  double min = 0, q1 = 0, median = 0, q3 = 0, max = 0;
  std::vector<std::pair<std::string, double>> worst;  // named next to their dots
};
struct DistributionChart {
  std::string title, axis_label, footnote;
  std::vector<BoxRow> rows;
};
void draw_distribution_chart(DisplayList& out, const DistributionChart& chart, const FigureOptions& options);

// "Nice" axis ticks (1, 2, 2.5, 5 x 10^k) covering [lo, hi], about `target` of them.
std::vector<double> nice_ticks(double lo, double hi, int target);
// A tick's text with as many decimals as the step needs (0.025 -> 3, 0.5 -> 1, 20 -> 0).
std::string tick_text(double v, double step);

}  // namespace ipd::ui
