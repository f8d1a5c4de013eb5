#include "ui/figures/figure_sweep.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "ui/figures/figure_charts.h"
#include "ui/figures/figure_common.h"

namespace ipd::ui {

using namespace fig;

namespace {

std::string names_of(const std::vector<std::pair<std::string, double>>& params) {
  std::string s;
  for (const auto& p : params) s += (s.empty() ? "" : ", ") + p.first;
  return "{" + s + "}";
}

std::set<std::string> name_set(const std::vector<std::pair<std::string, double>>& params) {
  std::set<std::string> s;
  for (const auto& p : params) s.insert(p.first);
  return s;
}

double value_of(const std::vector<std::pair<std::string, double>>& params, const std::string& name) {
  for (const auto& p : params)
    if (p.first == name) return p.second;
  return NAN;
}

}  // namespace

SweepChart sweep_chart(const Ranking& k, const std::string& choose) {
  const std::string hint = choose.empty() ? std::string() : " (" + choose + ")";
  const std::string then = choose.empty() ? std::string() : "; " + choose;
  if (k.ranked.empty()) throw StudyError("nothing to plot: no candidate was ranked");
  const RankedCandidate& first = k.ranked.front();
  for (const RankedCandidate& r : k.ranked) {
    if (r.params.empty())
      throw StudyError(fmt::format(
          "{} has no parameters in study.yaml (domains: {{{}: {{params: {{...}}}}}}); a sweep plots IPD against the "
          "parameters of its variants{}",
          r.domain, r.domain, hint));
    if (name_set(r.params) != name_set(first.params))
      throw StudyError(fmt::format(
          "the variants have different parameters: {} has {}, {} has {}; a sweep plots variants that share their "
          "parameter names{}",
          first.domain, names_of(first.params), r.domain, names_of(r.params), hint));
  }
  SweepChart c;
  for (const auto& [name, value] : first.params) {
    const bool varies = std::any_of(k.ranked.begin(), k.ranked.end(),
                                    [&](const RankedCandidate& r) { return value_of(r.params, name) != value; });
    if (varies) c.parameters.push_back(name);
  }
  if (c.parameters.empty())
    throw StudyError(fmt::format("no parameter varies among the variants ({} is the same in all): nothing to sweep",
                                 names_of(first.params)));
  if (c.parameters.size() > 2) {
    std::string list;
    for (const auto& p : c.parameters) list += (list.empty() ? "" : ", ") + p;
    throw StudyError(fmt::format("{} parameters vary ({}): a sweep plots one (a line) or two (a heat map){}",
                                 c.parameters.size(), list, then));
  }
  for (const RankedCandidate& r : k.ranked) {
    SweepPoint p;
    p.domain = r.domain;
    p.x = value_of(r.params, c.parameters[0]);
    p.y = c.parameters.size() > 1 ? value_of(r.params, c.parameters[1]) : 0;
    p.ipd = r.ipd;
    p.low = r.ci_low;
    p.high = r.ci_high;
    p.best = r.rank == 1;
    p.in_group = r.in_best_group;
    c.points.push_back(p);
  }
  std::sort(c.points.begin(), c.points.end(), [](const SweepPoint& a, const SweepPoint& b) {
    return std::make_pair(a.x, a.y) < std::make_pair(b.x, b.y);
  });
  c.title = fmt::format("IPD({}, variant) for {} along {}", k.ref, k.model,
                        c.parameters.size() == 1 ? c.parameters[0] : c.parameters[0] + " and " + c.parameters[1]);
  std::string group;
  for (const auto& r : k.ranked)
    if (r.in_best_group) group += (group.empty() ? "" : ", ") + r.domain;
  c.footnote = fmt::format(
      "Best: {} (IPD {:.4f}). {}: not distinguishable from the best at level {:g} (paired sign-flip test, "
      "Holm-corrected over {} comparison{}). {}",
      k.best()->domain, k.best()->ipd, c.parameters.size() == 1 ? "Filled dots" : "Values marked \u2248",
      k.options.level, k.tests, k.tests == 1 ? "" : "s",
      c.parameters.size() == 1 ? "Band: scene-bootstrap interval." : "Values: IPD, lower is better.");
  return c;
}

namespace {

// The gap between the value axis' title and its top tick label, in font sizes (about 2.4 pt at 8 pt).
constexpr double kAxisTitleGap = 0.3;

// A vertical value axis at x (ticks to its left), from y_bottom (lo) up to y_top (hi); returns its width.
double draw_value_axis(Canvas& c, double x, double y_top, double y_bottom, double lo, double hi,
                       const std::vector<double>& ticks, double right, const FigureOptions& o) {
  const TextStyle tick = style(secondary_pt(o.font_pt), kInk);
  const double lw = std::max(0.35, o.font_pt * 0.06), step = ticks.size() > 1 ? ticks[1] - ticks[0] : 1;
  auto at = [&](double v) { return y_bottom - (v - lo) / (hi - lo) * (y_bottom - y_top); };
  c.line({x, y_top}, {x, y_bottom}, kInk, lw);
  for (double t : ticks) {
    c.line({x, at(t)}, {right, at(t)}, rgb(225, 225, 225), lw);
    c.line({x - o.font_pt * 0.3, at(t)}, {x, at(t)}, kInk, lw);
    c.text({x - o.font_pt * 0.4, at(t)}, Anchor::kRight, tick, tick_text(t, step));
  }
  return 0;
}

double widest_tick(Canvas& c, const std::vector<double>& ticks, const FigureOptions& o) {
  const TextStyle tick = style(secondary_pt(o.font_pt), kInk);
  const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : 1;
  double w = 0;
  for (double t : ticks) w = std::max(w, c.measure(tick, tick_text(t, step)).x);
  return w;
}

// The heat map's shade of a value in [lo, hi]: luminance falls steadily from light (low IPD) to dark, so the
// order survives greyscale print.
Colour shade(double v, double lo, double hi) {
  const double t = hi > lo ? std::clamp((v - lo) / (hi - lo), 0.0, 1.0) : 0.0;
  auto mix = [&](double a, double b) { return static_cast<int>(std::lround(a + (b - a) * t)); };
  return rgb(mix(247, 24), mix(251, 48), mix(255, 107));
}

// The interval between the points as a grey band, filled in thin vertical strips (the canvas fills rectangles,
// not polygons), with its edges drawn.
template <typename ToX, typename ToY>
void draw_band(Canvas& out, const SweepChart& ch, ToX&& X, ToY&& Y, double lw) {
  std::vector<Pt> upper, lower;
  for (const auto& p : ch.points)
    if (std::isfinite(p.low) && std::isfinite(p.high))
      upper.push_back({X(p.x), Y(p.high)}), lower.push_back({X(p.x), Y(p.low)});
  if (upper.size() >= 2) {
    const Colour band = rgb(200, 200, 200);
    for (size_t i = 0; i + 1 < upper.size(); ++i) {
      const int strips = std::max(1, static_cast<int>((upper[i + 1].x - upper[i].x) / 0.5));
      for (int s = 0; s < strips; ++s) {
        const double t0 = static_cast<double>(s) / strips, t1 = static_cast<double>(s + 1) / strips;
        const double xa = upper[i].x + (upper[i + 1].x - upper[i].x) * t0;
        const double xb = upper[i].x + (upper[i + 1].x - upper[i].x) * t1;
        const double tm = 0.5 * (t0 + t1);
        const double ya = upper[i].y + (upper[i + 1].y - upper[i].y) * tm;
        const double yb = lower[i].y + (lower[i + 1].y - lower[i].y) * tm;
        out.fill_rect({xa, ya, xb + 0.05, yb}, band);
      }
    }
    out.polyline(upper, kGrey, lw * 0.7, false);
    out.polyline(lower, kGrey, lw * 0.7, false);
  }
}

void draw_line_sweep(DisplayList& out, const SweepChart& ch, const FigureOptions& o, double y) {
  const double W = o.width_pt(), F = o.font_pt;
  const TextStyle body = style(F, kInk), small = style(secondary_pt(F), kInk);
  double lo = INFINITY, hi = -INFINITY, xlo = INFINITY, xhi = -INFINITY;
  for (const auto& p : ch.points) {
    for (double v : {p.ipd, p.low, p.high})
      if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    xlo = std::min(xlo, p.x), xhi = std::max(xhi, p.x);
  }
  lo = 0;  // IPD is read as a length from 0
  if (!(hi > lo)) hi = lo + 1;
  std::vector<double> yt = nice_ticks(lo, hi, 5);
  // The axis ends on a labelled tick above the highest value.
  if (yt.size() > 1 && yt.back() < hi - 1e-12) yt.push_back(yt.back() + (yt[1] - yt[0]));
  hi = std::max(hi, yt.back());
  if (!(xhi > xlo)) xhi = xlo + 1;
  const double xpad = (xhi - xlo) * 0.04;
  const std::vector<double> xt = nice_ticks(xlo, xhi, std::max(2, static_cast<int>((W - 60) / 40)));
  const double axis_lo = std::min(xlo - xpad, xt.front()), axis_hi = std::max(xhi + xpad, xt.back());
  // The value axis' label above it, at the top left (a rotated label would need a rotated font).
  out.text({kFigureMargin, y}, Anchor::kTopLeft, small, "IPD (lower is better)");
  // The top tick's label is centred on the axis' end, half its height above it: the title clears that half
  // and a gap (kAxisTitleGap font sizes), so the two never touch.
  const double text_h = out.measure(small, "Ag").y;
  y += text_h + 0.5 * text_h + kAxisTitleGap * F;
  const double x0 = kFigureMargin + widest_tick(out, yt, o) + 0.8 * F, x1 = W - kFigureMargin - 0.5 * F;
  const double plot_h = std::max(90.0, 0.55 * (x1 - x0));
  const double top = y, bottom = y + plot_h;
  auto X = [&](double v) { return x0 + (v - axis_lo) / (axis_hi - axis_lo) * (x1 - x0); };
  auto Y = [&](double v) { return bottom - (v - lo) / (hi - lo) * (bottom - top); };
  draw_value_axis(out, x0, top, bottom, lo, hi, yt, x1, o);
  const double lw = std::max(0.4, F * 0.08);
  draw_band(out, ch, X, Y, lw);
  std::vector<Pt> line;
  for (const auto& p : ch.points) line.push_back({X(p.x), Y(p.ipd)});
  out.polyline(line, kInk, lw * 1.5, false);
  const double r = std::max(1.6, F * 0.28);
  for (const auto& p : ch.points) {
    const Pt at{X(p.x), Y(p.ipd)};
    if (p.in_group)
      out.fill_circle(at, r, kInk);
    else {
      out.fill_circle(at, r, kWhite);
      out.circle(at, r, kInk, lw);
    }
    if (p.best) out.circle(at, r * 2.1, kInk, lw * 1.5);
  }
  // The best, named beside its ring.
  for (const auto& p : ch.points)
    if (p.best) {
      const Pt at{X(p.x), Y(p.ipd)};
      out.text({at.x, at.y + r * 2.4}, Anchor::kTop, small, "best: " + p.domain);
    }
  out.line({x0, bottom}, {x1, bottom}, kInk, lw);
  const double step = xt.size() > 1 ? xt[1] - xt[0] : 1;
  double h = 0;
  for (double t : xt) {
    out.line({X(t), bottom}, {X(t), bottom + F * 0.3}, kInk, lw);
    out.text({X(t), bottom + F * 0.35}, Anchor::kTop, small, tick_text(t, step));
    h = std::max(h, F * 0.35 + out.measure(small, "0").y);
  }
  out.text({(x0 + x1) / 2, bottom + h + 0.2 * F}, Anchor::kTop, body, ch.parameters[0]);
  out.height_pt = bottom + h + 0.2 * F + out.measure(body, "Ag").y;
}

void draw_heat_sweep(DisplayList& out, const SweepChart& ch, const FigureOptions& o, double y) {
  const double W = o.width_pt(), F = o.font_pt;
  const TextStyle body = style(F, kInk), small = style(secondary_pt(F), kInk);
  std::vector<double> xs, ys;
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& p : ch.points) {
    if (std::find(xs.begin(), xs.end(), p.x) == xs.end()) xs.push_back(p.x);
    if (std::find(ys.begin(), ys.end(), p.y) == ys.end()) ys.push_back(p.y);
    lo = std::min(lo, p.ipd), hi = std::max(hi, p.ipd);
  }
  std::sort(xs.begin(), xs.end());
  std::sort(ys.begin(), ys.end());
  std::vector<std::string> ylabels;
  double yw = 0;
  for (double v : ys)
    ylabels.push_back(fmt::format("{:g}", v)), yw = std::max(yw, out.measure(small, ylabels.back()).x);
  out.text({kFigureMargin, y}, Anchor::kTopLeft, small, ch.parameters[1] + " (rows) \u2193");
  y += out.measure(small, "Ag").y + 0.3 * F;
  const double x0 = kFigureMargin + yw + 0.6 * F, x1 = W - kFigureMargin;
  const double cw = (x1 - x0) / xs.size();
  const double chh = std::max(out.measure(small, "0.0000").y * 2.2, std::min(cw * 0.6, 28.0));
  const double lw = std::max(0.4, F * 0.08);
  for (size_t j = 0; j < ys.size(); ++j)
    out.text({x0 - 0.4 * F, y + chh * (j + 0.5)}, Anchor::kRight, small, ylabels[j]);
  for (const auto& p : ch.points) {
    const size_t i = std::find(xs.begin(), xs.end(), p.x) - xs.begin();
    const size_t j = std::find(ys.begin(), ys.end(), p.y) - ys.begin();
    const PtRect cell{x0 + cw * i, y + chh * j, x0 + cw * (i + 1), y + chh * (j + 1)};
    const Colour c = shade(p.ipd, lo, hi);
    out.fill_rect(cell, c);
    const bool dark = (c.r * 0.299 + c.g * 0.587 + c.b * 0.114) < 128;
    const TextStyle value = style(secondary_pt(F), dark ? kWhite : kInk, p.best);
    out.text({(cell.x0 + cell.x1) / 2, (cell.y0 + cell.y1) / 2}, Anchor::kCentre, value,
             fmt::format("{:.3f}{}", p.ipd, p.in_group && !p.best ? "\u2248" : ""));
    if (p.best) out.rect({cell.x0 + lw, cell.y0 + lw, cell.x1 - lw, cell.y1 - lw}, dark ? kWhite : kInk, lw * 3);
  }
  const double bottom = y + chh * ys.size();
  double h = 0;
  for (size_t i = 0; i < xs.size(); ++i) {
    out.text({x0 + cw * (i + 0.5), bottom + 0.3 * F}, Anchor::kTop, small, fmt::format("{:g}", xs[i]));
    h = std::max(h, 0.3 * F + out.measure(small, "0").y);
  }
  out.text({(x0 + x1) / 2, bottom + h + 0.2 * F}, Anchor::kTop, body, ch.parameters[0] + " (columns)");
  out.height_pt = bottom + h + 0.2 * F + out.measure(body, "Ag").y;
}

}  // namespace

void draw_sweep_chart(DisplayList& out, const SweepChart& ch, const FigureOptions& o) {
  o.check();
  const double W = o.width_pt(), F = o.font_pt;
  const TextStyle body = style(F, kInk);
  const double y = kFigureMargin +
                   draw_wrapped(out, {kFigureMargin, kFigureMargin}, body, ch.title, W - 2 * kFigureMargin) + 0.5 * F;
  if (ch.parameters.size() == 1)
    draw_line_sweep(out, ch, o, y);
  else
    draw_heat_sweep(out, ch, o, y);
  double bottom = out.height_pt;
  if (!ch.footnote.empty())
    bottom += 0.4 * F + draw_wrapped(out, {kFigureMargin, bottom + 0.4 * F}, style(secondary_pt(F), kGrey), ch.footnote,
                                     W - 2 * kFigureMargin);
  out.width_pt = W;
  out.height_pt = std::ceil(bottom + kFigureMargin);
}

}  // namespace ipd::ui
