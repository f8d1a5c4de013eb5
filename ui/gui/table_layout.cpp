#include "ui/gui/table_layout.h"

namespace ipd::ui {

TableSize cross_table_size(const std::vector<float>& text_widths, int rows, float avail_width, const TableMetrics& m) {
  TableSize s;
  s.width = m.border;  // the left outer border; each column adds its padding and its right border
  for (float w : text_widths) s.width += w + 2 * m.cell_pad_x + m.border;
  s.scroll_x = s.width > avail_width;
  s.height = rows * (m.line + 2 * m.cell_pad_y) + m.border + (s.scroll_x ? m.scrollbar : 0);
  return s;
}

std::pair<std::string, std::string> cross_table_header(const std::string& a, const std::string& b) {
  return {"|" + a + " -", b + "|"};
}

}  // namespace ipd::ui
