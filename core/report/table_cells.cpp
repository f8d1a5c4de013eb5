#include "core/report/table_cells.h"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>

#include "core/report/table_format.h"
#include "core/util/number_text.h"

namespace ipd::table_cells {

std::string column_title(const std::pair<std::string, std::string>& c) { return c.first + " - " + c.second; }
std::string row_title(const ModelInfo& m) {
  return m.trained_on.empty() ? m.name : fmt::format("{} ({})", m.name, m.trained_on);
}

// "–" for cells that don't involve the training domain (as the paper), "n/a" when nothing was measured.
std::string cell_text(const TableCell& c, const char* dash) {
  if (!c.involves_training_domain) return dash;
  if (std::isnan(c.ipd)) return "n/a";
  return fmt::format("{:.4f}", c.ipd);
}

// The distinct reasons of cells that are not a number (TableCell::no_value_reason), in cell order: cell k's
// footnote is its reason's position + 1.
std::vector<std::string> footnotes(const CrossTable& t) {
  std::vector<std::string> out;
  for (const auto& c : t.cells)
    if (c.involves_training_domain && !c.no_value_reason.empty() &&
        std::find(out.begin(), out.end(), c.no_value_reason) == out.end())
      out.push_back(c.no_value_reason);
  return out;
}

int footnote_of(const std::vector<std::string>& notes, const TableCell& c) {
  if (!c.involves_training_domain || c.no_value_reason.empty()) return 0;
  return static_cast<int>(std::find(notes.begin(), notes.end(), c.no_value_reason) - notes.begin()) + 1;
}

// The text of a cell: a number, or "–" with the mark of its footnote when it is not one for a reason.
std::string marked_cell_text(const TableCell& c, const char* dash, const std::vector<std::string>& notes) {
  const int k = footnote_of(notes, c);
  return k > 0 ? no_value_mark(k) : cell_text(c, dash);
}

std::string footnote_lines(const std::vector<std::string>& notes) {
  std::string out;
  for (size_t k = 0; k < notes.size(); ++k) out += footnote_mark(static_cast<int>(k) + 1) + " " + notes[k] + "\n";
  return out;
}

bool has_ci(const TableCell& c) { return !std::isnan(c.ci_low) && !std::isnan(c.ci_high); }

// " [0.214, 0.238]" when the cell has an interval and is shown.
std::string ci_text(const TableCell& c) {
  if (!c.involves_training_domain || std::isnan(c.ipd) || !has_ci(c)) return {};
  return fmt::format(" [{:.3f}, {:.3f}]", c.ci_low, c.ci_high);
}

// " (15 pairs)", " (15 pairs; 1 scene: no interval)" when intervals were asked for and the cell can't have one.
std::string pairs_text(const TableCell& c, const TableFormatOptions& o) {
  if (!c.involves_training_domain || std::isnan(c.ipd)) return {};
  const std::string why = o.resamples > 0 && !has_ci(c) ? no_interval_reason(c) : std::string();
  return fmt::format(" ({} pairs{}{})", grouped_thousands(c.pairs), why.empty() ? "" : "; ", why);
}

bool any_ci(const CrossTable& t) {
  return std::any_of(t.cells.begin(), t.cells.end(), [](const TableCell& c) { return has_ci(c); });
}

std::string ci_caption(const TableFormatOptions& o) {
  return fmt::format("[low, high]: {:g}% scene-bootstrap percentile interval ({} resamples of scenes, seed {})",
                     100 * o.level, grouped_thousands(o.resamples), o.seed);
}

// The best (lowest) shown value of a row, bolded in Markdown and LaTeX as the paper does.
double row_best(const CrossTable& t, size_t row) {
  double best = INFINITY;
  for (size_t c = 0; c < t.columns.size(); ++c) {
    const auto& cell = t.cells[row * t.columns.size() + c];
    if (cell.involves_training_domain && !std::isnan(cell.ipd)) best = std::min(best, cell.ipd);
  }
  return best;
}

}  // namespace ipd::table_cells
