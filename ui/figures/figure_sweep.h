// `ipd figure sweep`: IPD(ref, variant) along the renderer parameter the variants differ in (study.yaml's
// domains.<name>.params), from a ranking (core/rank/ranking.h). One varying parameter: the IPD as a line with its
// scene-bootstrap interval as a band, the best marked and the group not distinguishable from it filled. Two: a
// heat map of the IPD, the best cell framed and the group's cells marked. Greyscale-safe: the marks differ by
// shape and fill, the heat map's shades by luminance, and every value is printed at >= 7 pt.
#pragma once

#include <string>
#include <vector>

#include "core/rank/ranking.h"
#include "ui/canvas/canvas.h"
#include "ui/figures/figure_options.h"

namespace ipd::ui {

struct SweepPoint {
  std::string domain;
  double x = 0, y = 0;  // the varying parameters' values (y: the second one, heat map only)
  double ipd = 0, low = 0, high = 0;
  bool best = false, in_group = false;
};

struct SweepChart {
  std::string title, footnote;
  std::vector<std::string> parameters;  // one (a line) or two (a heat map)
  std::vector<SweepPoint> points;       // sorted by the first parameter, then the second
};

// The chart of `ranking`'s ranked candidates. Throws StudyError when a candidate has no params or other parameter
// names than the rest (naming both), when no parameter varies, or when more than two do; `choose` ends those
// messages with how to choose other variants ("choose the variants with --candidates"; empty where there is no way).
SweepChart sweep_chart(const Ranking& ranking, const std::string& choose = "choose the variants with --candidates");

void draw_sweep_chart(DisplayList& out, const SweepChart& chart, const FigureOptions& options);

}  // namespace ipd::ui
