// ipd-studio's statistics panels: the interval of each cross-table cell (tooltip), a renderer comparison
// (ref / a / b -> ΔIPD, interval, p and the sentence), the histogram of per-scene IPD of the current cell
// (a click on a bar filters the scene list to those scenes) and the size breakdown as small bars. They draw
// a SessionStatistics computed off the UI thread; they never compute.
#pragma once

#include <cmath>
#include <string>

#include "core/session/session_statistics.h"
#include "ui/figures/stats_charts.h"
#include "ui/gui/views.h"

namespace ipd::ui {

struct StatsPanelState {
  int ref = 0, a = 1, b = 2;  // domain indices of the comparison
  int bins = 8;               // histogram bars
};

// What to compute for the current view (the app hands it to its statistics job).
SessionStatisticsRequest stats_request(const Session& s, const StatsPanelState& st);

// The compare panel's numbers line, written as comparison_sentence writes them (ΔIPD, the typographic minus
// U+2212): "ΔIPD = −0.0802 [−0.094, −0.066]   p = 0.0078"; the panel passes it through spell_missing_glyphs.
// Fewer than two scenes: "ΔIPD = 0.0200, 1 scene: no interval, no test" (never "p = nan").
std::string compare_delta_line(const Comparison& r);

// A tooltip with the cell's interval when the last item is hovered (nothing while unknown).
void cell_interval_tooltip(const SessionStatistics* stats, const std::string& model, int pair);

// `stats` may be null (first computation running) or older than the view, or of a first look's scenes while the
// study loads (`computing` is then true: each panel says "updating...").
void draw_stats_panels(const StudyView& v, const SessionStatistics* stats, bool computing, StatsPanelState& st,
                       UiState& ui, UiCommands& out);

// Histogram bins of values: `bins` bars of a round width from 0 (or the minimum) up to the maximum.
struct HistogramBins {
  double start = 0, width = 0;
  std::vector<int> counts;
  // Every value the same (one scene, say): three bins with the value's bin in the middle, and the value,
  // where its bar is drawn (not at its bin's centre, which would read half a bin off).
  double lone_value = std::nan("");
};
HistogramBins histogram_bins(const std::vector<double>& values, int bins);

// Why the per-scene IPD histogram has no bar, from the scene list's summaries: no scene has pairs, or scenes
// have pairs but no IPD (SceneSummary::no_value_reason, e.g. no predictions left above the threshold).
std::string empty_histogram_text(const std::vector<SceneSummary>& summaries);
// The IPD panel's line for the domain pair in view: "0.0295 over 69 pairs in 5 scenes" counts the scenes with
// pairs, as the per-scene histogram does (a scene without pairs has no IPD and no bar), and names the others.
std::string cell_totals_line(double ipd, long pairs, const std::vector<SceneSummary>& summaries);
// The histogram's caption: "5 scenes with pairs".
std::string histogram_scenes_text(size_t scenes);

// The studio's charts draw on the figure canvas in window pixels: text at the GUI font's size, the theme's
// colours.
TextStyle gui_text();
ChartColours gui_colours();

}  // namespace ipd::ui
