// What every `ipd figure` kind shares on the command line: --out (format from the extension), size, font,
// DPI; and writing the figure (cairo for PDF/SVG, OSMesa + ImGui for PNG).
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "ui/canvas/canvas.h"
#include "ui/figures/figure_options.h"

namespace ipd::cli {

struct FigureOutputArgs {
  std::string out, column = "single", font, layers, crop, panels = "auto";
  std::optional<double> width_in;  // --width-in; not given: --column's width
  double font_pt = 8, dpi = 300;
  bool mkdir = false;  // --mkdir: create --out's folder when it is missing
};
void add_figure_output_options(CLI::App* cmd, FigureOutputArgs* args);

// Checks --out's extension and folder (it must exist unless --mkdir) and the option values: prints
// "error: ..." and returns the exit code (2 usage, 1 missing font) when something is wrong, 0 and fills
// `out` when all is well (nothing is written either way).
int figure_options(const FigureOutputArgs& args, ui::FigureOptions* out);

// Writes the figure atomically to `path` (below the study never through a link it holds: write_output_file) and
// prints the path.
void write_figure(const ui::DisplayList& figure, const ui::FontMetrics& metrics, const ui::FigureOptions& options,
                  const std::string& study_root, const std::string& path, const std::string& title);

}  // namespace ipd::cli
