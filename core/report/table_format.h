// Rendering the cross table (the paper's Table I) as text, CSV, JSON, Markdown or LaTeX.
#pragma once

#include <string>
#include <vector>

#include "core/ipd/ipd.h"
#include "core/report/provenance.h"

namespace ipd {

enum class TableFormat { kText, kCsv, kJson, kMarkdown, kLatex };

struct TableFormatOptions {
  // LaTeX: print each cell's interval ("0.2256 [0.214, 0.238]"); the other formats always show intervals
  // when the cells have them (TableCell::ci_low / ci_high).
  bool latex_ci = false;
  bool booktabs = false;  // LaTeX: \toprule / \midrule / \bottomrule instead of vertical rules and \hline
  // LaTeX: the wide layout (domain and model names spelled out, intervals beside the values) for a table*
  // across both columns; the default is the compact one, which fits one IEEE column (252 pt at 10 pt type)
  // for up to three domains with intervals: domains abbreviated A, B, C with a legend below, intervals on a
  // second line.
  bool latex_wide = false;
  // What the intervals are, for the captions: "95% scene-bootstrap interval, 2,000 resamples, seed 0".
  int resamples = 0;
  double level = 0.95;
  unsigned long long seed = 0;
  double conf_threshold = 0;  // the prediction threshold the table was computed with (JSON)
  // When set, the table says where its numbers come from (hand-pair counts, label fingerprint): JSON a
  // "provenance" object, CSV the same columns on every row, Markdown and LaTeX a footnote line under the
  // table (the text table's caller prints it with its other notes).
  const Provenance* provenance = nullptr;

  // Empty when usable; otherwise the field that is wrong and the accepted range, in one sentence.
  std::string validate() const;
  // Throws std::invalid_argument("table format options: " + validate()) when not usable.
  void check() const;
};

// Why a shown cell has no interval: "1 scene: no interval" (or "0 scenes") when fewer than two of its
// scenes have pairs (a scene bootstrap needs two); "" otherwise.
std::string no_interval_reason(const TableCell& cell);

bool parse_table_format(const std::string& name, TableFormat* out);

// A footnote's mark, k from 1: "¹", "²", ... "¹⁰".
std::string footnote_mark(int k);
// The one mark of a shown cell that is not a number, with its footnote's number: "–¹". The text and
// Markdown tables, the table figure and ipd-studio's table all mark such cells with it and say why in
// footnote k (LaTeX spells the same mark "--$^{k}$").
std::string no_value_mark(int k);
// The footnote number (from 1) of `reason` among the distinct reasons met so far in cell order, adding it
// when new: the numbering every table of cells uses.
int footnote_number(std::vector<std::string>* reasons, const std::string& reason);

// One IEEE column at 10 pt type, and both columns (table*), in points.
constexpr double kIeeeColumnPt = 252, kIeeeTextWidthPt = 516;
// The LaTeX layouts. Each prints only the domain pairs some row's detector was trained on (a pair no row
// trained on is "--" in every row; the legend counts them). kWide: --latex-wide's, names spelled out, for a
// table*. The compact ones (letters A, B, ... with a legend, intervals on a second line): kPairColumns, the
// paper's orientation, written when it fits one IEEE column; else kPairRows (domain pairs as rows, one column
// per detector) when that is narrower, as with four or five domains and one to three detectors.
enum class LatexLayout { kWide, kPairColumns, kPairRows };
LatexLayout latex_layout(const CrossTable& table, const TableFormatOptions& options);
// The width a layout's tabular takes at 10 pt Computer Modern, estimated from the glyph widths (within a few
// points).
double latex_layout_width_pt(const CrossTable& table, const TableFormatOptions& options, LatexLayout layout);
// The width of the layout `format_table` writes for `options`.
double latex_table_width_pt(const CrossTable& table, const TableFormatOptions& options);
// What `ipd table --format latex` says about where its table fits, true for every layout: "" when the table
// fits where it is meant to go (one column; a table* for --latex-wide); which layout does fit otherwise (or
// that none does, and what to leave out); and, when the domain pairs were turned into rows, why.
std::string latex_fit_advice(const CrossTable& table, const TableFormatOptions& options);
std::string format_table(const CrossTable& table, TableFormat format, const TableFormatOptions& options = {});

}  // namespace ipd
