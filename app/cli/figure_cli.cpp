#include "app/cli/figure_cli.h"

#include <fmt/format.h>

#include <filesystem>

#include "app/cli/cli_common.h"
#include "app/cli/offscreen_renderer.h"
#include "core/util/atomic_file.h"
#include "core/util/contained_file.h"
#include "ui/canvas/canvas_cairo.h"
#include "ui/figures/figure_export.h"

namespace ipd::cli {

void add_figure_output_options(CLI::App* cmd, FigureOutputArgs* a) {
  cmd->add_option("--out", a->out, "File to write (atomically): .pdf, .svg or .png")->required();
  auto* column = cmd->add_option("--column", a->column, "single (3.5 in) or double (7.16 in)")
                     ->check(CLI::IsMember({"single", "double"}));
  // Any typed width is checked (1 to 40 inches): 0 or -3 is an error, never "not given" (--column's width).
  cmd->add_option_function<double>(
         "--width-in", [a](const double& inches) { a->width_in = inches; },
         "Width in inches, 1 to 40 (instead of --column)")
      ->excludes(column);
  cmd->add_option("--font-pt", a->font_pt, "Font size in points (default 8; at least 6)");
  cmd->add_option("--dpi", a->dpi, "PNG resolution (default 300: a single column is 1050 px wide)");
  cmd->add_option("--font", a->font, "TrueType font file (default: DejaVu Sans)");
  cmd->add_flag("--mkdir", a->mkdir, "Create --out's folder if it does not exist (otherwise that is an error)");
}

int figure_options(const FigureOutputArgs& a, ui::FigureOptions* out) {
  if (const std::string bad = ui::bad_extension_message(a.out); !bad.empty()) {
    fmt::print(stderr, "error: {}\n", bad);
    return kUsage;
  }
  // A typo in a folder name should not silently create a new folder.
  const std::filesystem::path folder = std::filesystem::path(a.out).parent_path();
  if (std::error_code ec; !folder.empty() && !a.mkdir && !std::filesystem::is_directory(folder, ec)) {
    if (std::filesystem::exists(folder, ec))
      fmt::print(stderr, "error: --out {}: '{}' is not a folder\n", a.out, folder.string());
    else
      fmt::print(stderr, "error: --out {}: the folder '{}' does not exist (create it, or pass --mkdir)\n", a.out,
                 folder.string());
    return kUsage;
  }
  ui::FigureOptions o;
  try {
    o.width_in = a.width_in ? *a.width_in : a.column == "double" ? ui::kDoubleColumnIn : ui::kSingleColumnIn;
    o.font_pt = a.font_pt;
    o.dpi = a.dpi;
    o.layers = a.layers.empty() ? ui::default_layers(o.width_in) : ui::parse_layers(a.layers);
    if (a.crop == "auto")
      o.crop_auto = true;
    else if (!a.crop.empty())
      o.crop = ui::parse_crop(a.crop);
    o.panels = ui::parse_panels(a.panels);
    o.font_file = a.font.empty() ? ui::default_font_file() : a.font;
    o.check();
  } catch (const std::invalid_argument& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return kUsage;
  }
  if (const std::string problem = ui::font_file_problem(o.font_file); !problem.empty()) {
    fmt::print(stderr, "error: {}\n", problem);
    return kBadInput;
  }
  *out = o;
  return kOk;
}

void write_figure(const ui::DisplayList& fig, const ui::FontMetrics& metrics, const ui::FigureOptions& o,
                  const std::string& study_root, const std::string& path, const std::string& title) {
  const ui::FigureFormat format = *ui::figure_format_of(path);
  const std::string bytes = format == ui::FigureFormat::kPng
                                ? figure::render_png(fig, metrics, o.dpi)
                                : ui::render_figure_file(fig, metrics, format, o.dpi, title);
  write_output_file(study_root, path, bytes);
  fmt::print("{}\n", path);
}

}  // namespace ipd::cli
