#include "ui/figures/stats_charts.h"

#include <algorithm>
#include <cmath>

#include "ui/figures/figure_charts.h"

namespace ipd::ui {

std::vector<double> count_ticks(int top, int most) {
  top = std::max(1, top);
  most = std::max(1, most);
  double step = 1;
  for (double p = 1;; p *= 10) {
    bool found = false;
    for (double m : {1.0, 2.0, 5.0})
      if (std::ceil(top / (m * p)) <= most) {
        step = m * p;
        found = true;
        break;
      }
    if (found) break;
  }
  std::vector<double> t;
  for (int k = 0; k * step < top + step - 1e-9; ++k) t.push_back(k * step);
  if (t.back() < top) t.push_back(t.back() + step);
  return t;
}

namespace {

double line_of(Canvas& c, const TextStyle& st) { return c.measure(st, "0").y; }
double tick_len(double line) { return std::round(0.3 * line); }

}  // namespace

HistogramChart layout_histogram(Canvas& c, const TextStyle& st, const HistogramInput& in, const PtRect& area) {
  HistogramChart ch;
  const double line = line_of(c, st);
  const size_t n = in.counts.size();
  ch.outline_gap = 1.5;
  ch.outline_width = 2;
  const double outline = ch.outline_gap + ch.outline_width;
  // Edge labels of the bins (every k-th when they would touch).
  std::vector<std::string> edges;
  double widest_edge = 0;
  for (size_t k = 0; k <= n; ++k) {
    edges.push_back(tick_text(in.start + k * in.width, in.width));
    widest_edge = std::max(widest_edge, c.measure(st, edges.back()).x);
  }
  const double top_pad = std::max(0.5 * line, outline + 0.5), bottom = tick_len(line) + 1 + line;
  const double plot_h = std::max(1.0, area.height() - top_pad - bottom);
  const int top = n ? *std::max_element(in.counts.begin(), in.counts.end()) : 0;
  const std::vector<double> counts = count_ticks(top, std::max(1, int(plot_h / (1.2 * line))));
  double gutter = 0;
  for (double v : counts) gutter = std::max(gutter, c.measure(st, tick_text(v, 1)).x);
  gutter += 0.3 * line + tick_len(line);
  ch.plot = {area.x0 + std::max(gutter, 0.5 * widest_edge), area.y0 + top_pad, area.x1 - 0.5 * widest_edge,
             area.y0 + top_pad + plot_h};
  const double axis_top = counts.back();
  for (double v : counts) ch.count_axis.push_back({v, ch.plot.y1 - ch.plot.height() * v / axis_top, tick_text(v, 1)});
  if (n == 0) return ch;
  const double slot = ch.plot.width() / n;
  // Room between bars for the outline of one of them; a lone bar no wider than a few characters.
  const double gap = std::max(2 * outline + 1, 0.15 * slot);
  const double bar_w = std::clamp(slot - gap, 1.0, 3.0 * line);
  for (size_t k = 0; k < n; ++k) {
    HistogramBar b;
    b.count = in.counts[k];
    b.lo = in.start + k * in.width;
    b.hi = b.lo + in.width;
    b.slot = {ch.plot.x0 + k * slot, ch.plot.y0, ch.plot.x0 + (k + 1) * slot, ch.plot.y1};
    // A non-empty bin always shows (and can be hovered): at least 2 pt, however many scenes the tallest has.
    const double h = b.count > 0 ? std::max(2.0, ch.plot.height() * b.count / axis_top) : 0.0;
    const bool lone = !std::isnan(in.lone_value) && b.count > 0 && in.lone_value >= b.lo && in.lone_value <= b.hi;
    const double cx = lone ? std::clamp(ch.plot.x0 + (in.lone_value - in.start) / in.width * slot,
                                        ch.plot.x0 + 0.5 * bar_w, ch.plot.x1 - 0.5 * bar_w)
                           : 0.5 * (b.slot.x0 + b.slot.x1);
    b.bar = {cx - 0.5 * bar_w, ch.plot.y1 - h, cx + 0.5 * bar_w, ch.plot.y1};
    const bool last = k + 1 == n;
    b.current = in.current >= b.lo && (in.current < b.hi || (last && in.current <= b.hi));
    ch.bars.push_back(b);
  }
  size_t every = 1;
  while (every < n && slot * every < widest_edge * 1.3) ++every;
  for (size_t k = 0; k <= n; k += every)
    ch.edge_axis.push_back({in.start + k * in.width, ch.plot.x0 + k * slot, edges[k]});
  return ch;
}

void draw_histogram(Canvas& c, const TextStyle& st, const HistogramChart& ch, const ChartColours& col, int hot) {
  const double line = line_of(c, st), tl = tick_len(line);
  const TextStyle label{st.size_pt, col.tick_text, false};
  for (const AxisTick& t : ch.count_axis) {
    c.line({ch.plot.x0 - tl, t.at}, {ch.plot.x0, t.at}, col.axis, 1);
    c.text({ch.plot.x0 - tl - 0.3 * line, t.at}, Anchor::kRight, label, t.text);
  }
  for (const AxisTick& t : ch.edge_axis) {
    c.line({t.at, ch.plot.y1}, {t.at, ch.plot.y1 + tl}, col.axis, 1);
    c.text({t.at, ch.plot.y1 + tl + 1}, Anchor::kTop, label, t.text);
  }
  for (size_t k = 0; k < ch.bars.size(); ++k)
    if (ch.bars[k].count > 0) c.fill_rect(ch.bars[k].bar, int(k) == hot ? col.bar_hot : col.bar);
  c.line({ch.plot.x0, ch.plot.y0}, {ch.plot.x0, ch.plot.y1}, col.axis, 1);
  c.line({ch.plot.x0, ch.plot.y1}, {ch.plot.x1, ch.plot.y1}, col.axis, 1);
  // The current bin: a bracket around its bar, open at the baseline, never over the bar itself.
  const double o = ch.outline_gap + 0.5 * ch.outline_width;
  for (const HistogramBar& b : ch.bars)
    if (b.current)
      c.polyline({{b.bar.x0 - o, b.bar.y1},
                  {b.bar.x0 - o, b.bar.y0 - o},
                  {b.bar.x1 + o, b.bar.y0 - o},
                  {b.bar.x1 + o, b.bar.y1}},
                 col.current, ch.outline_width, false);
}

double value_bars_height(Canvas& c, const TextStyle& st, size_t rows) {
  const double line = line_of(c, st);
  return rows * std::round(1.3 * line) + tick_len(line) + 1 + line;
}

ValueBarsChart layout_value_bars(Canvas& c, const TextStyle& st, const std::vector<ValueBarRow>& rows,
                                 const PtRect& area) {
  ValueBarsChart ch;
  const double line = line_of(c, st), row_h = std::round(1.3 * line);
  double label_w = 0, top = 0;
  for (const ValueBarRow& r : rows) {
    label_w = std::max(label_w, c.measure(st, r.label).x);
    for (double v : {r.value, r.high})
      if (std::isfinite(v)) top = std::max(top, v);
  }
  if (top <= 0) top = 1;
  const double x0 = area.x0 + label_w + 0.6 * line;
  // The most ticks whose labels keep apart (the last label's half width stays inside the area).
  std::vector<double> ticks;
  double half_last = 0;
  for (int target = 5; target >= 1; --target) {
    ticks = nice_ticks(0, top, target);
    const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : 1;
    if (ticks.back() < top * (1 - 1e-9))
      ticks.push_back(ticks.size() * step);  // the axis ends on a tick past every bar
    double widest = 0;
    for (double t : ticks) widest = std::max(widest, c.measure(st, tick_text(t, step)).x);
    half_last = 0.5 * c.measure(st, tick_text(ticks.back(), step)).x;
    if ((area.x1 - half_last - x0) / std::max<size_t>(1, ticks.size() - 1) > widest * 1.5) break;
  }
  ch.plot = {x0, area.y0, std::max(x0 + 1, area.x1 - half_last), area.y0 + rows.size() * row_h};
  const double hi = ticks.back(), step = ticks.size() > 1 ? ticks[1] - ticks[0] : 1;
  auto x = [&](double v) { return ch.plot.x0 + v / hi * ch.plot.width(); };
  for (double t : ticks) ch.value_axis.push_back({t, x(t), tick_text(t, step)});
  for (size_t i = 0; i < rows.size(); ++i) {
    const ValueBarRow& r = rows[i];
    ValueBarsChart::Row row;
    const double y0 = area.y0 + i * row_h, pad = std::round(0.15 * line);
    row.band = {area.x0, y0, area.x1, y0 + row_h};
    row.label_at = {x0 - 0.6 * line, y0 + 0.5 * row_h};
    if (std::isfinite(r.value)) row.bar = {x(0), y0 + pad, x(r.value), y0 + row_h - pad};
    if (std::isfinite(r.low) && std::isfinite(r.high)) row.whisker_x0 = x(r.low), row.whisker_x1 = x(r.high);
    ch.rows.push_back(row);
  }
  return ch;
}

void draw_value_bars(Canvas& c, const TextStyle& st, const ValueBarsChart& ch, const std::vector<ValueBarRow>& rows,
                     const ChartColours& col, int hot) {
  const double line = line_of(c, st), tl = tick_len(line);
  const TextStyle tick{st.size_pt, col.tick_text, false}, label{st.size_pt, col.label, false};
  for (const AxisTick& t : ch.value_axis) {
    c.line({t.at, ch.plot.y1}, {t.at, ch.plot.y1 + tl}, col.axis, 1);
    c.text({t.at, ch.plot.y1 + tl + 1}, Anchor::kTop, tick, t.text);
  }
  for (size_t i = 0; i < ch.rows.size() && i < rows.size(); ++i) {
    const ValueBarsChart::Row& r = ch.rows[i];
    c.text(r.label_at, Anchor::kRight, label, rows[i].label);
    if (r.bar.width() > 0) c.fill_rect(r.bar, int(i) == hot ? col.bar_hot : col.bar);
    if (r.whisker_x1 > r.whisker_x0) {
      const double ym = 0.5 * (r.band.y0 + r.band.y1), cap = 0.25 * line;
      c.line({r.whisker_x0, ym}, {r.whisker_x1, ym}, col.whisker, 1.5);
      c.line({r.whisker_x0, ym - cap}, {r.whisker_x0, ym + cap}, col.whisker, 1.5);
      c.line({r.whisker_x1, ym - cap}, {r.whisker_x1, ym + cap}, col.whisker, 1.5);
    }
  }
  c.line({ch.plot.x0, ch.plot.y0}, {ch.plot.x0, ch.plot.y1}, col.axis, 1);
  c.line({ch.plot.x0, ch.plot.y1}, {ch.plot.x1, ch.plot.y1}, col.axis, 1);
}

}  // namespace ipd::ui
