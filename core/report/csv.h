// CSV fields as RFC 4180 writes them: a field holding a comma, a double quote, a line feed or a carriage
// return is quoted and its quotes doubled, so a model, domain or scene named "a,b" stays one column in
// pandas, R and spreadsheets instead of shifting every column after it.
#pragma once

#include <string>
#include <vector>

namespace ipd {

std::string csv_field(const std::string& s);

// The fields joined by commas, each through csv_field, and a line feed.
std::string csv_row(const std::vector<std::string>& fields);

}  // namespace ipd
