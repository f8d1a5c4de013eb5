// The study-wide figure kinds (table, compare, distribution, breakdown) drawn from a cross table: the one
// function `ipd figure KIND` (a table computed from the study on disk) and the GUI's "Export figure…" (the
// session's table: its threshold and hand edits) both call, so the same study state gives the same figure.
#pragma once

#include <string>
#include <vector>

#include "core/stats/study_statistics.h"
#include "ui/canvas/canvas.h"
#include "ui/figures/figure_options.h"

namespace ipd::ui {

bool is_study_figure_kind(const std::string& kind);  // table | compare | distribution | breakdown

struct StudyFigureRequest {
  std::string kind;                 // table | compare | distribution | breakdown
  std::string model;                // distribution, breakdown: the model whose predictions count
  std::string ref, a, b;            // compare: reference and the two renderers; breakdown: the cell (a, b)
  std::vector<std::string> models;  // compare: only these rows (empty: every model)
  BootstrapOptions bootstrap;       // the intervals' resamples, level and seed (the table's cells carry them)
  int permutations = 2000;          // compare
  int worst = 2;                    // distribution: scenes named per domain pair
  int bins = 4;                     // breakdown by size or confidence
};

// Draws the figure into `out` (options.ci: the table's intervals; options.by: the breakdown's property) and
// returns its title (the PDF's metadata). `table` must have its intervals (add_confidence_intervals) and
// `labels` must be the labels it was computed from, predictions below the threshold already dropped (the
// breakdown reads rock sizes and confidences from them). Throws StudyError for a missing cell or domain.
std::string draw_study_figure(DisplayList& out, const CrossTable& table, const StudyLabels& labels,
                              const StudyFigureRequest& request, const FigureOptions& options);

}  // namespace ipd::ui
