// From a request to the bytes of a figure file: the one function the CLI and the GUI's "Export figure…"
// share (the GUI calls it on a worker thread; it needs no GL context).
#pragma once

#include <string>

#include "canvas_cairo.h"
#include "figure_input.h"
#include "figure_table.h"

namespace ipd::ui {

// The figure as a display list (page size set), for any backend. `metrics` must outlive the result.
DisplayList scene_figure(const std::string& kind, const SceneFigureInput& in, const FigureOptions& options,
                         const FontMetrics& metrics);

// The file's bytes through cairo (PDF, SVG, or PNG at options.dpi).
std::string scene_figure_file(const std::string& kind, const SceneFigureInput& in, const FigureOptions& options,
                              FigureFormat format);

// A sentence for a path whose extension is not a figure format (empty when it is one).
std::string bad_extension_message(const std::string& path);

// What the GUI's "Export figure…" asks for: a scene figure of the session's current view.
struct ExportRequest {
  std::string kind = "pairs";  // pairs | registration
  FigureOptions options;
  std::string path;            // .pdf, .svg or .png
  int scene = -1;
};
// Builds the figure from the session's current view (domains, model, threshold, edits), reads the pictures,
// renders with cairo and writes the file atomically. Off the UI thread (the session must not change while
// it runs: pass the worker's immutable snapshot). Returns the status line ("exported PATH" or the error).
std::string export_scene_figure(const Session& session, const ExportRequest& request);

}  // namespace ipd::ui
