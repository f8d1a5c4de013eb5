#include "ui/figures/figure_table.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include <fmt/format.h>
#include "core/ipd/ipd.h"
#include "ui/figures/figure_common.h"

#include "core/report/table_format.h"

namespace ipd::ui {

using namespace fig;

namespace {

double widest_word(Canvas& c, const TextStyle& st, const std::string& s) {
  std::istringstream in(s);
  double w = 0;
  for (std::string word; in >> word;) w = std::max(w, c.measure(st, word).x);
  return w;
}

// Every text of a column: the header, then each row's cell and its second line.
template <class F>
void for_each_text(const TableFigure& t, size_t c, F&& f) {
  f(t.header[c], true, false);
  for (size_t r = 0; r < t.rows.size(); ++r) {
    f(t.rows[r][c], false, false);
    if (r < t.sub.size() && c < t.sub[r].size()) f(t.sub[r][c], false, true);
  }
}

// The intervals' smaller font (secondary_pt of the cells').
double interval_pt(double cell_pt) { return secondary_pt(cell_pt); }

// The width each column needs at font size F with its cells wrapped at spaces (`lo`: the widest word, or the
// whole interval, which never wraps) and on one line (`hi`), padding included.
struct ColumnNeeds {
  std::vector<double> lo, hi;
};
ColumnNeeds column_needs(Canvas& out, const TableFigure& t, double F) {
  const size_t cols = t.header.size();
  const TextStyle bold = style(F, kInk, true), sub = style(interval_pt(F), kGrey);
  const double pad = 0.9 * F;
  ColumnNeeds n{std::vector<double>(cols, 0), std::vector<double>(cols, 0)};
  for (size_t c = 0; c < cols; ++c)
    for_each_text(t, c, [&](const std::string& s, bool, bool is_sub) {
      const TextStyle& st = is_sub ? sub : bold;
      n.lo[c] = std::max(n.lo[c], (is_sub ? out.measure(st, s).x : widest_word(out, st, s)) + pad);
      n.hi[c] = std::max(n.hi[c], out.measure(st, s).x + pad);
    });
  return n;
}

// The smallest font the table may use: the print minimum (kReadablePt), or --font-pt when that asks for less.
double floor_font(const FigureOptions& o) { return std::min(o.font_pt, kReadablePt); }

// The font size and column widths of a table `avail` wide.
struct TableFit {
  double font_pt = 0;
  std::vector<double> widths;
};

TableFit fit_table(Canvas& out, const TableFigure& t, const FigureOptions& o, double avail) {
  const size_t cols = t.header.size();
  // The largest font (up to --font-pt) at which every column fits with its cells wrapped at spaces; columns
  // narrower than their longest cell share the shortfall in proportion. Never below floor_font: a table
  // that does not fit there is split into column groups (table_column_groups) before it gets here.
  double F = o.font_pt;
  const double floor_pt = floor_font(o);
  std::vector<double> w(cols);
  for (;; F -= 0.25) {
    F = std::max(F, floor_pt);
    const ColumnNeeds n = column_needs(out, t, F);
    double sum_lo = 0, sum_hi = 0;
    for (size_t c = 0; c < cols; ++c) sum_lo += n.lo[c], sum_hi += n.hi[c];
    const double k = sum_hi <= avail   ? 1.0
                     : sum_hi > sum_lo ? std::max(0.0, (avail - sum_lo) / (sum_hi - sum_lo))
                                       : 0.0;
    for (size_t c = 0; c < cols; ++c) w[c] = n.lo[c] + k * (n.hi[c] - n.lo[c]);
    if (sum_lo <= avail || F <= floor_pt) break;
  }
  // A table narrower than the page spreads its spare width over the value columns, so the rules span the
  // figure's width as a paper's full-width table does.
  if (double used = 0; cols > 1) {
    for (double v : w) used += v;
    if (used < avail)
      for (size_t c = 1; c < cols; ++c) w[c] += (avail - used) / static_cast<double>(cols - 1);
  }
  return {F, w};
}

// The table restricted to the first column (the row names) and the value columns `keep`.
TableFigure with_columns(const TableFigure& t, const std::vector<size_t>& keep) {
  TableFigure g;
  const auto pick = [&](const auto& row) {
    std::decay_t<decltype(row)> out;
    if (!row.empty()) out.push_back(row[0]);
    for (size_t c : keep)
      if (c < row.size()) out.push_back(row[c]);
    return out;
  };
  g.header = pick(t.header);
  for (const auto& r : t.rows) g.rows.push_back(pick(r));
  for (const auto& r : t.bold) g.bold.push_back(pick(r));
  for (const auto& r : t.sub) g.sub.push_back(pick(r));
  return g;
}

// One table block (header band, rows, rules) from y down; returns the y below its bottom rule.
double draw_table_block(DisplayList& out, const TableFigure& t, const FigureOptions& o, double y) {
  const double m = kFigureMargin, avail = o.width_pt() - 2 * m;
  const size_t cols = t.header.size();
  const TableFit fit = fit_table(out, t, o, avail);
  const double F = fit.font_pt;
  const std::vector<double>& w = fit.widths;
  const TextStyle body = style(F, kInk), bold = style(F, kInk, true), sub = style(interval_pt(F), kGrey);
  const double pad = 0.9 * F, line_h = out.measure(body, "Ag").y, sub_h = out.measure(sub, "Ag").y;
  const double lw = std::max(0.3, 0.06 * F);
  std::vector<double> x(cols + 1, m);
  for (size_t c = 0; c < cols; ++c) x[c + 1] = x[c] + w[c];
  // Header: wrapped per column, on a light band.
  size_t header_lines = 1;
  std::vector<std::vector<std::string>> head(cols);
  for (size_t c = 0; c < cols; ++c) {
    head[c] = wrap(out, bold, t.header[c], w[c] - pad);
    header_lines = std::max(header_lines, head[c].size());
  }
  const double top = y, head_h = header_lines * line_h + 0.5 * F;
  out.fill_rect({x[0], y, x[cols], y + head_h}, rgb(235, 235, 240));
  for (size_t c = 0; c < cols; ++c)
    for (size_t l = 0; l < head[c].size(); ++l)
      out.text({x[c] + pad / 2, y + 0.25 * F + l * line_h}, Anchor::kTopLeft, bold, head[c][l]);
  y += head_h;
  for (size_t r = 0; r < t.rows.size(); ++r) {
    double row_h = line_h;
    for (size_t c = 0; c < cols; ++c) {
      const bool is_bold = r < t.bold.size() && c < t.bold[r].size() && t.bold[r][c];
      double cy = y + 0.25 * F;
      for (const std::string& l : wrap(out, is_bold ? bold : body, t.rows[r][c], w[c] - pad)) {
        out.text({x[c] + pad / 2, cy}, Anchor::kTopLeft, is_bold ? bold : body, l);
        cy += line_h;
      }
      if (r < t.sub.size() && c < t.sub[r].size())
        if (!t.sub[r][c].empty()) {
          out.text({x[c] + pad / 2, cy}, Anchor::kTopLeft, sub, t.sub[r][c]);
          cy += sub_h;
        }
      row_h = std::max(row_h, cy - y - 0.25 * F);
    }
    y += row_h + 0.5 * F;
  }
  out.line({x[0], top}, {x[cols], top}, kInk, lw * 2);
  out.line({x[0], top + head_h}, {x[cols], top + head_h}, kInk, lw);
  out.line({x[0], y}, {x[cols], y}, kInk, lw * 2);
  return y;
}

}  // namespace

std::vector<std::vector<size_t>> table_column_groups(Canvas& c, const TableFigure& t, const FigureOptions& o) {
  o.check();
  const double avail = o.width_pt() - 2 * kFigureMargin;
  const size_t cols = t.header.size();
  const ColumnNeeds n = column_needs(c, t, floor_font(o));
  std::vector<std::vector<size_t>> groups(1);
  double used = cols > 0 ? n.lo[0] : 0;
  for (size_t k = 1; k < cols; ++k) {
    if (!groups.back().empty() && used + n.lo[k] > avail) groups.emplace_back(), used = n.lo[0];
    if (n.lo[0] + n.lo[k] > avail) {
      // Even alone beside the row names this column is wider than the page: say which width holds it.
      const double need_in = (n.lo[0] + n.lo[k] + 2 * kFigureMargin) / 72.0;
      throw std::invalid_argument(fmt::format(
          "the table's column \"{}\" needs {:.2f} in beside the row names, more than the figure's {:g} in: "
          "{}",
          t.header[k], need_in, o.width_in,
          need_in <= kSingleColumnIn   ? std::string("--column single fits it")
          : need_in <= kDoubleColumnIn ? std::string("--column double fits it")
                                       : fmt::format("--width-in {:.1f} fits it", std::ceil(need_in * 10) / 10)));
    }
    groups.back().push_back(k);
    used += n.lo[k];
  }
  // As many columns in each group as the others, when that fits: two tables of 3 read better than 5 and 1.
  const size_t values = cols > 0 ? cols - 1 : 0, per = (values + groups.size() - 1) / groups.size();
  std::vector<std::vector<size_t>> even;
  for (size_t k = 1; k < cols; ++k) {
    if (even.empty() || even.back().size() == per) even.emplace_back();
    even.back().push_back(k);
  }
  const bool even_fits = std::all_of(even.begin(), even.end(), [&](const std::vector<size_t>& g) {
    double w = n.lo[0];
    for (size_t k : g) w += n.lo[k];
    return w <= avail;
  });
  return even_fits && even.size() == groups.size() ? even : groups;
}

void draw_table_figure(DisplayList& out, const TableFigure& t, const FigureOptions& o) {
  o.check();
  const double W = o.width_pt(), m = kFigureMargin, avail = W - 2 * m;
  const double F = o.font_pt;
  double y = m + draw_wrapped(out, {m, m}, style(o.font_pt, kInk), t.title, avail) + 0.4 * F;
  // A table wider than the page at the print minimum is drawn as several tables, one under the other, each
  // with the row names and as many columns as fit: every cell is on the page, none cut or overrun.
  const std::vector<std::vector<size_t>> groups = table_column_groups(out, t, o);
  for (size_t g = 0; g < groups.size(); ++g) {
    if (g > 0) y += 0.6 * F;
    // Split tables share one font size (the print minimum), so a value reads the same in each.
    FigureOptions block = o;
    if (groups.size() > 1) block.font_pt = floor_font(o);
    y = draw_table_block(out, groups.size() == 1 ? t : with_columns(t, groups[g]), block, y);
  }
  y += 0.4 * F;
  if (!t.note.empty()) y += draw_wrapped(out, {m, y}, style(secondary_pt(o.font_pt), kGrey), t.note, avail);
  out.width_pt = W;
  out.height_pt = std::ceil(y + m);
}

TableFigure table_figure_of(const CrossTable& t, bool ci, double level) {
  TableFigure fig;
  fig.title = "Instance Performance Difference (lower is better)";
  fig.header.push_back("Train \\ Eval");
  for (const auto& [a, b] : t.columns)
    fig.header.push_back("|" + a + "\u00a0\u2212 " + b + "|");  // "−" stays with the first name
  const size_t nc = t.columns.size();
  // Cells that are not a number (no predictions left on either side) are marked and say why in the note, as
  // the text table's footnotes do.
  std::vector<std::string> reasons;
  for (size_t r = 0; r < t.models.size(); ++r) {
    const auto& m = t.models[r];
    std::vector<std::string> row = {m.trained_on.empty() ? m.name : m.name + " (" + m.trained_on + ")"};
    std::vector<char> bold(nc + 1, 0);
    std::vector<std::string> sub(nc + 1);
    double best = INFINITY;
    for (size_t c = 0; c < nc; ++c) {
      const auto& cell = t.cells[r * nc + c];
      if (cell.involves_training_domain && !std::isnan(cell.ipd)) best = std::min(best, cell.ipd);
    }
    for (size_t c = 0; c < nc; ++c) {
      const auto& cell = t.cells[r * nc + c];
      row.push_back(!cell.involves_training_domain  ? "\u2013"
                    : !cell.no_value_reason.empty() ? no_value_mark(footnote_number(&reasons, cell.no_value_reason))
                    : std::isnan(cell.ipd)          ? "n/a"
                                                    : fmt::format("{:.4f}", cell.ipd));
      bold[c + 1] = cell.involves_training_domain && cell.ipd == best;
      if (ci && cell.involves_training_domain && std::isfinite(cell.ci_low) && std::isfinite(cell.ci_high))
        sub[c + 1] = fmt::format("[{:.3f},\u2009{:.3f}]", cell.ci_low, cell.ci_high);  // thin space: one word
      else if (ci)
        sub[c + 1] = no_interval_reason(cell);  // "1 scene: no interval"
    }
    if (ci) fig.sub.push_back(sub);
    fig.rows.push_back(row);
    fig.bold.push_back(bold);
  }
  // A domain pair no row's detector was trained on holds no number, only "–": it is left out, and said.
  std::vector<size_t> keep;
  for (size_t c = 0; c < nc; ++c)
    for (size_t r = 0; r < t.models.size(); ++r)
      if (t.cells[r * nc + c].involves_training_domain) {
        keep.push_back(c + 1);
        break;
      }
  const size_t dropped = nc - keep.size();
  if (dropped > 0 && !keep.empty()) {
    TableFigure kept = with_columns(fig, keep);
    fig.header = kept.header, fig.rows = kept.rows, fig.bold = kept.bold, fig.sub = kept.sub;
  }
  fig.note =
      "Rows: detector and its training domain. \u2013: pair not involving the training domain; bold: the row's best.";
  // Only when some cell has brackets (a one-scene study has none: its cells say "1 scene: no interval").
  const bool brackets = std::any_of(t.cells.begin(), t.cells.end(), [](const TableCell& c) {
    return c.involves_training_domain && std::isfinite(c.ci_low) && std::isfinite(c.ci_high);
  });
  if (ci && brackets) fig.note += fmt::format(" Brackets: {:g}% scene-bootstrap interval.", 100 * level);
  if (dropped > 0 && !keep.empty())
    fig.note += fmt::format(" Not shown: {} domain pair{} without any row's training domain (every cell \u2013).",
                            dropped, dropped == 1 ? "" : "s");
  for (size_t k = 0; k < reasons.size(); ++k)
    fig.note += fmt::format(" {}: not a number, {}.", no_value_mark(static_cast<int>(k) + 1), reasons[k]);
  return fig;
}

}  // namespace ipd::ui
