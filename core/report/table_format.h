// Rendering the cross table (the paper's Table I) as text, CSV, JSON, Markdown or LaTeX.
#pragma once

#include <string>

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
  // What the intervals are, for the captions: "95% scene-bootstrap interval, 2000 resamples, seed 0".
  int resamples = 0;
  double level = 0.95;
  unsigned long long seed = 0;
  double conf_threshold = 0;  // the prediction threshold the table was computed with (JSON)
  // JSON: a "provenance" object (hand-pair counts, edited scenes, label fingerprint) when set.
  const Provenance* provenance = nullptr;
};

// Why a shown cell has no interval: "1 scene: no interval" (or "0 scenes") when fewer than two of its
// scenes have pairs (a scene bootstrap needs two); "" otherwise.
std::string no_interval_reason(const TableCell& cell);

bool parse_table_format(const std::string& name, TableFormat* out);

// One IEEE column at 10 pt type, and both columns (table*), in points.
constexpr double kIeeeColumnPt = 252, kIeeeTextWidthPt = 516;
// The width the LaTeX tabular of `options` (compact or wide) takes at 10 pt Computer Modern, estimated from
// the glyph widths (within a few points): to say when only the wide layout across both columns fits.
double latex_table_width_pt(const CrossTable& table, const TableFormatOptions& options);
std::string format_table(const CrossTable& table, TableFormat format, const TableFormatOptions& options = {});

}  // namespace ipd
