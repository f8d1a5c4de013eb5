#include "core/report/table_format.h"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "core/report/csv.h"
#include "core/report/markdown.h"
#include "core/report/table_cells.h"
#include "core/stats/study_statistics.h"
#include "core/util/json_output.h"
#include "core/util/number_text.h"

namespace ipd {

std::string no_interval_reason(const TableCell& cell) {
  if (!cell.involves_training_domain || std::isnan(cell.ipd)) return {};
  const auto scenes =
      std::count_if(cell.per_scene.begin(), cell.per_scene.end(), [](const SceneIpd& s) { return s.pairs > 0; });
  if (scenes >= 2) return {};
  return fmt::format("{} scene{}: no interval", scenes, scenes == 1 ? "" : "s");
}

std::string footnote_mark(int k) {
  static const char* const kDigits[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
  const std::string digits = std::to_string(k);
  std::string out;
  for (char ch : digits) out += kDigits[ch - '0'];
  return out;
}

std::string no_value_mark(int k) { return "–" + footnote_mark(k); }

int footnote_number(std::vector<std::string>* reasons, const std::string& reason) {
  auto it = std::find(reasons->begin(), reasons->end(), reason);
  if (it == reasons->end()) it = reasons->insert(reasons->end(), reason);
  return static_cast<int>(it - reasons->begin()) + 1;
}

bool parse_table_format(const std::string& name, TableFormat* out) {
  static const std::pair<const char*, TableFormat> kNames[] = {{"text", TableFormat::kText},
                                                               {"csv", TableFormat::kCsv},
                                                               {"json", TableFormat::kJson},
                                                               {"markdown", TableFormat::kMarkdown},
                                                               {"latex", TableFormat::kLatex}};
  for (const auto& [n, f] : kNames)
    if (name == n) {
      *out = f;
      return true;
    }
  return false;
}

using namespace table_cells;

namespace {

std::string number_or_empty(double v) { return std::isnan(v) ? std::string() : fmt::format("{:.6f}", v); }
nlohmann::json number_or_null(double v) { return std::isnan(v) ? nlohmann::json(nullptr) : nlohmann::json(v); }

std::string text_table(const CrossTable& t, const TableFormatOptions& o) {
  std::vector<std::vector<std::string>> grid;
  std::vector<std::string> head = {"train \\ eval (IPD, lower is better)"};
  for (const auto& c : t.columns) head.push_back("|" + column_title(c) + "|");
  grid.push_back(head);
  const std::vector<std::string> notes = footnotes(t);
  for (size_t r = 0; r < t.models.size(); ++r) {
    std::vector<std::string> row = {row_title(t.models[r])};
    for (size_t c = 0; c < t.columns.size(); ++c) {
      const auto& cell = t.cells[r * t.columns.size() + c];
      row.push_back(marked_cell_text(cell, "–", notes) + ci_text(cell) + pairs_text(cell, o));
    }
    grid.push_back(row);
  }
  std::vector<size_t> width(head.size(), 0);
  auto display_len = [](const std::string& s) {  // UTF-8 aware enough for "–"
    size_t n = 0;
    for (unsigned char ch : s) n += (ch & 0xC0) != 0x80;
    return n;
  };
  for (const auto& row : grid)
    for (size_t k = 0; k < row.size(); ++k) width[k] = std::max(width[k], display_len(row[k]));
  std::string out;
  for (const auto& row : grid) {
    for (size_t k = 0; k < row.size(); ++k) {
      out += row[k] + std::string(width[k] - display_len(row[k]) + (k + 1 < row.size() ? 2 : 0), ' ');
    }
    while (!out.empty() && out.back() == ' ') out.pop_back();
    out += '\n';
  }
  if (any_ci(t)) out += ci_caption(o) + "\n";
  return out + footnote_lines(notes);
}

nlohmann::json distribution_json(const TableCell& c) {
  const SceneDistribution d = scene_distribution(c);
  nlohmann::json worst = nlohmann::json::array();
  for (const auto& [stem, v] : d.worst) worst.push_back({{"scene", stem}, {"ipd", v}});
  return {{"scenes", d.scenes},
          {"min", number_or_null(d.min)},
          {"q1", number_or_null(d.q1)},
          {"median", number_or_null(d.median)},
          {"q3", number_or_null(d.q3)},
          {"max", number_or_null(d.max)},
          {"worst", worst}};
}

std::string csv_table(const CrossTable& t, const TableFormatOptions& o) {
  std::string out =
      "model,trained_on,a,b,ipd,pairs,unpaired_a,unpaired_b,scenes,involves_training_domain,ci_low,ci_high,se,"
      "reason";
  // Provenance: the same columns on every row (provenance_csv_fields).
  const auto prov =
      o.provenance ? provenance_csv_fields(*o.provenance) : std::vector<std::pair<std::string, std::string>>();
  for (const auto& [name, value] : prov) out += "," + name;
  out += "\n";
  for (const auto& c : t.cells) {
    std::vector<std::string> fields = {c.model,
                                       c.trained_on,
                                       c.a,
                                       c.b,
                                       number_or_empty(c.ipd),
                                       std::to_string(c.pairs),
                                       std::to_string(c.unpaired_a),
                                       std::to_string(c.unpaired_b),
                                       std::to_string(c.scenes),
                                       c.involves_training_domain ? "true" : "false",
                                       number_or_empty(c.ci_low),
                                       number_or_empty(c.ci_high),
                                       number_or_empty(c.se),
                                       c.no_value_reason};
    for (const auto& [name, value] : prov) fields.push_back(value);
    out += csv_row(fields);
  }
  return out;
}

}  // namespace

std::string TableFormatOptions::validate() const {
  if (resamples < 0) return fmt::format("resamples must be >= 0 (0: no intervals), got {}", resamples);
  if (!(level > 0 && level < 1)) return fmt::format("level must be in (0, 1), got {}", level);
  if (!(conf_threshold >= 0 && conf_threshold <= 1))
    return fmt::format("conf_threshold must be in [0, 1], got {}", conf_threshold);
  return {};
}

void TableFormatOptions::check() const {
  if (const std::string problem = validate(); !problem.empty())
    throw std::invalid_argument("table format options: " + problem);
}

std::string format_table(const CrossTable& t, TableFormat format, const TableFormatOptions& o) {
  o.check();
  const size_t nc = t.columns.size();
  switch (format) {
    case TableFormat::kText:
      return text_table(t, o);
    case TableFormat::kCsv:
      return csv_table(t, o);
    case TableFormat::kJson: {
      nlohmann::json j;
      j["cells"] = nlohmann::json::array();
      for (const auto& c : t.cells) {
        nlohmann::json cell = {{"model", c.model},
                               {"trained_on", c.trained_on},
                               {"a", c.a},
                               {"b", c.b},
                               {"pairs", c.pairs},
                               {"unpaired_a", c.unpaired_a},
                               {"unpaired_b", c.unpaired_b},
                               {"scenes", c.scenes},
                               {"involves_training_domain", c.involves_training_domain}};
        cell["ipd"] = number_or_null(c.ipd);
        cell["ci_low"] = number_or_null(c.ci_low);
        cell["ci_high"] = number_or_null(c.ci_high);
        cell["se"] = number_or_null(c.se);
        if (c.missing_predictions)
          cell["missing_predictions"] = true;
        else if (!c.no_value_reason.empty())
          cell["reason"] = c.no_value_reason;
        else
          cell["scene_ipd"] = distribution_json(c);
        j["cells"].push_back(cell);
      }
      j["bootstrap"] = {{"resamples", o.resamples}, {"level", o.level}, {"seed", o.seed}};
      j["conf_threshold"] = o.conf_threshold;
      j["warnings"] = t.warnings;
      if (o.provenance) j["provenance"] = provenance_json(*o.provenance);
      return dump_json_output(j, 2) + "\n";
    }
    case TableFormat::kMarkdown: {
      std::string out = "| Train \\ Eval |";
      for (const auto& c : t.columns) out += " \\|" + markdown_cell(column_title(c)) + "\\| |";
      out += "\n|---|";
      for (size_t k = 0; k < nc; ++k) out += "---:|";
      out += "\n";
      const std::vector<std::string> notes = footnotes(t);
      for (size_t r = 0; r < t.models.size(); ++r) {
        const double best = row_best(t, r);
        out += "| " + markdown_cell(row_title(t.models[r])) + " |";
        for (size_t c = 0; c < nc; ++c) {
          const auto& cell = t.cells[r * nc + c];
          const std::string s = marked_cell_text(cell, "–", notes);
          out +=
              (cell.involves_training_domain && cell.ipd == best ? " **" + s + "**" : " " + s) + ci_text(cell) + " |";
        }
        out += "\n";
      }
      out += "\nIPD: mean |performance-value difference| over matched rock pairs; lower is better.";
      if (any_ci(t)) out += " " + ci_caption(o) + ".";
      out += "\n";
      if (!notes.empty()) out += "\n" + footnote_lines(notes);
      if (o.provenance) out += "\n" + provenance_note(*o.provenance) + "\n";
      return out;
    }
    case TableFormat::kLatex: {
      std::string out = latex_cross_table(t, o);
      // A footnote line under the table: it wraps to the column like the legend.
      if (o.provenance) out += "\\par{\\footnotesize " + latex_text(provenance_note(*o.provenance)) + "\\par}\n";
      return out;
    }
  }
  return {};
}

}  // namespace ipd
