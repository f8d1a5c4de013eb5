// Rendering a ranking of renderer settings (core/rank/ranking.h) as text, CSV, JSON, Markdown or LaTeX, with the
// same interval caption and provenance as the cross table (table_format.h).
#pragma once

#include <string>

#include "core/rank/ranking.h"
#include "core/report/provenance.h"
#include "core/report/table_format.h"

namespace ipd {

// `options`: the intervals' resamples, level and seed, the threshold and the provenance, as for the table.
std::string format_ranking(const Ranking& ranking, TableFormat format, const TableFormatOptions& options);

// The notes every format ends with, one per line (text and Markdown print them under the table, LaTeX as
// footnote lines, CSV and JSON carry them as fields and the command prints them on stderr): the best's group at
// the level, how Δ and p were made ("Holm"), candidates not ranked and why, candidates without predictions.
std::vector<std::string> ranking_notes(const Ranking& ranking, const TableFormatOptions& options);

// LaTeX (format_ranking): by default a compact layout for one IEEE column (settings by their parameter values when
// they all have the same parameters, intervals on a second line); `options.latex_wide`: names, parameters and
// intervals on one line, for a table* across both columns.
// What `ipd rank --format latex` says when the compact ranking is wider than one IEEE column (252 pt at 10 pt
// type), with its estimated width and where it fits; "" when it fits or for the wide layout.
std::string latex_ranking_fit_advice(const Ranking& ranking, const TableFormatOptions& options);

}  // namespace ipd
