// Fig. 2 of one scene: GT centres before and after registration, lines between partners, pair numbers on both
// panels or on neither.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "ui/figures/figure_scene.h"
#include "ui/figures/scene_panels.h"

namespace ipd::ui {

using namespace fig;
using namespace scene;

namespace {

// One panel of Fig. 2: B's GT centres (rings), A's (dots; moved by the affine when `aligned`) and the pair
// lines. Returns the panel's pair numbers, placed later on both panels together.
SideLabels draw_registration_panel(DisplayList& out, const SceneFigureInput& in, const PanelMap& m, bool aligned,
                                   const FigureOptions& o) {
  const double F = o.font_pt;
  const double dot = std::max(0.6, 0.11 * F), ring = dot * 2.8, lw = std::max(0.35, 0.07 * F);
  SideLabels numbers;
  out.fill_rect(m.panel, rgb(248, 248, 248));
  out.rect(m.panel, rgb(120, 120, 120), lw);
  std::vector<Pt> pa, pb;
  for (const Box& b : in.gt_a) {
    const Eigen::Vector2d q = aligned ? apply(in.affine, b.centre()) : b.centre();
    pa.push_back(m(q.x(), q.y()));
  }
  for (const Box& b : in.gt_b) pb.push_back(m(b.cx, b.cy));
  out.push_clip(m.panel);
  // Rings first, pair lines over them with a white halo, the (small) dots last: a line shorter than a
  // ring's radius (a small misalignment) still shows as a green stroke between the dot and the ring.
  if (o.layers.gt)
    for (const Pt& q : pb) out.circle(q, ring, kPinkC, lw * 1.4);
  if (o.layers.pairs) {
    for (int pass = 0; pass < 2; ++pass)
      for (const auto& [i, j] : in.pairs)
        if (i >= 0 && j >= 0 && i < int(pa.size()) && j < int(pb.size()))
          out.line(pa[i], pb[j], pass == 0 ? kWhite : kGreenC, pass == 0 ? lw * 3.2 : lw * 1.6);
  }
  if (o.layers.gt)
    for (const Pt& q : pa) out.fill_circle(q, dot, kBlueC);
  out.pop_clip();
  if (o.layers.gt && o.layers.indices) {
    std::vector<Label>& labels = numbers.labels;
    const auto square = [](Pt q, double r) { return PtRect{q.x - r, q.y - r, q.x + r, q.y + r}; };
    for (const auto& [i, j] : in.pairs) {
      if (i < 0 || i >= int(pa.size())) continue;
      const Pt q = pa[i];
      if (q.x < m.panel.x0 || q.x > m.panel.x1 || q.y < m.panel.y0 || q.y > m.panel.y1) continue;
      // A pair is named by its left rock, as in the GUI and the pairs figure (pair_numbers). The number
      // must read as this marker's: clear of every other dot and ring but its partner's, else moved with
      // a leader or left out.
      Label l{std::to_string(i + 1), style(F, kInk), square(q, ring), true, 0};
      for (size_t a = 0; a < pa.size(); ++a)
        if (int(a) != i) l.keep_off.push_back(square(pa[a], dot));
      for (size_t b = 0; b < pb.size(); ++b)
        if (int(b) != j) l.keep_off.push_back(square(pb[b], ring));
      l.keep_off_clearance = kExclusiveClearancePt;
      labels.push_back(std::move(l));
      numbers.pair.push_back(i + 1);
    }
  }
  return numbers;
}

std::vector<LegendItem> registration_legend(const SceneFigureInput& in, const FigureOptions& o) {
  std::vector<LegendItem> items;
  if (o.layers.gt) {
    items.push_back({Swatch::kDot, kBlueC, "GT centres of " + in.a});
    items.push_back({Swatch::kRing, kPinkC, "GT centres of " + in.b});
  }
  if (o.layers.pairs) items.push_back({Swatch::kLine, kGreenC, "rock pairs"});
  if (o.layers.indices && o.layers.gt) items.push_back({Swatch::kDot, kInk, "numbers: pairs, by " + in.a + " rock"});
  return items;
}

}  // namespace

namespace {

Numbered draw_registration(DisplayList& out, const SceneFigureInput& in, const FigureOptions& o, bool stacked) {
  const double W = o.width_pt(), F = o.font_pt;
  const std::string title = fmt::format("{}: GT box centres of {} and {}, {} ({} pair{})", in.stem, in.a, in.b,
                                        in.pairs_fixed ? "pairs fixed by hand" : "registration: " + in.method,
                                        in.pairs.size(), in.pairs.size() == 1 ? "" : "s");
  double y = draw_title(out, title, o) + 0.3 * F;
  const PanelPlan plan = plan_panels(out, in, o, y, stacked);
  const TextStyle caption = style(F, kInk, true);
  out.text(plan.caption[0], Anchor::kTopLeft, caption, "before registration");
  out.text(plan.caption[1], Anchor::kTopLeft, caption, in.pairs_fixed ? "aligned by the pairs" : "after registration");
  y = plan.bottom;
  SideLabels all[2];  // every pair number of each panel
  PtRect panels[2];
  for (int k = 0; k < 2; ++k) {
    const PanelMap m{plan.panel[k], o.crop};
    all[k] = draw_registration_panel(out, in, m, k == 1, o);
    panels[k] = m.panel;
  }
  const std::vector<PtRect> none[2];
  const TwoPanelLabels t = place_on_both(
      out,
      [&](int k, const std::set<int>& unnumbered) {
        SideLabels s;
        for (size_t i = 0; i < all[k].labels.size(); ++i)
          if (!unnumbered.count(all[k].pair[i])) s.labels.push_back(all[k].labels[i]), s.pair.push_back(all[k].pair[i]);
        return s;
      },
      panels, none);
  for (int k = 0; k < 2; ++k) draw_placed_labels(out, t.side[k].labels, t.placed[k], false);
  const int left_out = t.left_out_other[0] + t.left_out_other[1];
  y += 0.35 * F;
  if (o.layers.legend) y += draw_legend(out, {kMargin, y}, W - 2 * kMargin, style(F, kInk), registration_legend(in, o));
  double note_gap = o.layers.legend ? 0.2 * F : 0;
  if (!t.unnumbered.empty()) {
    y += note_gap + draw_wrapped(out, {kMargin, y + note_gap}, style(secondary_pt(F), kGrey),
                                 unnumbered_note(int(t.unnumbered.size()), o), W - 2 * kMargin);
    note_gap = 0;
  }
  if (left_out > 0)
    y += note_gap + draw_footnote(out, {kMargin, y + note_gap}, W - 2 * kMargin, F, left_out,
                                  "--crop or " + wider_hint(o.width_in));
  out.width_pt = W;
  out.height_pt = std::ceil(y + kMargin);
  return {int(in.pairs.size()), int(t.unnumbered.size())};
}

}  // namespace

void draw_registration_figure(DisplayList& out, const SceneFigureInput& in, const FigureOptions& options) {
  options.check();
  FigureOptions o = options;
  if (o.crop_auto) o.crop = rocks_crop(in, true);
  const bool stacked =
      choose_stacked(out.metrics(), o, [&](DisplayList& d, bool s) { return draw_registration(d, in, o, s); });
  draw_registration(out, in, o, stacked);
}

}  // namespace ipd::ui
