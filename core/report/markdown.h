// Text in a Markdown table cell: a `|` in a model, domain or scene name would end the cell and shift every
// column after it, so it is written `\|` (GitHub Flavored Markdown's escape); a backslash is doubled first, so
// a name that holds `\|` itself reads back as written.
#pragma once

#include <string>
#include <string_view>

namespace ipd {

std::string markdown_cell(std::string_view text);

}  // namespace ipd
