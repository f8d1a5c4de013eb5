// Table I as a figure: the cross table with the row's best cell in bold, optional confidence intervals.
#pragma once

#include <string>
#include <vector>

#include "ui/canvas/canvas.h"
#include "ui/figures/figure_options.h"

namespace ipd::ui {

struct TableFigure {
  std::string title;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::vector<std::vector<char>> bold;        // per cell (rows x header), the row's best
  std::vector<std::vector<std::string>> sub;  // optional second line per cell (a confidence interval)
  std::string note;
};

// Columns fit the width: headers wrap at spaces, then the font shrinks (never below 6 pt).
void draw_table_figure(DisplayList& out, const TableFigure& table, const FigureOptions& options);

}  // namespace ipd::ui

namespace ipd {
struct CrossTable;
}
namespace ipd::ui {
// Table I's cells as the paper shows them: "–" for pairs not involving the training domain, the row's
// best in bold; `ci`: each cell's `level` interval on a second line, never wrapped (when the table has them).
TableFigure table_figure_of(const CrossTable& table, bool ci = false, double level = 0.95);
}  // namespace ipd::ui
