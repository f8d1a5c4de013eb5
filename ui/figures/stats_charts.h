// The small charts of ipd-studio's statistics panel, laid out and drawn on the figure canvas (canvas.h) so
// the GUI and any other backend draw the same thing, and tests can read the layout: the per-scene IPD
// histogram (a count axis on the left, bin edges below, the current scene's bin outlined) and the IPD
// bars of the size breakdown (an IPD axis below). Sizes come from the text style's measured line height.
// Pure layout + drawing: no ImGui, no I/O.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "ui/canvas/canvas.h"

namespace ipd::ui {

struct AxisTick {
  double value = 0;
  double at = 0;  // y (count axis) or x (value axis) in points
  std::string text;
};

// Integer ticks 0, step, ..., top' >= top with step 1, 2 or 5 × 10^k and at most `most` intervals.
std::vector<double> count_ticks(int top, int most);

struct HistogramBar {
  PtRect slot;  // the bin's column (what a click hits)
  PtRect bar;   // the bar inside it (zero height for an empty bin)
  int count = 0;
  double lo = 0, hi = 0;  // the bin's IPD range
  bool current = false;   // holds the current scene
};
struct HistogramChart {
  PtRect plot;  // bars stand on plot.y1; the count axis is at plot.x0
  std::vector<HistogramBar> bars;
  std::vector<AxisTick> count_axis, edge_axis;
  double outline_gap = 0, outline_width = 0;  // the current bin's outline, around (not over) its bar
};
struct HistogramInput {
  double start = 0, width = 0;  // bin k covers [start + k width, start + (k+1) width)
  std::vector<int> counts;
  double current = 0;                // the current scene's value (NaN: none)
  double lone_value = std::nan("");  // all values equal: the bar holding it is centred at it, not its bin
};
HistogramChart layout_histogram(Canvas& c, const TextStyle& text, const HistogramInput& in, const PtRect& area);
struct ChartColours {
  Colour bar, bar_hot, current, axis, whisker, tick_text, label;
};
void draw_histogram(Canvas& c, const TextStyle& text, const HistogramChart& chart, const ChartColours& colours,
                    int hot_bar);

// Horizontal bars with an interval whisker, one row per label, an IPD axis below.
struct ValueBarRow {
  std::string label;
  double value = 0, low = 0, high = 0;  // value NaN: no bar; low/high NaN: no whisker
};
struct ValueBarsChart {
  PtRect plot;  // bars start at plot.x0; the axis runs along plot.y1
  struct Row {
    PtRect band;                            // the whole row (label and bar: what hovering hits)
    Pt label_at;                            // right end of the label, vertically centred
    PtRect bar;                             // empty when the value is NaN
    double whisker_x0 = 0, whisker_x1 = 0;  // equal: no whisker
  };
  std::vector<Row> rows;
  std::vector<AxisTick> value_axis;
};
ValueBarsChart layout_value_bars(Canvas& c, const TextStyle& text, const std::vector<ValueBarRow>& rows,
                                 const PtRect& area);
void draw_value_bars(Canvas& c, const TextStyle& text, const ValueBarsChart& chart,
                     const std::vector<ValueBarRow>& rows, const ChartColours& colours, int hot_row);
// The height layout_value_bars needs for `rows` rows (row height and axis from the text's line height).
double value_bars_height(Canvas& c, const TextStyle& text, size_t rows);

}  // namespace ipd::ui
