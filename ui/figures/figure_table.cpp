#include "ui/figures/figure_table.h"

#include <algorithm>
#include <cmath>
#include <sstream>

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

// The font size and column widths of a table `avail` wide.
struct TableFit {
  double font_pt = 0;
  std::vector<double> widths;
};

TableFit fit_table(Canvas& out, const TableFigure& t, const FigureOptions& o, double avail) {
  const size_t cols = t.header.size();
  // The largest font (up to --font-pt) at which every column fits with its cells wrapped at spaces; columns
  // narrower than their longest cell share the shortfall in proportion.
  // Never below the print minimum (kReadablePt) unless --font-pt asks for less: a table that still doesn't
  // fit wraps its cells rather than shrinking further.
  double F = o.font_pt;
  const double floor_pt = std::min(o.font_pt, kReadablePt);
  std::vector<double> w(cols);
  for (;; F -= 0.25) {
    F = std::max(F, floor_pt);
    const TextStyle bold = style(F, kInk, true), sub = style(interval_pt(F), kGrey);
    const double pad = 0.9 * F;
    std::vector<double> lo(cols, 0), hi(cols, 0);
    for (size_t c = 0; c < cols; ++c)
      for_each_text(t, c, [&](const std::string& s, bool, bool is_sub) {
        const TextStyle& st = is_sub ? sub : bold;
        // An interval is one unit: it never wraps (its column is at least as wide as it).
        lo[c] = std::max(lo[c], (is_sub ? out.measure(st, s).x : widest_word(out, st, s)) + pad);
        hi[c] = std::max(hi[c], out.measure(st, s).x + pad);
      });
    double sum_lo = 0, sum_hi = 0;
    for (size_t c = 0; c < cols; ++c) sum_lo += lo[c], sum_hi += hi[c];
    const double k = sum_hi <= avail   ? 1.0
                     : sum_hi > sum_lo ? std::max(0.0, (avail - sum_lo) / (sum_hi - sum_lo))
                                       : 0.0;
    for (size_t c = 0; c < cols; ++c) w[c] = lo[c] + k * (hi[c] - lo[c]);
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

}  // namespace

void draw_table_figure(DisplayList& out, const TableFigure& t, const FigureOptions& o) {
  o.check();
  const double W = o.width_pt(), m = kFigureMargin, avail = W - 2 * m;
  const size_t cols = t.header.size();
  const TableFit fit = fit_table(out, t, o, avail);
  const double F = fit.font_pt;
  const std::vector<double>& w = fit.widths;
  const TextStyle body = style(F, kInk), bold = style(F, kInk, true), sub = style(interval_pt(F), kGrey);
  const double pad = 0.9 * F, line_h = out.measure(body, "Ag").y, sub_h = out.measure(sub, "Ag").y;
  const double lw = std::max(0.3, 0.06 * F);
  double y = m + draw_wrapped(out, {m, m}, style(o.font_pt, kInk), t.title, avail) + 0.4 * F;
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
  fig.note =
      "Rows: detector and its training domain. \u2013: pair not involving the training domain; bold: the row's best.";
  // Only when some cell has brackets (a one-scene study has none: its cells say "1 scene: no interval").
  const bool brackets = std::any_of(t.cells.begin(), t.cells.end(), [](const TableCell& c) {
    return c.involves_training_domain && std::isfinite(c.ci_low) && std::isfinite(c.ci_high);
  });
  if (ci && brackets) fig.note += fmt::format(" Brackets: {:g}% scene-bootstrap interval.", 100 * level);
  for (size_t k = 0; k < reasons.size(); ++k)
    fig.note += fmt::format(" {}: not a number, {}.", no_value_mark(static_cast<int>(k) + 1), reasons[k]);
  return fig;
}

}  // namespace ipd::ui
