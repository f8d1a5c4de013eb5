#include "ui/figures/figure_common.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "ui/canvas/text_wrap.h"
#include "ui/figures/figure_options.h"

namespace ipd::ui::fig {

namespace {
constexpr double kLabelPad = 0.6;  // a label's backdrop margin around its text
}  // namespace

TextStyle style(double size_pt, Colour colour, bool bold) { return {std::max(kMinTextPt, size_pt), colour, bold}; }

std::vector<std::string> wrap(Canvas& c, const TextStyle& st, const std::string& text, double width) {
  // The studio's rule (ui/canvas/text_wrap.h): never "scene IPD" on one line and its number on the next.
  return wrap_at_spaces(text, static_cast<float>(width),
                        [&](const std::string& s) { return static_cast<float>(c.measure(st, s).x); });
}

double draw_wrapped(Canvas& c, Pt at, const TextStyle& st, const std::string& text, double width) {
  double y = at.y;
  for (const std::string& line : wrap(c, st, text, width)) {
    c.text({at.x, y}, Anchor::kTopLeft, st, line);
    y += c.measure(st, line).y;
  }
  return y - at.y;
}

double draw_legend(Canvas& c, Pt at, double width, const TextStyle& st, const std::vector<LegendItem>& items) {
  const double h = c.measure(st, "Ag").y, sw = h * 1.1, pad = h * 0.3, item_gap = h * 0.9;
  double x = at.x, y = at.y;
  for (const LegendItem& it : items) {
    const double w = sw + pad + c.measure(st, it.text).x;
    if (x > at.x && x + w > at.x + width) x = at.x, y += h * 1.15;
    const double cy = y + h / 2, lw = std::max(0.5, st.size_pt * 0.09);
    const bool halo = it.halo.a > 0;
    // Inset so a halo stays inside the swatch's cell (and off the figure's margin).
    const double inset = std::max(0.5, halo ? 0.5 * lw * 1.3 * kHaloRatio : 0.0);
    const PtRect box{x + inset, y + h * 0.18, x + sw - inset, y + h * 0.82};
    switch (it.swatch) {
      case Swatch::kBox:
        if (halo) c.rect(box, it.halo, lw * 1.3 * kHaloRatio);
        c.rect(box, it.colour, lw * 1.3);
        break;
      case Swatch::kDashedBox:
        if (halo) dashed_rect(c, box, it.halo, lw * 1.3 * kHaloRatio, box.width() * 0.32);
        dashed_rect(c, box, it.colour, lw * 1.3, box.width() * 0.32);
        break;
      case Swatch::kStruckBox:
        if (halo) {
          c.rect(box, it.halo, lw * 1.3 * kHaloRatio);
          c.line({box.x0, box.y0}, {box.x1, box.y1}, it.halo, lw * 1.3 * kHaloRatio);
        }
        c.rect(box, it.colour, lw * 1.3);
        c.line({box.x0, box.y0}, {box.x1, box.y1}, it.colour, lw * 1.3);
        break;
      case Swatch::kDot:
        c.fill_circle({x + sw / 2, cy}, h * 0.2, it.colour);
        break;
      case Swatch::kRing:
        c.circle({x + sw / 2, cy}, h * 0.3, it.colour, lw * 1.3);
        break;
      case Swatch::kLine:
        c.line({x, cy}, {x + sw, cy}, it.colour, lw * 1.5);
        break;
      case Swatch::kOutline:  // a stroke as the pictures draw it: on its halo
        if (halo) c.line({box.x0, cy}, {box.x1, cy}, it.halo, lw * 1.3 * kHaloRatio);
        c.line({box.x0, cy}, {box.x1, cy}, it.colour, lw * 1.3);
        break;
      case Swatch::kDashedOutline: {  // two dashes and a gap, as an outline's dashes
        const double dash = box.width() / 2.6;
        for (double x0 : {box.x0, box.x1 - dash}) {
          if (halo) c.line({x0, cy}, {x0 + dash, cy}, it.halo, lw * 1.3 * kHaloRatio);
          c.line({x0, cy}, {x0 + dash, cy}, it.colour, lw * 1.3);
        }
        break;
      }
    }
    c.text({x + sw + pad, y}, Anchor::kTopLeft, st, it.text);
    x += w + item_gap;
  }
  return y + h - at.y;
}

LabelPlacement place_figure_labels(Canvas& c, const std::vector<Label>& labels, const PtRect& bounds,
                                   const std::vector<PtRect>& taken) {
  std::vector<LabelRequest> req;
  for (const Label& l : labels) {
    const Pt m = c.measure(l.style, l.text);
    LabelRequest r{
        {l.target.x0, l.target.y0, l.target.x1, l.target.y1}, m.x + 2 * kLabelPad, m.y, l.exclusive, l.group};
    for (const PtRect& k : l.keep_off) r.keep_off.push_back({k.x0, k.y0, k.x1, k.y1});
    r.keep_off_clearance = l.keep_off_clearance;
    r.nearest_own = l.nearest_own;
    req.push_back(std::move(r));
  }
  LabelPlacementOptions o;
  o.bounds = {bounds.x0, bounds.y0, bounds.x1, bounds.y1};
  for (const PtRect& t : taken) o.taken.push_back({t.x0, t.y0, t.x1, t.y1});
  o.gap = 0.5;
  o.max_leader = 3;
  o.exclusive_clearance = kExclusiveClearancePt;
  return place_labels(req, o);
}

void draw_placed_labels(Canvas& c, const std::vector<Label>& labels, const LabelPlacement& p, bool backdrop) {
  for (size_t i = 0; i < labels.size(); ++i) {
    const PlacedLabel& pl = p.labels[i];
    if (!pl.shown()) continue;
    if (pl.position == LabelPosition::kLeader)
      c.line({pl.leader_x0, pl.leader_y0}, {pl.leader_x1, pl.leader_y1}, labels[i].style.colour,
             std::max(kLeaderPt, labels[i].style.size_pt * 0.06));
    if (backdrop) c.fill_rect({pl.box.x0, pl.box.y0, pl.box.x1, pl.box.y1}, kBackdrop);
    c.text({pl.box.x0 + kLabelPad, pl.box.y0}, Anchor::kTopLeft, labels[i].style, labels[i].text);
  }
}

int draw_labels(Canvas& c, const std::vector<Label>& labels, const PtRect& bounds, const std::vector<PtRect>& taken,
                bool backdrop, LabelPlacement* placement) {
  const LabelPlacement p = place_figure_labels(c, labels, bounds, taken);
  draw_placed_labels(c, labels, p, backdrop);
  if (placement) *placement = p;
  return p.left_out;
}

double outline_dash(double perimeter_pt, double dash) {
  return std::max(kMinDashPt, std::min(dash, perimeter_pt / (kMinDashes * 1.6)));
}

void dashed_polygon(Canvas& c, const std::vector<Pt>& points, Colour colour, double width_pt, double dash) {
  double perimeter = 0;
  for (size_t k = 0; k < points.size(); ++k)
    perimeter +=
        std::hypot(points[(k + 1) % points.size()].x - points[k].x, points[(k + 1) % points.size()].y - points[k].y);
  dash = outline_dash(perimeter, dash);
  const double gap = 0.6 * dash;
  double phase = 0;  // carried from edge to edge, so short edges of a fine outline still show dashes
  for (size_t k = 0; k < points.size(); ++k) {
    const Pt a = points[k], b = points[(k + 1) % points.size()];
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    if (len <= 0) continue;
    const double ux = (b.x - a.x) / len, uy = (b.y - a.y) / len;
    for (double t = -phase; t < len; t += dash + gap) {
      const double s = std::max(0.0, t), e = std::min(len, t + dash);
      if (e > s) c.line({a.x + ux * s, a.y + uy * s}, {a.x + ux * e, a.y + uy * e}, colour, width_pt);
    }
    phase = std::fmod(phase + len, dash + gap);
  }
}

void dashed_rect(Canvas& c, const PtRect& r, Colour colour, double width_pt, double dash) {
  dash = outline_dash(2 * (std::abs(r.width()) + std::abs(r.height())), dash);
  const double gap = 0.6 * dash;
  const auto edge = [&](Pt a, Pt b) {
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    if (len <= 0) return;
    const double ux = (b.x - a.x) / len, uy = (b.y - a.y) / len;
    for (double t = 0; t < len; t += dash + gap) {
      const double e = std::min(len, t + dash);
      c.line({a.x + ux * t, a.y + uy * t}, {a.x + ux * e, a.y + uy * e}, colour, width_pt);
    }
  };
  edge({r.x0, r.y0}, {r.x1, r.y0});
  edge({r.x1, r.y0}, {r.x1, r.y1});
  edge({r.x1, r.y1}, {r.x0, r.y1});
  edge({r.x0, r.y1}, {r.x0, r.y0});
}

std::string wider_hint(double width_in) {
  return width_in <= kSingleColumnIn + 0.01 ? "--column double" : "a larger --width-in";
}

double draw_footnote(Canvas& c, Pt at, double width, double font_pt, int left_out, const std::string& hint) {
  if (left_out <= 0) return 0;
  const TextStyle st = style(secondary_pt(font_pt), kGrey);
  return draw_wrapped(c, at, st,
                      fmt::format("{} label{} left out: no room at this size{}", left_out, left_out == 1 ? "" : "s",
                                  hint.empty() ? "" : " (try " + hint + ")"),
                      width);
}

}  // namespace ipd::ui::fig
