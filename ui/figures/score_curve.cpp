#include "ui/figures/score_curve.h"

#include <algorithm>
#include <cmath>

#include "core/util/number_text.h"
#include "ui/figures/figure_charts.h"

namespace ipd::ui {

const char* score_direction(FitMeasure measure) {
  return lower_is_better(measure) ? "lower is better" : "higher is better";
}

ScoreCurve layout_score_curve(Canvas& c, const TextStyle& st, const ScoreCurveInput& in, const PtRect& area) {
  ScoreCurve out;
  const double line = c.measure(st, "0").y, tick = std::round(0.3 * line);
  double lo = INFINITY, hi = -INFINITY;
  for (double v : in.best)
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (!(lo <= hi)) lo = 0, hi = 1;
  if (hi - lo < 1e-12) lo -= 0.5, hi += 0.5;  // a flat curve: a unit range around it
  // Few value ticks: the strip is short. The widest label sets the plot's left edge.
  std::vector<double> vt = nice_ticks(lo, hi, area.height() > 6 * line ? 4 : 2);
  const double step = vt.size() > 1 ? vt[1] - vt[0] : 1;
  if (vt.back() < hi - 1e-12) vt.push_back(vt.back() + step);  // the axis covers the highest value
  double label_w = 0;
  for (double v : vt) label_w = std::max(label_w, c.measure(st, tick_text(v, step)).x);
  // The last step's label is centred on the plot's right end: half of it must fit inside the area ("5000" was
  // cut to "500" at the panel's edge).
  const int n = static_cast<int>(in.best.size());
  const double last_half = c.measure(st, grouped_thousands(std::max(1, n))).x / 2;
  out.plot = {area.x0 + label_w + tick + 2, area.y0 + 0.5 * line, area.x1 - std::max(2.0, last_half + 1),
              area.y1 - line - tick - 1};
  if (out.plot.y1 <= out.plot.y0) out.plot.y1 = out.plot.y0 + 1;
  const double v0 = vt.front(), v1 = vt.back();
  const auto y_of = [&](double v) { return out.plot.y1 - (v - v0) / (v1 - v0) * out.plot.height(); };
  for (double v : vt) out.value_axis.push_back({v, y_of(v), tick_text(v, step)});
  const auto x_of = [&](double k) { return out.plot.x0 + (n > 1 ? k / (n - 1) : 0.5) * out.plot.width(); };
  for (int k = 0; k < n; ++k)
    if (std::isfinite(in.best[k])) out.points.push_back({x_of(k), y_of(in.best[k])});
  // Step ticks numbered from 1 (the replay's "step 1 of N"), with thousands separators as the replay's counts,
  // the first and the last one always shown.
  const std::vector<double> st_ticks = nice_ticks(1, std::max(1, n), std::max(2, int(out.plot.width() / (6 * line))));
  const auto step_label = [](double s) { return grouped_thousands(std::llround(s)); };
  if (n > 0) out.step_axis.push_back({1, x_of(0), "1"});
  for (double s : st_ticks) {
    if (!(s > 1 && s <= n && s == std::round(s))) continue;
    // A tick too close to "1" gives way to it.
    if (x_of(s - 1) - out.step_axis.front().at < c.measure(st, "1  " + step_label(s)).x) continue;
    out.step_axis.push_back({s, x_of(s - 1), step_label(s)});
  }
  if (n > 1 && out.step_axis.back().value < n) {
    // The last step's label replaces a tick too close to it.
    const double x = x_of(n - 1);
    const std::string t = step_label(n);
    const auto crowded = [&] {
      return x - out.step_axis.back().at < c.measure(st, t + "  " + out.step_axis.back().text).x;
    };
    if (crowded() && out.step_axis.size() > 1) out.step_axis.pop_back();  // "1" stays
    if (!crowded()) out.step_axis.push_back({double(n), x, t});
  }
  if (in.current >= 0 && in.current < n) out.current_x = x_of(in.current);
  out.direction = score_direction(in.measure);
  if (lower_is_better(in.measure)) {
    out.direction_at = {out.plot.x1 - 2, out.plot.y0 + 1};
    out.direction_anchor = Anchor::kTopRight;
  } else {
    out.direction_at = {out.plot.x1 - 2, out.plot.y1 - 1};
    out.direction_anchor = Anchor::kBottomRight;
  }
  return out;
}

void draw_score_curve(Canvas& c, const TextStyle& st, const ScoreCurve& ch, const ChartColours& col) {
  const double line = c.measure(st, "0").y, tick = std::round(0.3 * line);
  const TextStyle tick_st{st.size_pt, col.tick_text, false};
  c.line({ch.plot.x0, ch.plot.y0}, {ch.plot.x0, ch.plot.y1}, col.axis, 1);
  c.line({ch.plot.x0, ch.plot.y1}, {ch.plot.x1, ch.plot.y1}, col.axis, 1);
  for (const AxisTick& t : ch.value_axis) {
    c.line({ch.plot.x0 - tick, t.at}, {ch.plot.x0, t.at}, col.axis, 1);
    c.text({ch.plot.x0 - tick - 2, t.at}, Anchor::kRight, tick_st, t.text);
  }
  for (const AxisTick& t : ch.step_axis) {
    c.line({t.at, ch.plot.y1}, {t.at, ch.plot.y1 + tick}, col.axis, 1);
    c.text({t.at, ch.plot.y1 + tick + 1}, Anchor::kTop, tick_st, t.text);
  }
  if (ch.points.size() > 1) c.polyline(ch.points, col.bar_hot, 1.5, false);
  if (ch.points.size() == 1) c.fill_circle(ch.points.front(), 2, col.bar_hot);
  if (ch.current_x >= 0) c.line({ch.current_x, ch.plot.y0}, {ch.current_x, ch.plot.y1}, col.current, 1.5);
  c.text(ch.direction_at, ch.direction_anchor, TextStyle{st.size_pt, col.label, false}, ch.direction);
}

}  // namespace ipd::ui
