#include "ui/figures/figure_export.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "core/io/label_io.h"
#include "core/session/session_statistics.h"
#include "core/util/atomic_file.h"
#include "core/util/contained_file.h"
#include "ui/figures/figure_study.h"

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

const char* const kFigureKinds[7] = {"pairs",        "registration", "table",  "compare",
                                     "distribution", "breakdown",    "gallery"};

bool is_figure_kind(const std::string& kind) {
  return std::find(std::begin(kFigureKinds), std::end(kFigureKinds), kind) != std::end(kFigureKinds);
}

namespace {

// The session's labels with its threshold applied, as `ipd figure --conf` loads them (the session keeps
// every prediction and filters when it scores).
StudyLabels thresholded_labels(const Session& session) {
  StudyLabels labels = session.labels();
  for (auto& [domain, models] : labels.predictions)
    for (auto& [model, stems] : models)
      for (auto& [stem, file] : stems) keep_confident(&file, session.conf_threshold());
  return labels;
}

std::string study_figure_file(const Session& session, const ExportRequest& r, FigureFormat format) {
  StudyFigureRequest sr;
  sr.kind = r.kind;
  sr.model = session.model();
  sr.ref = r.ref;
  sr.a = r.kind == "compare" ? r.a : session.left_domain();
  sr.b = r.kind == "compare" ? r.b : session.right_domain();
  sr.bootstrap.seed = session.study().config.registration.seed;  // as `ipd table` without --seed
  sr.conf_threshold = session.conf_threshold();
  sr.count = r.gallery_count;
  sr.gallery_sort = r.gallery_sort;
  CrossTable table = session_table(session);
  add_confidence_intervals(&table, sr.bootstrap, 1);
  StudyLabels labels;
  if (r.kind == "breakdown" || r.kind == "gallery")
    labels = thresholded_labels(session);
  else
    labels.study = session.study();
  const FontMetrics metrics(r.options.font_file.empty() ? default_font_file() : r.options.font_file);
  DisplayList fig(metrics);
  // Its table has no pairings to count: the session's edits, over the domain pairs the figure draws.
  const Provenance provenance = session_provenance(session, study_figure_domain_pairs(session.study(), sr));
  const std::string title = draw_study_figure(fig, table, labels, sr, r.options, &provenance);
  return render_figure_file(fig, metrics, format, r.options.dpi, title);
}

}  // namespace

std::string export_figure(const Session& session, const ExportRequest& r) {
  try {
    const auto format = figure_format_of(r.path);
    if (!format) return bad_extension_message(r.path);
    if (!is_figure_kind(r.kind)) return "export failed: unknown figure kind '" + r.kind + "'";
    if (is_study_figure_kind(r.kind)) {
      write_output_file(session.study().root, r.path, study_figure_file(session, r, *format));
      return "exported " + r.path;
    }
    if (r.scene < 0 || r.scene >= int(session.scenes().size())) return "export failed: no scene selected";
    SceneFigureInput in = scene_input_from_session(session, r.scene);
    if (r.kind == "pairs") load_pictures(in, session.study());
    write_output_file(session.study().root, r.path, scene_figure_file(r.kind, in, r.options, *format));
    return "exported " + r.path;
  } catch (const std::exception& e) {
    return std::string("export failed: ") + e.what();
  }
}

}  // namespace ipd::ui
