// The study-wide figure kinds (table, compare, distribution, breakdown) drawn from a cross table: the one
// function `ipd figure KIND` (a table computed from the study on disk) and the GUI's "Export figure…" (the
// session's table: its threshold and hand edits) both call, so the same study state gives the same figure.
#pragma once

#include <string>
#include <vector>

#include "core/report/provenance.h"
#include "core/session/rock_pair_points.h"
#include "core/stats/study_statistics.h"
#include "ui/canvas/canvas.h"
#include "ui/figures/figure_options.h"

namespace ipd::ui {

bool is_study_figure_kind(const std::string& kind);  // table | compare | distribution | breakdown | gallery

struct StudyFigureRequest {
  std::string kind;                 // table | compare | distribution | breakdown | gallery
  std::string model;                // distribution, breakdown, gallery: the model whose predictions count
  std::string ref, a, b;            // compare: reference and the two renderers; breakdown, gallery: the cell
  std::vector<std::string> models;  // compare: only these rows (empty: every model)
  BootstrapOptions bootstrap;       // the intervals' resamples, level and seed (the table's cells carry them)
  int permutations = 2000;          // compare
  int worst = 2;                    // distribution: scenes named per domain pair
  int bins = 4;                     // breakdown by size or confidence
  int count = 8;                    // gallery: how many pairs
  std::string scene;                // gallery: only this scene's pairs (empty: all)
  int rock = 0;                     // gallery, with scene: only the pair of this rock of `a` (from 1; 0: all)
  GallerySort gallery_sort = GallerySort::kDiff;
  // The confidence threshold the predictions were cut at (`--conf`, the studio's slider, else study.yaml's):
  // above 0 the table, compare, distribution and breakdown say it under the figure, as the pairs figure's
  // caption does ("conf ≥ 0.3"), since their numbers depend on it.
  double conf_threshold = 0;
};

// Draws the figure into `out` (options.ci: the table's intervals; options.by: the breakdown's property) and
// returns its title (the PDF's metadata). `table` must have its intervals (add_confidence_intervals) and
// `labels` must be the labels it was computed from, predictions below the threshold already dropped (the
// breakdown reads rock sizes and confidences from them, the gallery boxes; the gallery reads the pictures).
// The provenance of `table` goes into the figure (figure_provenance.h). Throws StudyError for a missing
// cell or domain.
// `provenance` (optional): what the figure says about hand edits; null: table_provenance of `table` over the
// domain pairs the figure draws (study_figure_domain_pairs), which needs the table's pairings (a session's
// table has none: pass session_provenance over the same domain pairs).
// The domain pairs whose numbers a figure shows, so its provenance counts the hand pairs of those alone:
// compare (ref, a) and (ref, b), breakdown and gallery their cell's pair; empty (every pair) for the rest.
// Throws StudyError as the figure would for domains it can't resolve.
DomainPairFilter study_figure_domain_pairs(const Study& study, const StudyFigureRequest& request);

std::string draw_study_figure(DisplayList& out, const CrossTable& table, const StudyLabels& labels,
                              const StudyFigureRequest& request, const FigureOptions& options,
                              const Provenance* provenance = nullptr);

}  // namespace ipd::ui
