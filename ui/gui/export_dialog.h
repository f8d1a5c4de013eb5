// ipd-studio's "Export figure…" dialog: kind (the six of `ipd figure`), format, column, layers and crop
// (= the current zoom) for the scene kinds, intervals for the table, the property of a breakdown; filled from
// the view; it only returns a request, which the app hands to a worker (figure_export.h renders it).
#pragma once

#include <optional>
#include <string>

#include "ui/figures/figure_export.h"
#include "ui/gui/scene_canvas.h"
#include "ui/gui/stats_panels.h"
#include "ui/gui/views.h"

namespace ipd::ui {

struct ExportDialogState {
  bool open = false;                                       // the popup should be shown (set to open it)
  int kind = 0;                                            // index into kFigureKinds
  int by = 0;                                              // breakdown: 0 size, 1 region, 2 confidence
  bool ci = true;                                          // table: each cell's interval
  int format = 0;                                          // 0 pdf, 1 svg, 2 png
  int column = 0;                                          // 0 single, 1 double
  bool layers[6] = {true, true, false, true, true, true};  // gt, pred, conf, indices, pairs, legend
  bool crop_to_view = true;
  float font_pt = 8;
  char dir[512] = "";
  char name[256] = "";
  int gallery_sort = 0;   // gallery: a GallerySort, the Rock pairs gallery's order when the dialog opens
  int gallery_count = 8;  // gallery: how many pairs
};

// What the view shows, to fill the dialog when it opens.
struct ExportViewContext {
  std::string default_dir, base_name;  // e.g. STUDY/figures, scene_02_real_principled
  std::string model, left, right;      // the view's model and domains (the study kinds' file names)
  double conf_threshold = 0;           // the view's prediction threshold (0: none)
  std::string ref, a, b;               // the statistics panel's comparison (empty: the CLI's defaults)
  SideLayers layers;                   // the view's visible layers
  CanvasView view;                     // zoom and pan of the left picture
  int image_w = 0, image_h = 0;
  int scene = -1;
  bool scene_stale = false;  // its pairs file no longer matches its labels: the CLI needs --skip-bad-lines
  GallerySort gallery_sort = GallerySort::kDiff;  // the order the Rock pairs gallery shows
};

// The context of the session's current view (scene, layers, zoom, the comparison the statistics panel
// shows; files go to STUDY/figures, or the working directory for a read-only study).
ExportViewContext export_view_context(const Session& session, const UiState& ui, const StatsPanelState& stats);

// The visible region of a picture shown with `view` in a pane of the picture's aspect (normalised, clamped).
Crop crop_of_view(const CanvasView& view);

// Opens the dialog pre-filled from the view.
void open_export_dialog(ExportDialogState& state, const ExportViewContext& context);
// The file name (without folder or extension) the dialog proposes for its kind: everything the figure
// depends on (scene, domains, model, threshold), so exports of different views never overwrite each other,
// e.g. "scene_02_real_principled_det-real_pairs", "scene_02_real_principled_det-real_conf0.4_pairs",
// "table", "table_conf0.4", "breakdown_size_det-real_real_principled".
std::string default_figure_name(const ExportDialogState& state, const ExportViewContext& context);
// "pairs", ..., "breakdown" (with state.by = 0) or "breakdown-size|region|confidence" into the state's kind
// and by; false for anything else.
bool set_export_kind(ExportDialogState& state, const std::string& kind);
// The request the dialog's Export button makes (also used by ipd-studio --replay's `export`).
ExportRequest export_request(const ExportDialogState& state, const ExportViewContext& context, const std::string& path);
// Draws it when open; returns the request when the user presses Export.
std::optional<ExportRequest> draw_export_dialog(ExportDialogState& state, const ExportViewContext& context);

}  // namespace ipd::ui
