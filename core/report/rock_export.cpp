#include "core/report/rock_export.h"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "core/report/csv.h"
#include "core/session/audit.h"
#include "core/stats/image_metrics.h"
#include "core/stats/study_statistics.h"
#include "core/util/json_output.h"

namespace ipd {

namespace {
// A class by name where a file names it, else by number: what a reader of the rows groups by.
std::string class_word(const StudyLabels& labels, int cls) {
  const auto& names = labels.study.classes.names;
  return cls >= 0 && static_cast<size_t>(cls) < names.size() && !names[cls].empty() ? names[cls] : std::to_string(cls);
}
}  // namespace

std::vector<RockRow> rock_rows(const StudyLabels& labels, const CrossTable& table, const RockExportOptions& options) {
  std::vector<RockRow> rows;
  const size_t nc = table.columns.size();
  std::vector<std::pair<int, int>> size_of_b(nc);
  for (size_t c = 0; c < nc; ++c) size_of_b[c] = domain_image_size(labels.study, table.columns[c].second);
  for (size_t k = 0; k < table.cells.size(); ++k) {
    const TableCell& cell = table.cells[k];
    if (cell.missing_predictions) continue;
    const size_t column = k % nc;
    const auto& pairings = table.pairings[column];
    for (size_t s = 0; s < cell.per_scene.size(); ++s) {
      const SceneIpd& sc = cell.per_scene[s];
      const ScenePairing& pairing = pairings[s];
      const auto& ga = labels.gt_of(cell.a, sc.stem).boxes;
      const auto& gb = labels.gt_of(cell.b, sc.stem).boxes;
      RockRow base;
      base.model = cell.model;
      base.trained_on = cell.trained_on;
      base.a = cell.a;
      base.b = cell.b;
      base.scene = sc.stem;
      base.source = pairing.fixed ? "hand" : "auto";
      const auto [w, h] = size_of_b[column];
      SceneAudit audit;
      if (w > 0 && h > 0) audit = audit_pairs(ga, gb, sc.counted, scene_b_from_a(pairing, ga, gb), w, h);
      std::vector<char> paired_a(ga.size(), 0), paired_b(gb.size(), 0);
      for (size_t p = 0; p < sc.counted.size(); ++p) {
        RockRow r = base;
        std::tie(r.index_a, r.index_b) = sc.counted[p];
        paired_a[r.index_a] = paired_b[r.index_b] = 1;
        r.perf_a = sc.perf_a[p];
        r.perf_b = sc.perf_b[p];
        r.diff = std::abs(r.perf_a - r.perf_b);
        r.box_a = ga[r.index_a];
        r.box_b = gb[r.index_b];
        r.cls = class_word(labels, r.box_a.cls);
        if (!audit.pairs.empty()) r.residual_px = audit.pairs[p].residual_px;
        rows.push_back(std::move(r));
      }
      if (!options.unpaired) continue;
      const Task task = labels.study.config.task;
      const PerformanceValues pa =
          performance_values(ga, labels.predictions_of(cell.a, cell.model, sc.stem).boxes, task);
      const PerformanceValues pb =
          performance_values(gb, labels.predictions_of(cell.b, cell.model, sc.stem).boxes, task);
      const auto listed = [](const std::vector<int>& v, size_t i) {
        return std::find(v.begin(), v.end(), static_cast<int>(i)) != v.end();
      };
      for (size_t i = 0; i < ga.size(); ++i) {
        if (paired_a[i]) continue;
        RockRow r = base;
        r.index_a = static_cast<int>(i);
        r.excluded = listed(pairing.excluded_a, i);
        r.perf_a = pa.value[i];
        r.box_a = ga[i];
        r.cls = class_word(labels, r.box_a.cls);
        rows.push_back(std::move(r));
      }
      for (size_t j = 0; j < gb.size(); ++j) {
        if (paired_b[j]) continue;
        RockRow r = base;
        r.index_b = static_cast<int>(j);
        r.excluded = listed(pairing.excluded_b, j);
        r.perf_b = pb.value[j];
        r.box_b = gb[j];
        r.cls = class_word(labels, r.box_b.cls);
        rows.push_back(std::move(r));
      }
    }
  }
  return rows;
}

namespace {
const char* const kColumns[] = {"model",   "trained_on",  "a",      "b",        "scene",       "class",
                                "index_a", "index_b",     "perf_a", "perf_b",   "diff",        "cx_a",
                                "cy_a",    "w_a",         "h_a",    "cx_b",     "cy_b",        "w_b",
                                "h_b",     "residual_px", "source", "excluded", "mask_area_a", "mask_area_b"};

std::string num(double v) { return std::isnan(v) ? std::string() : fmt::format("{:.12g}", v); }
std::string field(const std::string& s) { return csv_field(s); }
// A rock's mask area (normalised: the picture is 1); NaN for a box without an outline or no rock.
double mask_area(bool has, const Box& b) { return has && b.outline ? b.outline->area : std::nan(""); }
}  // namespace

std::string rock_rows_csv(const std::vector<RockRow>& rows, const Provenance* provenance) {
  std::string out, tail;  // tail: the provenance values every row ends with
  for (const char* c : kColumns) out += std::string(out.empty() ? "" : ",") + c;
  if (provenance)
    for (const auto& [name, value] : provenance_csv_fields(*provenance)) {
      out += "," + name;
      tail += "," + field(value);
    }
  out += "\n";
  for (const auto& r : rows) {
    const bool a = r.index_a >= 0, b = r.index_b >= 0;
    auto box = [&](bool has, const Box& x) {
      return has ? fmt::format("{},{},{},{}", num(x.cx), num(x.cy), num(x.w), num(x.h)) : std::string(",,,");
    };
    out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}{}\n", field(r.model), field(r.trained_on),
                       field(r.a), field(r.b), field(r.scene), field(r.cls), a ? std::to_string(r.index_a) : "",
                       b ? std::to_string(r.index_b) : "", num(r.perf_a), num(r.perf_b), num(r.diff), box(a, r.box_a),
                       box(b, r.box_b), num(r.residual_px), r.source, r.excluded ? "true" : "false",
                       num(mask_area(a, r.box_a)), num(mask_area(b, r.box_b)), tail);
  }
  return out;
}

std::string rock_rows_json(const std::vector<RockRow>& rows, const Provenance* provenance) {
  nlohmann::ordered_json prov = nlohmann::ordered_json::object();
  if (provenance) {
    const nlohmann::ordered_json all = provenance_json(*provenance);  // items() refers to it
    for (const auto& [key, value] : all.items())
      if (!value.is_structured()) prov[key] = value;
  }
  auto n = [](double v) { return std::isnan(v) ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(v); };
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const auto& r : rows) {
    const bool a = r.index_a >= 0, b = r.index_b >= 0;
    const double nan = std::nan("");
    out.push_back({{"model", r.model},
                   {"trained_on", r.trained_on},
                   {"a", r.a},
                   {"b", r.b},
                   {"scene", r.scene},
                   {"class", r.cls},
                   {"index_a", a ? nlohmann::ordered_json(r.index_a) : nlohmann::ordered_json(nullptr)},
                   {"index_b", b ? nlohmann::ordered_json(r.index_b) : nlohmann::ordered_json(nullptr)},
                   {"perf_a", n(r.perf_a)},
                   {"perf_b", n(r.perf_b)},
                   {"diff", n(r.diff)},
                   {"cx_a", n(a ? r.box_a.cx : nan)},
                   {"cy_a", n(a ? r.box_a.cy : nan)},
                   {"w_a", n(a ? r.box_a.w : nan)},
                   {"h_a", n(a ? r.box_a.h : nan)},
                   {"cx_b", n(b ? r.box_b.cx : nan)},
                   {"cy_b", n(b ? r.box_b.cy : nan)},
                   {"w_b", n(b ? r.box_b.w : nan)},
                   {"h_b", n(b ? r.box_b.h : nan)},
                   {"residual_px", n(r.residual_px)},
                   {"source", r.source},
                   {"excluded", r.excluded},
                   {"mask_area_a", n(mask_area(a, r.box_a))},
                   {"mask_area_b", n(mask_area(b, r.box_b))}});
    out.back().update(prov);
  }
  return dump_json_output(out, 1) + "\n";
}

}  // namespace ipd
