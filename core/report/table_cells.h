// What every format of the cross table says of a cell, a row and a column, so text, Markdown, LaTeX and the
// figures word them alike: titles, a cell's number or dash, footnotes for cells that are not a number,
// intervals and the row's best. Internal to the report library (core/report/table_format.h is the API).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/ipd/ipd.h"

namespace ipd {
struct TableFormatOptions;
}

namespace ipd::table_cells {

std::string column_title(const std::pair<std::string, std::string>& c);  // "real - synth"
std::string row_title(const ModelInfo& m);                               // "det (real)"
// `dash` for cells that don't involve the training domain (as the paper), "n/a" when nothing was measured.
std::string cell_text(const TableCell& c, const char* dash);
// The distinct reasons of cells that are not a number (TableCell::no_value_reason), in cell order: cell k's
// footnote is its reason's position + 1.
std::vector<std::string> footnotes(const CrossTable& t);
int footnote_of(const std::vector<std::string>& notes, const TableCell& c);  // 0: none
// The text of a cell: a number, or "–" with the mark of its footnote when it is not one for a reason.
std::string marked_cell_text(const TableCell& c, const char* dash, const std::vector<std::string>& notes);
std::string footnote_lines(const std::vector<std::string>& notes);
bool has_ci(const TableCell& c);
// " [0.214, 0.238]" when the cell has an interval and is shown.
std::string ci_text(const TableCell& c);
// " (15 pairs)", " (15 pairs; 1 scene: no interval)" when intervals were asked for and the cell can't have one.
std::string pairs_text(const TableCell& c, const TableFormatOptions& o);
bool any_ci(const CrossTable& t);
std::string ci_caption(const TableFormatOptions& o);
// The best (lowest) shown value of a row, bolded in Markdown and LaTeX as the paper does.
double row_best(const CrossTable& t, size_t row);

// The LaTeX layouts (table_latex.cpp): the wide or the compact one, as `o.latex_wide` says, and LaTeX's
// escaping of plain text.
std::string latex_cross_table(const CrossTable& t, const TableFormatOptions& o);
std::string latex_text(const std::string& s);
// The advance width of plain text at 10 pt Computer Modern (roman, or bold), in points, within a few.
double latex_text_width_pt(const std::string& s, bool bold);

}  // namespace ipd::table_cells
