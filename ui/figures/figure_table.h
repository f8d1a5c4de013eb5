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

// Columns fit the width: headers wrap at spaces, then the font shrinks (never below the print minimum, 7 pt,
// unless --font-pt asks for less); a table still wider than the page is drawn as several tables one under the
// other (table_column_groups), so no cell is ever cut.
void draw_table_figure(DisplayList& out, const TableFigure& table, const FigureOptions& options);

// The value columns (indices into header, from 1) of each table the figure draws: one group when the table
// fits the width at the smallest font, else consecutive groups, as even as fits, each drawn beside the row
// names. Throws std::invalid_argument naming the --column (or --width-in) that fits when one value column
// beside the row names is wider than the page.
std::vector<std::vector<size_t>> table_column_groups(Canvas& c, const TableFigure& table, const FigureOptions& options);

}  // namespace ipd::ui

namespace ipd {
struct CrossTable;
}
namespace ipd::ui {
// Table I's cells as the paper shows them: "–" for pairs not involving the training domain, the row's
// best in bold; `ci`: each cell's `level` interval on a second line, never wrapped (when the table has them).
TableFigure table_figure_of(const CrossTable& table, bool ci = false, double level = 0.95);
}  // namespace ipd::ui
