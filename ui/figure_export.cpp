#include "figure_export.h"

#include <fmt/format.h>

#include <filesystem>

#include "ipd/atomic_file.h"

namespace ipd::ui {

DisplayList scene_figure(const std::string& kind, const SceneFigureInput& in, const FigureOptions& options,
                         const FontMetrics& metrics) {
  DisplayList out(metrics);
  draw_scene_figure(out, kind, in, options);
  return out;
}

std::string scene_figure_file(const std::string& kind, const SceneFigureInput& in, const FigureOptions& options,
                              FigureFormat format) {
  const FontMetrics metrics(options.font_file.empty() ? default_font_file() : options.font_file);
  const DisplayList fig = scene_figure(kind, in, options, metrics);
  return render_figure_file(fig, metrics, format, options.dpi, fmt::format("{} {} vs {}", in.stem, in.a, in.b));
}

std::string bad_extension_message(const std::string& path) {
  if (figure_format_of(path)) return {};
  const std::string ext = std::filesystem::path(path).extension().string();
  return fmt::format("{}: unknown figure format '{}'; the file name must end in .pdf, .svg or .png", path,
                     ext.empty() ? "(no extension)" : ext);
}

std::string export_scene_figure(const Session& session, const ExportRequest& r) {
  try {
    const auto format = figure_format_of(r.path);
    if (!format) return bad_extension_message(r.path);
    if (r.scene < 0 || r.scene >= int(session.scenes().size())) return "export failed: no scene selected";
    SceneFigureInput in = scene_input_from_session(session, r.scene);
    if (r.kind == "pairs") load_pictures(in, session.study());
    write_file_atomically(r.path, scene_figure_file(r.kind, in, r.options, *format));
    return "exported " + r.path;
  } catch (const std::exception& e) {
    return std::string("export failed: ") + e.what();
  }
}

}  // namespace ipd::ui
