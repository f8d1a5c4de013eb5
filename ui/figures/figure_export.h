// From a request to the bytes of a figure file: the one function the CLI and the GUI's "Export figure…"
// share (the GUI calls it on a worker thread; it needs no GL context).
#pragma once

#include <string>

#include "core/session/rock_pair_points.h"
#include "ui/canvas/canvas_cairo.h"
#include "ui/figures/figure_input.h"
#include "ui/figures/figure_table.h"

namespace ipd::ui {

// The figure as a display list (page size set), for any backend. `metrics` must outlive the result.
DisplayList scene_figure(const std::string& kind, const SceneFigureInput& in, const FigureOptions& options,
                         const FontMetrics& metrics);

// The file's bytes through cairo (PDF, SVG, or PNG at options.dpi).
std::string scene_figure_file(const std::string& kind, const SceneFigureInput& in, const FigureOptions& options,
                              FigureFormat format);

// A sentence for a path whose extension is not a figure format (empty when it is one).
std::string bad_extension_message(const std::string& path);

// The figure kinds, in the order the GUI's dialog lists them.
// pairs, registration, table, compare, distribution, breakdown, gallery
extern const char* const kFigureKinds[7];
bool is_figure_kind(const std::string& kind);

// What the GUI's "Export figure…" asks for: a figure of the session's current view.
struct ExportRequest {
  std::string kind = "pairs";  // one of kFigureKinds
  FigureOptions options;       // .ci: the table's intervals; .by: the breakdown's property
  std::string path;            // .pdf, .svg or .png
  int scene = -1;              // pairs, registration
  std::string ref, a, b;       // compare: the statistics panel's domains (empty: as `ipd figure compare`)
  int gallery_count = 8;       // gallery: how many pairs, in the order of gallery_sort (as on screen)
  GallerySort gallery_sort = GallerySort::kDiff;
};
// Builds the figure from the session's current view (domains, model, threshold, edits) exactly as
// `ipd figure KIND` builds it from the same study state on disk: scene kinds read the pictures; the study
// kinds compute the session's cross table with intervals (seeded as `ipd table`), the comparison and the
// breakdown (of the view's model and domain pair). Renders with cairo and writes the file atomically. Off
// the UI thread (the session must not change while it runs: pass the worker's immutable snapshot). Returns
// the status line ("exported PATH" or the error).
std::string export_figure(const Session& session, const ExportRequest& request);

}  // namespace ipd::ui
