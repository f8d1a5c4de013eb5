// Rendering the cross table (the paper's Table I) as text, CSV, JSON, Markdown or LaTeX.
#pragma once

#include <string>

#include "ipd/ipd.h"

namespace ipd {

enum class TableFormat { kText, kCsv, kJson, kMarkdown, kLatex };

bool parse_table_format(const std::string& name, TableFormat* out);
std::string format_table(const CrossTable& table, TableFormat format);

}  // namespace ipd
