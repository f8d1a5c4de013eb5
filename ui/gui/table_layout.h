// ipd-studio's cross table sized to its content. A table that may scroll sideways is a child window whose
// height must be given (given none, it takes the rest of the panel and shows blank rows); ImGui lays a row
// out as one text line plus the cell padding above and below it.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace ipd::ui {

struct TableMetrics {
  float line = 0;  // text line height
  float cell_pad_x = 0, cell_pad_y = 0;
  float border = 1;     // a border line
  float scrollbar = 0;  // the horizontal scrollbar's height
};
struct TableSize {
  float width = 0, height = 0;
  bool scroll_x = false;  // the columns are wider than the panel: scroll sideways
};
// `text_widths`: the widest text of each column; `rows` counts header rows too.
TableSize cross_table_size(const std::vector<float>& text_widths, int rows, float avail_width, const TableMetrics& m);

// A domain pair's header on two rows, the paper's |a − b| split after the minus: {"|real -", "principled|"}
// ("real" over "- principled" read like a list item). ASCII '-': the studio's font has no U+2212.
std::pair<std::string, std::string> cross_table_header(const std::string& a, const std::string& b);

}  // namespace ipd::ui
