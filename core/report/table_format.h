// Rendering the cross table (the paper's Table I) as text, CSV, JSON, Markdown or LaTeX.
#pragma once

#include <string>

#include "core/ipd/ipd.h"

namespace ipd {

enum class TableFormat { kText, kCsv, kJson, kMarkdown, kLatex };

struct TableFormatOptions {
  // LaTeX: print each cell's interval ("0.2256 [0.214, 0.238]"); the other formats always show intervals
  // when the cells have them (TableCell::ci_low / ci_high).
  bool latex_ci = false;
  bool booktabs = false;  // LaTeX: \toprule / \midrule / \bottomrule instead of vertical rules and \hline
  // What the intervals are, for the captions: "95% scene-bootstrap interval, 2000 resamples, seed 0".
  int resamples = 0;
  double level = 0.95;
  unsigned long long seed = 0;
  double conf_threshold = 0;  // the prediction threshold the table was computed with (JSON)
};

// Why a shown cell has no interval: "1 scene: no interval" (or "0 scenes") when fewer than two of its
// scenes have pairs (a scene bootstrap needs two); "" otherwise.
std::string no_interval_reason(const TableCell& cell);

bool parse_table_format(const std::string& name, TableFormat* out);
std::string format_table(const CrossTable& table, TableFormat format, const TableFormatOptions& options = {});

}  // namespace ipd
