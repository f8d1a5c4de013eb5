#include "ui/figures/scene_panels.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace ipd::ui::scene {

using namespace fig;

double aspect_of(const SceneFigureInput& in, const Crop& crop) {
  int w = in.image_w, h = in.image_h;
  if (!in.picture_a.empty()) w = in.picture_a.cols, h = in.picture_a.rows;
  const double a = (w > 0 && h > 0) ? double(w) / h : 1936.0 / 1216.0;
  return a * (crop.x1 - crop.x0) / (crop.y1 - crop.y0);
}

namespace {

// The pairs whose number is shown on a side.
std::set<int> shown_pairs(const SideLabels& s, const LabelPlacement& p) {
  std::set<int> out;
  for (size_t i = 0; i < s.labels.size(); ++i)
    if (s.pair[i] > 0 && p.labels[i].shown()) out.insert(s.pair[i]);
  return out;
}
std::set<int> requested_pairs(const SideLabels& s) {
  std::set<int> out;
  for (int p : s.pair)
    if (p > 0) out.insert(p);
  return out;
}

}  // namespace

TwoPanelLabels place_on_both(Canvas& c, const std::function<SideLabels(int, const std::set<int>&)>& make,
                             const PtRect bounds[2], const std::vector<PtRect> taken[2]) {
  TwoPanelLabels t;
  for (;;) {
    std::set<int> requested[2], shown[2];
    for (int k = 0; k < 2; ++k) {
      t.side[k] = make(k, t.unnumbered);
      t.placed[k] = place_figure_labels(c, t.side[k].labels, bounds[k], taken[k]);
      requested[k] = requested_pairs(t.side[k]);
      shown[k] = shown_pairs(t.side[k], t.placed[k]);
    }
    const size_t before = t.unnumbered.size();
    for (int p : requested[0])  // in view on both panels, its number shown on one only
      if (requested[1].count(p) && shown[0].count(p) != shown[1].count(p)) t.unnumbered.insert(p);
    if (t.unnumbered.size() == before) {
      for (int p : requested[0])  // shown on neither: counted with the dropped ones
        if (requested[1].count(p) && !shown[0].count(p)) t.unnumbered.insert(p);
      for (int k = 0; k < 2; ++k)
        for (size_t i = 0; i < t.side[k].labels.size(); ++i)
          if (!t.placed[k].labels[i].shown() && !t.unnumbered.count(t.side[k].pair[i])) ++t.left_out_other[k];
      return t;
    }
  }
}

// "N pairs unnumbered: ..." for both scene figures.
std::string unnumbered_note(int n, const FigureOptions& o) {
  return fmt::format(
      "{} pair{} unnumbered: no room for {} number on both pictures (to show {}: --crop, fewer "
      "--layers or {})",
      n, n == 1 ? "" : "s", n == 1 ? "its" : "their", n == 1 ? "it" : "them", wider_hint(o.width_in));
}

double draw_title(Canvas& c, const std::string& title, const FigureOptions& o) {
  return kMargin + draw_wrapped(c, {kMargin, kMargin}, style(o.font_pt, kInk), title, o.width_pt() - 2 * kMargin);
}

PanelPlan plan_panels(Canvas& c, const SceneFigureInput& in, const FigureOptions& o, double y, bool stacked) {
  const double W = o.width_pt(), F = o.font_pt, gap = std::max(4.0, 0.5 * F);
  const TextStyle caption = style(F, kInk, true);
  const double caption_h = c.measure(caption, "Ag").y + 0.15 * F;
  PanelPlan p;
  if (!stacked) {
    const double pw = (W - 2 * kMargin - gap) / 2, ph = pw / aspect_of(in, o.crop);
    for (int k = 0; k < 2; ++k) {
      const double x = kMargin + k * (pw + gap);
      p.caption[k] = {x, y};
      p.panel[k] = {x, y + caption_h, x + pw, y + caption_h + ph};
    }
    p.bottom = y + caption_h + ph;
    return p;
  }
  const double pw = W - 2 * kMargin, ph = pw / aspect_of(in, o.crop);
  for (int k = 0; k < 2; ++k) {
    p.caption[k] = {kMargin, y};
    p.panel[k] = {kMargin, y + caption_h, kMargin + pw, y + caption_h + ph};
    y += caption_h + ph + (k == 0 ? 0.5 * F : 0);
  }
  p.bottom = y;
  return p;
}

bool choose_stacked(const FontMetrics& metrics, const FigureOptions& o,
                    const std::function<Numbered(DisplayList&, bool)>& draw) {
  if (o.panels == PanelArrangement::kStacked) return true;
  if (o.panels == PanelArrangement::kSideBySide) return false;
  DisplayList side(metrics);
  const Numbered s = draw(side, false);
  if (s.pairs == 0 || s.pairs - s.unnumbered >= kNumberedShare * s.pairs) return false;
  DisplayList stacked(metrics);
  return draw(stacked, true).unnumbered < s.unnumbered;
}

Crop rocks_crop(const SceneFigureInput& in, bool registration) {
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  const auto take = [&](double ax, double ay, double bx, double by) {
    x0 = std::min(x0, ax), y0 = std::min(y0, ay), x1 = std::max(x1, bx), y1 = std::max(y1, by);
  };
  for (const auto* list : {&in.gt_a, &in.gt_b})
    for (const Box& b : *list) take(b.x0(), b.y0(), b.x1(), b.y1());
  if (registration)
    for (const Box& b : in.gt_a) {
      const Eigen::Vector2d q = apply(in.affine, b.centre());
      take(q.x(), q.y(), q.x(), q.y());
    }
  if (!(x1 > x0 && y1 > y0)) return {};
  // The picture's own shape (as wide as high in normalised units): a crop flatter than the picture would make
  // the panels shorter and leave the numbers less room, not more. Widened about the rocks' centre, moved back
  // inside the picture.
  const double side = std::min(1.0, std::max(x1 - x0, y1 - y0) + 2 * kCropMargin);
  const auto span = [&](double lo, double hi) {
    const double start = std::clamp((lo + hi) / 2 - side / 2, 0.0, 1.0 - side);
    return std::pair<double, double>{start, start + side};
  };
  const auto [cx0, cx1] = span(x0, x1);
  const auto [cy0, cy1] = span(y0, y1);
  return {cx0, cy0, cx1, cy1};
}

}  // namespace ipd::ui::scene
