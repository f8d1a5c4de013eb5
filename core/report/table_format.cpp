#include "core/report/table_format.h"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "core/report/csv.h"
#include "core/report/markdown.h"
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

namespace {

std::string column_title(const std::pair<std::string, std::string>& c) { return c.first + " - " + c.second; }
std::string row_title(const ModelInfo& m) {
  return m.trained_on.empty() ? m.name : fmt::format("{} ({})", m.name, m.trained_on);
}

// "–" for cells that don't involve the training domain (as the paper), "n/a" when nothing was measured.
std::string cell_text(const TableCell& c, const char* dash) {
  if (!c.involves_training_domain) return dash;
  if (std::isnan(c.ipd)) return "n/a";
  return fmt::format("{:.4f}", c.ipd);
}

// The distinct reasons of cells that are not a number (TableCell::no_value_reason), in cell order: cell k's
// footnote is its reason's position + 1.
std::vector<std::string> footnotes(const CrossTable& t) {
  std::vector<std::string> out;
  for (const auto& c : t.cells)
    if (c.involves_training_domain && !c.no_value_reason.empty() &&
        std::find(out.begin(), out.end(), c.no_value_reason) == out.end())
      out.push_back(c.no_value_reason);
  return out;
}

int footnote_of(const std::vector<std::string>& notes, const TableCell& c) {
  if (!c.involves_training_domain || c.no_value_reason.empty()) return 0;
  return static_cast<int>(std::find(notes.begin(), notes.end(), c.no_value_reason) - notes.begin()) + 1;
}

// The text of a cell: a number, or "–" with the mark of its footnote when it is not one for a reason.
std::string marked_cell_text(const TableCell& c, const char* dash, const std::vector<std::string>& notes) {
  const int k = footnote_of(notes, c);
  return k > 0 ? no_value_mark(k) : cell_text(c, dash);
}

std::string footnote_lines(const std::vector<std::string>& notes) {
  std::string out;
  for (size_t k = 0; k < notes.size(); ++k) out += footnote_mark(static_cast<int>(k) + 1) + " " + notes[k] + "\n";
  return out;
}

bool has_ci(const TableCell& c) { return !std::isnan(c.ci_low) && !std::isnan(c.ci_high); }

// " [0.214, 0.238]" when the cell has an interval and is shown.
std::string ci_text(const TableCell& c) {
  if (!c.involves_training_domain || std::isnan(c.ipd) || !has_ci(c)) return {};
  return fmt::format(" [{:.3f}, {:.3f}]", c.ci_low, c.ci_high);
}

// " (15 pairs)", " (15 pairs; 1 scene: no interval)" when intervals were asked for and the cell can't have one.
std::string pairs_text(const TableCell& c, const TableFormatOptions& o) {
  if (!c.involves_training_domain || std::isnan(c.ipd)) return {};
  const std::string why = o.resamples > 0 && !has_ci(c) ? no_interval_reason(c) : std::string();
  return fmt::format(" ({} pairs{}{})", grouped_thousands(c.pairs), why.empty() ? "" : "; ", why);
}

bool any_ci(const CrossTable& t) {
  return std::any_of(t.cells.begin(), t.cells.end(), [](const TableCell& c) { return has_ci(c); });
}

std::string ci_caption(const TableFormatOptions& o) {
  return fmt::format("[low, high]: {:g}% scene-bootstrap percentile interval ({} resamples of scenes, seed {})",
                     100 * o.level, grouped_thousands(o.resamples), o.seed);
}

std::string number_or_empty(double v) { return std::isnan(v) ? std::string() : fmt::format("{:.6f}", v); }
nlohmann::json number_or_null(double v) { return std::isnan(v) ? nlohmann::json(nullptr) : nlohmann::json(v); }

// The best (lowest) shown value of a row, bolded in Markdown and LaTeX as the paper does.
double row_best(const CrossTable& t, size_t row) {
  double best = INFINITY;
  for (size_t c = 0; c < t.columns.size(); ++c) {
    const auto& cell = t.cells[row * t.columns.size() + c];
    if (cell.involves_training_domain && !std::isnan(cell.ipd)) best = std::min(best, cell.ipd);
  }
  return best;
}

std::string latex_escape(const std::string& s) {
  std::string o;
  for (char ch : s) {
    if (ch == '\\')
      o += "\\textbackslash{}";
    else if (ch == '~')
      o += "\\textasciitilde{}";
    else if (ch == '^')
      o += "\\textasciicircum{}";
    else if (ch == '_' || ch == '&' || ch == '%' || ch == '#' || ch == '$' || ch == '{' || ch == '}')
      o += std::string("\\") + ch;
    else
      o += ch;
  }
  return o;
}

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

// How to read the numbers, under either LaTeX layout: a table in a paper must say it without its caption.
std::string latex_reading(bool ci, const TableFormatOptions& o) {
  std::string s =
      "IPD: mean $|$performance-value difference$|$ over matched rock pairs, lower is better; bold: the "
      "row's best; --: pair not involving the training domain.";
  if (ci) s += " " + latex_escape(ci_caption(o)) + ".";
  return s;
}

std::string latex_table(const CrossTable& t, const TableFormatOptions& o) {
  const size_t nc = t.columns.size();
  const bool bt = o.booktabs;
  const char* rule = bt ? "" : "\\hline\n";
  std::string out = "% IPD cross table, generated by `ipd table --format latex`\n";
  if (o.latex_ci && any_ci(t)) out += "% " + ci_caption(o) + "\n";
  if (bt) {
    out += "% needs \\usepackage{booktabs}\n\\begin{tabular}{l";
    for (size_t k = 0; k < nc; ++k) out += "c";
    out += "}\n\\toprule\n";
    out += fmt::format(" & \\multicolumn{{{}}}{{c}}{{$\\downarrow$ Instance Performance Difference (IPD)}} \\\\\n", nc);
    out += fmt::format("\\cmidrule(lr){{2-{}}}\n", nc + 1);
  } else {
    out += "\\begin{tabular}{|c|";
    for (size_t k = 0; k < nc; ++k) out += "c|";
    out += "}\n\\hline\n";
    out += fmt::format(
        " & \\multicolumn{{{}}}{{c|}}{{$\\downarrow$ Instance Performance Difference (IPD)}} \\\\\n\\hline\n", nc);
  }
  out += "Train\\textbackslash Eval";
  // Single bars: the paper's \| prints a double bar (a norm), not an absolute value.
  for (const auto& c : t.columns) out += " & $|$" + latex_escape(c.first) + " $-$ " + latex_escape(c.second) + "$|$";
  out += " \\\\\n";
  out += bt ? "\\midrule\n" : rule;
  const std::vector<std::string> notes = footnotes(t);
  for (size_t r = 0; r < t.models.size(); ++r) {
    const double best = row_best(t, r);
    out += latex_escape(row_title(t.models[r]));
    for (size_t c = 0; c < nc; ++c) {
      const auto& cell = t.cells[r * nc + c];
      const int note = footnote_of(notes, cell);
      // an en dash in LaTeX, as the text table's "–"
      const std::string s = note > 0 ? fmt::format("--$^{{{}}}$", note) : cell_text(cell, "--");
      out += " & " + (cell.involves_training_domain && cell.ipd == best ? "\\textbf{" + s + "}" : s);
      if (o.latex_ci) out += ci_text(cell);
    }
    out += " \\\\\n";
    if (!bt) out += rule;
  }
  if (bt) out += "\\bottomrule\n";
  out += "\\end{tabular}\n";
  out += "\\par\\smallskip{\\footnotesize " + latex_reading(o.latex_ci && any_ci(t), o) + "\\par}\n";
  for (size_t k = 0; k < notes.size(); ++k)
    out += fmt::format("\\par{{\\footnotesize $^{{{}}}$ {}}}\n", k + 1, latex_escape(notes[k]));
  return out;
}

// The compact LaTeX layout (TableFormatOptions::latex_wide): domains as letters in study order, rows named
// by their training domain's letter when that is unambiguous (else M1, M2, ...), intervals on a second
// line, the legend below the tabular (it wraps to the column).
struct CompactNames {
  std::vector<std::string> domains;  // A, B, C, ... -> name
  std::vector<std::string> rows;     // per model
  bool rows_by_domain = false;
};

std::string letter(size_t k) { return k < 26 ? std::string(1, char('A' + k)) : fmt::format("D{}", k + 1); }

CompactNames compact_names(const CrossTable& t) {
  CompactNames n;
  const auto index = [&](const std::string& d) {
    const auto it = std::find(n.domains.begin(), n.domains.end(), d);
    if (it != n.domains.end()) return size_t(it - n.domains.begin());
    n.domains.push_back(d);
    return n.domains.size() - 1;
  };
  for (const auto& [a, b] : t.columns) index(a), index(b);
  std::vector<std::string> trained;
  for (const ModelInfo& m : t.models) trained.push_back(m.trained_on);
  std::vector<std::string> sorted = trained;
  std::sort(sorted.begin(), sorted.end());
  n.rows_by_domain = !t.models.empty() && std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end() &&
                     std::all_of(trained.begin(), trained.end(), [&](const std::string& d) {
                       return std::find(n.domains.begin(), n.domains.end(), d) != n.domains.end();
                     });
  for (size_t r = 0; r < t.models.size(); ++r)
    n.rows.push_back(n.rows_by_domain ? letter(index(trained[r])) : fmt::format("M{}", r + 1));
  return n;
}

std::string compact_column(const CompactNames& n, const std::pair<std::string, std::string>& c) {
  const auto letter_of = [&](const std::string& d) {
    return letter(size_t(std::find(n.domains.begin(), n.domains.end(), d) - n.domains.begin()));
  };
  return "$|$" + letter_of(c.first) + "$-$" + letter_of(c.second) + "$|$";
}

std::string compact_interval(const TableCell& c) {
  if (!c.involves_training_domain || std::isnan(c.ipd) || !has_ci(c)) return {};
  return fmt::format("{{[}}{:.3f}, {:.3f}{{]}}", c.ci_low, c.ci_high);  // braced: "[" after \\ is an argument
}

std::string latex_compact_table(const CrossTable& t, const TableFormatOptions& o) {
  const size_t nc = t.columns.size();
  const bool bt = o.booktabs, ci = o.latex_ci && any_ci(t);
  const CompactNames n = compact_names(t);
  std::string out = "% IPD cross table, generated by `ipd table --format latex` (one column; --latex-wide: table*)\n";
  if (ci) out += "% " + ci_caption(o) + "\n";
  if (bt) out += "% needs \\usepackage{booktabs}\n";
  out += bt ? "\\begin{tabular}{@{}l" + std::string(nc, 'c') + "@{}}\n\\toprule\n" : "\\begin{tabular}{|l|";
  if (!bt) {
    for (size_t k = 0; k < nc; ++k) out += "c|";
    out += "}\n\\hline\n";
  }
  out += fmt::format("Train & \\multicolumn{{{}}}{{c{}}}{{$\\downarrow$ IPD}} \\\\\n", nc, bt ? "" : "|");
  out += bt ? fmt::format("\\cmidrule(lr){{2-{}}}\n", nc + 1) : "";
  for (const auto& c : t.columns) out += " & " + compact_column(n, c);
  out += " \\\\\n";
  out += bt ? "\\midrule\n" : "\\hline\n";
  const std::vector<std::string> notes = footnotes(t);
  for (size_t r = 0; r < t.models.size(); ++r) {
    const double best = row_best(t, r);
    out += n.rows[r];
    for (size_t c = 0; c < nc; ++c) {
      const auto& cell = t.cells[r * nc + c];
      const int note = footnote_of(notes, cell);  // a cell that is not a number says why below
      const std::string s = note > 0 ? fmt::format("--$^{{{}}}$", note) : cell_text(cell, "--");
      out += " & " + (cell.involves_training_domain && cell.ipd == best ? "\\textbf{" + s + "}" : s);
    }
    out += " \\\\\n";
    if (ci) {
      for (size_t c = 0; c < nc; ++c) out += " & " + compact_interval(t.cells[r * nc + c]);
      out += " \\\\\n";
    }
    if (!bt) out += "\\hline\n";
  }
  out += bt ? "\\bottomrule\n\\end{tabular}\n" : "\\end{tabular}\n";
  // The legend: what the letters stand for, what the rows are, what the numbers mean.
  std::string legend;
  for (size_t k = 0; k < n.domains.size(); ++k)
    legend += (k ? ", " : "") + letter(k) + ": " + latex_escape(n.domains[k]);
  legend += n.rows_by_domain ? ". Rows: the detector trained on " : ". Rows: ";
  for (size_t r = 0; r < t.models.size(); ++r) {
    legend += (r ? (n.rows_by_domain ? ", " : "; ") : "") + n.rows[r] + (n.rows_by_domain ? " (" : ": ") +
              latex_escape(t.models[r].name);
    if (!n.rows_by_domain && !t.models[r].trained_on.empty())
      legend += " (trained on " + latex_escape(t.models[r].trained_on) + ")";
    legend += n.rows_by_domain ? ")" : "";
  }
  legend += ". " + latex_reading(ci, o);
  out += "\\par\\smallskip{\\footnotesize " + legend + "\\par}\n";
  for (size_t k = 0; k < notes.size(); ++k)
    out += fmt::format("\\par{{\\footnotesize $^{{{}}}$ {}}}\n", k + 1, latex_escape(notes[k]));
  return out;
}

// Computer Modern Roman 10 pt advance widths (cmr10/cmbx10, points), enough to tell a table's width within
// a few points.
double cm_width(const std::string& s, bool bold) {
  double w = 0;
  for (unsigned char ch : s) {
    if (ch >= '0' && ch <= '9')
      w += bold ? 5.75 : 5.0;
    else if (ch == '.' || ch == ',' || ch == '[' || ch == ']' || ch == '|' || ch == ':' || ch == ';')
      w += 2.78;
    else if (ch == ' ')
      w += 3.33;
    else if (ch == '(' || ch == ')')
      w += 3.89;
    else if (ch == '-')
      w += 3.33;
    else if (ch >= 'A' && ch <= 'Z')
      w += bold ? 8.3 : 7.3;
    else if ((ch & 0xC0) == 0x80)
      continue;  // UTF-8 continuation
    else
      w += bold ? 5.6 : 4.9;  // lower case and the rest, on average
  }
  return w;
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

double latex_table_width_pt(const CrossTable& t, const TableFormatOptions& o) {
  const size_t nc = t.columns.size();
  const double sep = 12, rule = 0.4;  // 2 \tabcolsep, one vertical rule
  const bool ci = o.latex_ci && any_ci(t);
  const CompactNames n = compact_names(t);
  std::vector<double> w(nc + 1, 0);
  const auto fit = [&](size_t col, double v) { w[col] = std::max(w[col], v); };
  const double minus = 7.78 + 2 * 2.22;  // $-$ with its binary spacing
  fit(0, cm_width(o.latex_wide ? "Train\\Eval" : "Train", false));
  for (size_t c = 0; c < nc; ++c) {
    const auto& [a, b] = t.columns[c];
    fit(c + 1, o.latex_wide ? cm_width("||" + a + b, false) + minus : 2 * 2.78 + 2 * 7.3 + minus);
  }
  for (size_t r = 0; r < t.models.size(); ++r) {
    fit(0, cm_width(o.latex_wide ? row_title(t.models[r]) : n.rows[r], false));
    for (size_t c = 0; c < nc; ++c) {
      const TableCell& cell = t.cells[r * nc + c];
      const double value = cm_width(cell_text(cell, "--"), cell.involves_training_domain);
      const double interval = ci ? cm_width(ci_text(cell), false) : 0;
      fit(c + 1, o.latex_wide ? value + (o.latex_ci ? interval : 0) : std::max(value, interval - 3.33));
    }
  }
  double total = o.booktabs ? -sep : (nc + 2) * rule;  // booktabs' @{} drops the outer padding
  for (double v : w) total += v + sep;
  // The spanning "IPD" header widens the value columns when it is the wider.
  const double header =
      o.latex_wide ? cm_width("Instance Performance Difference (IPD)", false) + 10 : cm_width("IPD", false) + 10;
  double values = 0;
  for (size_t c = 1; c <= nc; ++c) values += w[c] + sep;
  return total + std::max(0.0, header + sep - values);
}

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
      std::string out = o.latex_wide ? latex_table(t, o) : latex_compact_table(t, o);
      // A footnote line under the table: it wraps to the column like the legend.
      if (o.provenance) out += "\\par{\\footnotesize " + latex_escape(provenance_note(*o.provenance)) + "\\par}\n";
      return out;
    }
  }
  return {};
}

}  // namespace ipd
