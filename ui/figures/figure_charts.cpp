#include "ui/figures/figure_charts.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "ui/figures/figure_common.h"

namespace ipd::ui {

using namespace fig;

std::vector<double> nice_ticks(double lo, double hi, int target) {
  if (!(hi > lo)) hi = lo + 1;
  target = std::max(2, target);
  const double raw = (hi - lo) / target, mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (m * mag >= raw) {
      step = m * mag;
      break;
    }
  std::vector<double> t;
  for (long k = long(std::floor(lo / step + 1e-9)); k * step <= hi + step * 1e-9; ++k)
    t.push_back(k == 0 ? 0.0 : k * step);
  return t;
}

std::string tick_text(double v, double step) {
  int decimals = 0;
  while (decimals < 6 && std::abs(step * std::pow(10.0, decimals) - std::round(step * std::pow(10.0, decimals))) > 1e-6)
    ++decimals;
  return fmt::format("{:.{}f}", v, decimals);
}

namespace {

constexpr double kMargin = kFigureMargin;

// A figure's tick: a typographic minus (U+2212) as in the rows' notes and the titles, one style per page.
std::string axis_tick(double v, double step) {
  const std::string t = tick_text(v, step);
  return !t.empty() && t[0] == '-' ? "\u2212" + t.substr(1) : t;
}

struct Axis {
  double x0, x1, lo, hi;
  double at(double v) const { return x0 + (v - lo) / (hi - lo) * (x1 - x0); }
};

// Picks the axis range and ticks whose labels fit the plot width; draws axis, ticks and label; returns
// the height used below `y`.
// Ticks cover [tick_lo, tick_hi] (the data; default [lo, hi]), the axis [lo, hi] (the data and its padding)
// and the ticks: padding never adds a whole tick step (data from -0.095 ran to -0.2 when padded to -0.1).
double draw_axis(Canvas& c, Axis& ax, double lo, double hi, double y_top, double y, const std::string& label,
                 const FigureOptions& o, bool zero_line, bool end_on_tick = false, double tick_lo = NAN,
                 double tick_hi = NAN) {
  const TextStyle tick = style(secondary_pt(o.font_pt), kInk);
  if (std::isnan(tick_lo) || std::isnan(tick_hi)) tick_lo = lo, tick_hi = hi;
  std::vector<double> ticks;
  for (int target = 6; target >= 2; --target) {
    ticks = nice_ticks(tick_lo, tick_hi, target);
    const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : 1;
    double widest = 0;
    for (double t : ticks) widest = std::max(widest, c.measure(tick, axis_tick(t, step)).x);
    if ((ax.x1 - ax.x0) / std::max<size_t>(1, ticks.size() - 1) > widest * 1.6) break;
  }
  // Ending on a labelled tick, an axis that runs to the page margin ends with ink there (its last label).
  if (end_on_tick && ticks.size() > 1 && ticks.back() < hi - 1e-12) ticks.push_back(ticks.back() + ticks[1] - ticks[0]);
  ax.lo = std::min(lo, ticks.front());
  ax.hi = std::max(hi, ticks.back());
  const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : 1, lw = std::max(0.35, o.font_pt * 0.06);
  // The end labels are centred on their ticks: keep their outer halves out of the page margin.
  const double page_w = o.width_pt();
  ax.x0 = std::max(ax.x0, kMargin + 0.5 * c.measure(tick, axis_tick(ticks.front(), step)).x);
  ax.x1 = std::min(ax.x1, page_w - kMargin - 0.5 * c.measure(tick, axis_tick(ticks.back(), step)).x);
  for (double t : ticks) c.line({ax.at(t), y_top}, {ax.at(t), y}, rgb(225, 225, 225), lw);
  if (zero_line && ax.lo <= 0 && ax.hi >= 0) c.line({ax.at(0), y_top}, {ax.at(0), y}, kGrey, lw * 2);
  c.line({ax.x0, y}, {ax.x1, y}, kInk, lw);
  const double tick_len = o.font_pt * 0.3;
  double h = 0;
  for (double t : ticks) {
    c.line({ax.at(t), y}, {ax.at(t), y + tick_len}, kInk, lw);
    c.text({ax.at(t), y + tick_len + 0.5}, Anchor::kTop, tick, axis_tick(t, step));
    h = std::max(h, tick_len + 0.5 + c.measure(tick, "0").y);
  }
  const TextStyle ls = style(o.font_pt, kInk);
  c.text({(ax.x0 + ax.x1) / 2, y + h + 0.2 * o.font_pt}, Anchor::kTop, ls, label);
  return h + 0.2 * o.font_pt + c.measure(ls, label).y;
}

// The label column: as wide as the widest label, at most 40% of the width (longer labels wrap).
double label_width(Canvas& c, const TextStyle& st, const std::vector<std::string>& labels, double W) {
  double w = 0;
  for (const auto& l : labels) w = std::max(w, c.measure(st, l).x);
  return std::min(w, 0.4 * W);
}

// A row label right-aligned at x, its lines centred on cy.
void row_label(Canvas& c, double x, double cy, double width, const TextStyle& st, const std::string& label) {
  const auto lines = wrap(c, st, label, width);
  const double h = c.measure(st, "Ag").y;
  double y = cy - h * lines.size() / 2;
  for (const auto& l : lines) {
    c.text({x, y}, Anchor::kTopRight, st, l);
    y += h;
  }
}

size_t most_lines(Canvas& c, const TextStyle& st, const std::vector<std::string>& labels, double width) {
  size_t n = 1;
  for (const auto& l : labels) n = std::max(n, wrap(c, st, l, width).size());
  return n;
}

}  // namespace

void draw_dot_whisker_chart(DisplayList& out, const DotWhiskerChart& ch, const FigureOptions& o) {
  o.check();
  const double W = o.width_pt(), F = o.font_pt;
  const TextStyle body = style(F, kInk), note = style(secondary_pt(F), kGrey);
  double y = kMargin + draw_wrapped(out, {kMargin, kMargin}, body, ch.title, W - 2 * kMargin) + 0.5 * F;
  std::vector<std::string> labels, notes;
  double lo = INFINITY, hi = -INFINITY;
  for (const ChartRow& r : ch.rows) {
    labels.push_back(r.label);
    notes.push_back(r.note);
    for (double v : {r.estimate, r.low, r.high})
      if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  }
  if (ch.zero_line) lo = std::min(lo, 0.0), hi = std::max(hi, 0.0);
  // A quantity that cannot be negative (IPD) is read as a length from 0, as the studio's panel draws it: its
  // axis and ticks start at 0 even when every value lies far from it (0.22 to 0.28, say).
  if (ch.non_negative && std::isfinite(lo) && lo >= 0) lo = 0;
  if (!std::isfinite(lo)) lo = 0, hi = 1;
  const double pad = (hi - lo) * 0.05 + 1e-9;
  // Not from a padding below 0 either.
  const double axis_lo = ch.non_negative && lo >= 0 ? std::max(0.0, lo - pad) : lo - pad;
  const double lw_labels = label_width(out, body, labels, W);
  double lw_notes = 0;
  for (const auto& n : notes) lw_notes = std::max(lw_notes, out.measure(note, n).x);
  Axis ax{kMargin + lw_labels + 0.6 * F, W - kMargin - lw_notes - (lw_notes > 0 ? 0.6 * F : 0.3 * F), axis_lo,
          hi + pad};
  const double line = out.measure(body, "Ag").y;
  const double row_h = std::max(line * 1.5, line * most_lines(out, body, labels, lw_labels) + 0.3 * F);
  const double top = y, bottom = y + row_h * ch.rows.size();
  const double lw = std::max(0.4, F * 0.08);
  Axis fitted = ax;
  const double axis_h =
      draw_axis(out, fitted, axis_lo, hi + pad, top, bottom, ch.axis_label, o, ch.zero_line, false, lo, hi);
  for (size_t i = 0; i < ch.rows.size(); ++i) {
    const ChartRow& r = ch.rows[i];
    const double cy = top + row_h * (i + 0.5);
    row_label(out, kMargin + lw_labels, cy, lw_labels, body, r.label);
    if (std::isfinite(r.low) && std::isfinite(r.high)) {
      const double cap = row_h * 0.18;
      out.line({fitted.at(r.low), cy}, {fitted.at(r.high), cy}, kBlueC, lw);
      out.line({fitted.at(r.low), cy - cap}, {fitted.at(r.low), cy + cap}, kBlueC, lw);
      out.line({fitted.at(r.high), cy - cap}, {fitted.at(r.high), cy + cap}, kBlueC, lw);
    }
    if (std::isfinite(r.estimate)) out.fill_circle({fitted.at(r.estimate), cy}, std::max(1.2, F * 0.22), kBlueC);
    if (!r.note.empty()) out.text({W - kMargin - lw_notes, cy}, Anchor::kLeft, note, r.note);
  }
  // A footnote 0.4 font sizes below the axis; none: the page ends at the axis label (the 4 pt margin).
  y = bottom + axis_h;
  if (!ch.footnote.empty())
    y += 0.4 * F +
         draw_wrapped(out, {kMargin, y + 0.4 * F}, style(secondary_pt(F), kGrey), ch.footnote, W - 2 * kMargin);
  out.width_pt = W;
  out.height_pt = std::ceil(y + kMargin);
}

void draw_distribution_chart(DisplayList& out, const DistributionChart& ch, const FigureOptions& o) {
  o.check();
  const double W = o.width_pt(), F = o.font_pt;
  const TextStyle body = style(F, kInk), name = style(secondary_pt(F), kRedC);
  double y = kMargin + draw_wrapped(out, {kMargin, kMargin}, body, ch.title, W - 2 * kMargin) + 0.5 * F;
  std::vector<std::string> labels;
  double lo = 0, hi = -INFINITY;
  for (const BoxRow& r : ch.rows) {
    labels.push_back(r.label);
    for (double v : r.values) hi = std::max(hi, v);
  }
  if (!std::isfinite(hi) || hi <= 0) hi = 1;
  const double lw_labels = label_width(out, body, labels, W);
  Axis ax{kMargin + lw_labels + 0.6 * F, W - kMargin, lo, hi * 1.05};
  // Room for a name above and below each box.
  const double line = out.measure(body, "Ag").y;
  const double row_h = std::max(line * 4.0, line * most_lines(out, body, labels, lw_labels) + 0.3 * F);
  const double top = y, bottom = y + row_h * ch.rows.size();
  const double axis_h = draw_axis(out, ax, lo, hi * 1.05, top, bottom, ch.axis_label, o, false, true);
  const double lw = std::max(0.4, F * 0.08);
  int left_out = 0;
  for (size_t i = 0; i < ch.rows.size(); ++i) {
    const BoxRow& r = ch.rows[i];
    const double cy = top + row_h * (i + 0.5), bh = line * 0.9;
    row_label(out, kMargin + lw_labels, cy, lw_labels, body, r.label);
    if (r.values.empty()) continue;
    out.line({ax.at(r.min), cy}, {ax.at(r.q1), cy}, kInk, lw);
    out.line({ax.at(r.q3), cy}, {ax.at(r.max), cy}, kInk, lw);
    for (double v : {r.min, r.max}) out.line({ax.at(v), cy - bh * 0.3}, {ax.at(v), cy + bh * 0.3}, kInk, lw);
    out.fill_rect({ax.at(r.q1), cy - bh / 2, ax.at(r.q3), cy + bh / 2}, rgb(200, 220, 250));
    out.rect({ax.at(r.q1), cy - bh / 2, ax.at(r.q3), cy + bh / 2}, kInk, lw);
    out.line({ax.at(r.median), cy - bh / 2}, {ax.at(r.median), cy + bh / 2}, kInk, lw * 2);
    const double dot = std::max(0.8, F * 0.13);
    for (double v : r.values) out.fill_circle({ax.at(v), cy}, dot, rgb(40, 110, 230, 150));
    // The worst scenes, named beside their dots, without collisions (within the row's band).
    std::vector<Label> names;
    for (const auto& [stem, v] : r.worst) {
      out.circle({ax.at(v), cy}, dot * 2, kRedC, lw);
      // Circles less than a dot apart are one place on the page: one name for them ("scene_01, scene_02").
      const double x = ax.at(v);
      bool merged = false;
      for (Label& l : names)
        if (std::abs((l.target.x0 + l.target.x1) / 2 - x) < dot) l.text += ", " + stem, merged = true;
      // Exclusive: beside its own circle and 2 pt clear of the others (or led to it), so two close circles
      // never get two names stacked between them that a reader cannot tell apart.
      if (!merged) names.push_back({stem, name, {x - dot * 2, cy - dot * 2, x + dot * 2, cy + dot * 2}, true});
    }
    const PtRect band{ax.x0, top + row_h * i, W - kMargin, top + row_h * (i + 1)};
    // The box and every named circle are obstacles: a name never covers its own circle or a neighbour's.
    std::vector<PtRect> taken = {{ax.at(r.q1), cy - bh / 2, ax.at(r.q3), cy + bh / 2}};
    for (const Label& l : names) taken.push_back(l.target);
    left_out += draw_labels(out, names, band, taken, false);
  }
  y = bottom + axis_h;
  if (!ch.footnote.empty())
    y += 0.4 * F +
         draw_wrapped(out, {kMargin, y + 0.4 * F}, style(secondary_pt(F), kGrey), ch.footnote, W - 2 * kMargin);
  y += draw_footnote(out, {kMargin, y}, W - 2 * kMargin, F, left_out, wider_hint(o.width_in));
  out.width_pt = W;
  out.height_pt = std::ceil(y + kMargin);
}

}  // namespace ipd::ui
