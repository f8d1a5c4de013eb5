#include "ui/figures/figure_scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>

#include "core/ipd/ipd.h"
#include "core/session/audit.h"
#include "ui/figures/figure_common.h"

namespace ipd::ui {

using namespace fig;

SceneNumbers scene_numbers(const SceneFigureInput& in) {
  ScenePairing p;
  p.stem = in.stem;
  p.pairs = in.pairs;
  p.fixed = in.pairs_fixed;
  p.excluded_a = in.excluded_a;
  p.excluded_b = in.excluded_b;
  p.count_a = int(in.gt_a.size());
  p.count_b = int(in.gt_b.size());
  const SceneIpd s = scene_ipd(p, in.gt_a, in.pred_a, in.gt_b, in.pred_b, in.task);
  return {s.ipd(), s.pairs};
}

namespace {

constexpr double kMargin = kFigureMargin;

double aspect_of(const SceneFigureInput& in, const Crop& crop) {
  int w = in.image_w, h = in.image_h;
  if (!in.picture_a.empty()) w = in.picture_a.cols, h = in.picture_a.rows;
  const double a = (w > 0 && h > 0) ? double(w) / h : 1936.0 / 1216.0;
  return a * (crop.x1 - crop.x0) / (crop.y1 - crop.y0);
}

// Normalised picture coordinates -> points inside a panel showing `crop`.
struct PanelMap {
  PtRect panel;
  Crop crop;
  Pt operator()(double x, double y) const {
    return {panel.x0 + (x - crop.x0) / (crop.x1 - crop.x0) * panel.width(),
            panel.y0 + (y - crop.y0) / (crop.y1 - crop.y0) * panel.height()};
  }
  // The box on the page, clipped to the panel; false when it is entirely outside.
  bool box(const Box& b, PtRect& out) const {
    const Pt p0 = (*this)(b.x0(), b.y0()), p1 = (*this)(b.x1(), b.y1());
    out = {std::max(p0.x, panel.x0), std::max(p0.y, panel.y0), std::min(p1.x, panel.x1), std::min(p1.y, panel.y1)};
    return out.x0 < out.x1 && out.y0 < out.y1;
  }
  PtRect raw(const Box& b) const {
    const Pt p0 = (*this)(b.x0(), b.y0()), p1 = (*this)(b.x1(), b.y1());
    return {p0.x, p0.y, p1.x, p1.y};
  }
  std::vector<Pt> outline(const Outline& o) const {
    std::vector<Pt> out;
    out.reserve(o.points.size());
    for (const Eigen::Vector2d& p : o.points) out.push_back((*this)(p.x(), p.y()));
    return out;
  }
};

// The crop of a picture at its own resolution (never resampled here), on whole pixels, and the normalised
// region those pixels cover (so boxes and pixels stay registered).
FigurePicture crop_picture(const cv::Mat& img, const Crop& c, Crop* covered) {
  const int x0 = std::clamp(int(std::floor(c.x0 * img.cols + 1e-6)), 0, img.cols - 1);
  const int y0 = std::clamp(int(std::floor(c.y0 * img.rows + 1e-6)), 0, img.rows - 1);
  const int x1 = std::clamp(int(std::ceil(c.x1 * img.cols - 1e-6)), x0 + 1, img.cols);
  const int y1 = std::clamp(int(std::ceil(c.y1 * img.rows - 1e-6)), y0 + 1, img.rows);
  *covered = {double(x0) / img.cols, double(y0) / img.rows, double(x1) / img.cols, double(y1) / img.rows};
  return {c.whole() ? img : img(cv::Rect(x0, y0, x1 - x0, y1 - y0)).clone()};
}

std::string title_of(const SceneFigureInput& in, const SceneNumbers& n) {
  // Two empty prediction sets are not a perfect match: no number, and why (no_predictions_reason).
  const std::string none =
      in.model.empty() ? std::string()
                       : no_predictions_reason(static_cast<long>(in.pred_a.size()), static_cast<long>(in.pred_b.size()),
                                               in.a, in.b, in.conf_threshold);
  const std::string value = !none.empty()       ? "not a number (" + none + ")"
                            : std::isnan(n.ipd) ? std::string("n/a")
                                                : fmt::format("{:.4f}", n.ipd);
  return fmt::format("{}: {} vs {}, model {}, scene IPD {} ({} pair{}){}{}", in.stem, in.a, in.b,
                     in.model.empty() ? "none" : in.model, value, n.pairs, n.pairs == 1 ? "" : "s",
                     in.conf_threshold > 0 ? fmt::format(", conf \u2265 {:g}", in.conf_threshold) : "",
                     in.pairs_fixed ? ", pairs fixed by hand" : "");
}

}  // namespace

PtRect place_notice(const PtRect& panel, Pt size, const std::vector<PtRect>& boxes, double inset) {
  const double left = panel.x0 + inset, right = panel.x1 - inset - size.x, top = panel.y0 + inset,
               bottom = panel.y1 - inset - size.y, mid_x = (panel.x0 + panel.x1 - size.x) / 2,
               mid_y = (panel.y0 + panel.y1 - size.y) / 2;
  const Pt corners[] = {{mid_x, top},    {mid_x, bottom}, {left, top},    {right, top},  {left, bottom},
                        {right, bottom}, {left, mid_y},   {right, mid_y}, {mid_x, mid_y}};
  PtRect best{};
  double least = INFINITY;
  for (const Pt& p : corners) {
    const PtRect at{p.x, p.y, p.x + size.x, p.y + size.y};
    double covered = 0;
    for (const PtRect& b : boxes)
      covered += std::max(0.0, std::min(at.x1, b.x1) - std::max(at.x0, b.x0)) *
                 std::max(0.0, std::min(at.y1, b.y1) - std::max(at.y0, b.y0));
    if (covered < least) least = covered, best = at;
  }
  return best;
}

namespace {

// The picture of one side of Fig. 1 (or a notice naming why there is none) and its boxes: GT solid and
// light on a dark halo, predictions dashed and dark on a light halo (figure_common.h: greyscale and
// colour-vision safe). Returns the notice's box, which labels keep off (empty rect with a picture).
PtRect draw_side_boxes(Canvas& c, const PanelMap& m, const cv::Mat& picture, const std::string& problem,
                       const std::vector<Box>& gt, const std::vector<Box>& pred, Task task,
                       const std::vector<int>& number, const std::vector<int>& excluded, const FigureOptions& o) {
  const FigureLayers& L = o.layers;
  const PtRect& P = m.panel;
  PtRect notice{};
  if (picture.empty()) {
    c.fill_rect(P, rgb(70, 70, 76));
    const TextStyle st = style(secondary_pt(o.font_pt), rgb(255, 200, 120));
    const std::string text = problem.empty() ? "no picture" : problem;
    // Where it crosses the fewest boxes (the rocks are what the figure is for), not over the middle rocks.
    std::vector<PtRect> boxes;
    PtRect r;
    for (const auto* list : {&gt, &pred})
      for (const Box& b : *list)
        if (m.box(b, r)) boxes.push_back(r);
    notice = place_notice(P, c.measure(st, text), boxes, 0.3 * o.font_pt);
    c.text({notice.x0, notice.y0}, Anchor::kTopLeft, st, text);
  } else {
    Crop covered;
    const FigurePicture pixels = crop_picture(picture, m.crop, &covered);
    const Pt p0 = m(covered.x0, covered.y0), p1 = m(covered.x1, covered.y1);
    c.push_clip(P);
    c.image(pixels, {p0.x, p0.y, p1.x, p1.y});
    c.pop_clip();
  }
  const double lw = std::max(0.35, o.font_pt * 0.07), dash = std::max(1.5, 4 * lw);
  const std::vector<int> best = performance_values(gt, pred, task).best_prediction;
  c.push_clip(P);
  PtRect r;
  if (L.pred)
    for (size_t k = 0; k < pred.size(); ++k) {
      if (!m.box(pred[k], r)) continue;
      // A rock's best prediction (the one its performance value comes from) full strength, the others
      // thinner and fainter.
      const bool is_best = std::find(best.begin(), best.end(), int(k)) != best.end();
      const double w = is_best ? lw * 1.5 : lw;
      const auto faint = [&](Colour col) { return is_best ? col : rgb(col.r, col.g, col.b, col.a * 3 / 5); };
      if (pred[k].outline) {  // the mask the performance value is about, not its bounds
        const std::vector<Pt> q = m.outline(*pred[k].outline);
        dashed_polygon(c, q, faint(kLightHalo), w * kHaloRatio, dash);
        dashed_polygon(c, q, faint(kPredC), w, dash);
        continue;
      }
      dashed_rect(c, m.raw(pred[k]), faint(kLightHalo), w * kHaloRatio, dash);
      dashed_rect(c, m.raw(pred[k]), faint(kPredC), w, dash);
    }
  auto colour_of = [&](size_t k) { return (!L.pairs || number[k] > 0) ? kGtC : kGtUnpairedC; };
  if (L.gt)
    for (size_t k = 0; k < gt.size(); ++k) {
      if (!m.box(gt[k], r)) continue;
      const PtRect b = m.raw(gt[k]);
      const bool struck = std::find(excluded.begin(), excluded.end(), int(k)) != excluded.end();
      if (gt[k].outline) {
        const std::vector<Pt> q = m.outline(*gt[k].outline);
        c.polyline(q, kDarkHalo, lw * kHaloRatio, true);
        c.polyline(q, colour_of(k), lw, true);
      } else {
        c.rect(b, kDarkHalo, lw * kHaloRatio);
        c.rect(b, colour_of(k), lw);
      }
      if (struck) c.line({b.x0, b.y0}, {b.x1, b.y1}, kDarkHalo, lw * kHaloRatio);
      if (struck) c.line({b.x0, b.y0}, {b.x1, b.y1}, colour_of(k), lw);
    }
  c.pop_clip();
  return notice;
}

// The labels of one side and, for each, the pair it numbers (0: an unpaired rock's "x" index, a plain
// index or a confidence). Pairs in `unnumbered` get no number: a reader matches a pair by its number on
// both pictures, so one that can't be shown on both is shown on neither.
struct SideLabels {
  std::vector<Label> labels;
  std::vector<int> pair;
};
SideLabels side_labels(const PanelMap& m, const std::vector<Box>& gt, const std::vector<Box>& pred, Task task,
                       const std::vector<int>& number, const std::set<int>& unnumbered, const FigureOptions& o) {
  const FigureLayers& L = o.layers;
  SideLabels out;
  PtRect r;
  if (L.gt && L.indices) {
    // Pair numbers first, in number order (the ones a reader matches across the pictures), then the rest.
    std::vector<size_t> order(gt.size());
    for (size_t k = 0; k < gt.size(); ++k) order[k] = k;
    std::stable_sort(order.begin(), order.end(), [&](size_t x, size_t y) {
      const int nx = number[x] > 0 ? number[x] : 1 << 30, ny = number[y] > 0 ? number[y] : 1 << 30;
      return nx < ny;
    });
    for (size_t k : order) {
      if (!m.box(gt[k], r)) continue;
      const int pair = L.pairs ? number[k] : 0;
      if (pair > 0 && unnumbered.count(pair)) continue;
      const std::string text = !L.pairs   ? std::to_string(k + 1)
                               : pair > 0 ? std::to_string(pair)
                                          : "x" + std::to_string(k + 1);
      // A number must read as its own box's, never the neighbour's: nearest it unless a leader joins them.
      Label l{text, style(o.font_pt, (!L.pairs || pair > 0) ? kGtC : kGtUnpairedC), r, true, 0};
      l.nearest_own = true;
      out.labels.push_back(std::move(l));
      out.pair.push_back(pair);
    }
  }
  if (L.pred && L.conf) {
    std::vector<size_t> order(pred.size());
    for (size_t k = 0; k < pred.size(); ++k) order[k] = k;
    std::stable_sort(order.begin(), order.end(), [&](size_t x, size_t y) { return pred[x].conf > pred[y].conf; });
    for (size_t k : order) {
      if (!m.box(pred[k], r)) continue;
      // The one GT box this prediction matches (its highest IoU; a duplicate detection matches the rock
      // it sits on too): the only GT box its confidence may lie on.
      int matched = -1;
      double matched_iou = 0;
      for (size_t j = 0; j < gt.size(); ++j) {
        if (gt[j].cls != pred[k].cls) continue;  // a rock matches its own class
        if (const double v = instance_iou(gt[j], pred[k], task); v > matched_iou) matched = int(j), matched_iou = v;
      }
      Label l{fmt::format("{:.2f}", pred[k].conf), style(secondary_pt(o.font_pt), kPredTextC), r, true, 1};
      for (size_t j = 0; j < gt.size(); ++j)
        if (int(j) != matched) l.keep_off.push_back(m.raw(gt[j]));
      out.labels.push_back(std::move(l));
      out.pair.push_back(0);
    }
  }
  return out;
}

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

// What Fig. 1's labels left out, by kind.
struct PairsLeftOut {
  int unnumbered_pairs = 0;  // pairs numbered on neither picture (no spot on one of them)
  int numbers = 0;           // other rock numbers (unpaired rocks, plain indices) with no spot
  int confidences = 0;       // confidences with no spot clearly beside their own box
};

// Two panels' labels placed so that a pair's number shows on both panels or on neither: a reader matches a
// pair by its number. Pairs that fit on one side only are dropped from both and the placement redone
// (dropping only frees room) until every shown pair number shows twice. `make(side, unnumbered)` gives a
// side's labels without the numbers of `unnumbered`.
struct TwoPanelLabels {
  SideLabels side[2];
  LabelPlacement placed[2];
  std::set<int> unnumbered;        // pairs in view on both panels, numbered on neither
  int left_out_other[2] = {0, 0};  // labels not shown that number no pair in view on both panels
};
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

// Fig. 1's labels on both sides, drawn on their backdrops.
PairsLeftOut draw_pair_labels(Canvas& c, const PanelMap& left, const PanelMap& right, const SceneFigureInput& in,
                              const std::vector<int>& num_a, const std::vector<int>& num_b, const PtRect& notice_a,
                              const PtRect& notice_b, const FigureOptions& o) {
  const auto taken = [](const PtRect& n) { return n.width() > 0 ? std::vector<PtRect>{n} : std::vector<PtRect>{}; };
  const PtRect bounds[2] = {left.panel, right.panel};
  const std::vector<PtRect> obstacles[2] = {taken(notice_a), taken(notice_b)};
  const TwoPanelLabels t = place_on_both(
      c,
      [&](int k, const std::set<int>& unnumbered) {
        return k == 0 ? side_labels(left, in.gt_a, in.pred_a, in.task, num_a, unnumbered, o)
                      : side_labels(right, in.gt_b, in.pred_b, in.task, num_b, unnumbered, o);
      },
      bounds, obstacles);
  PairsLeftOut out;
  out.unnumbered_pairs = int(t.unnumbered.size());
  for (int k = 0; k < 2; ++k) {
    draw_placed_labels(c, t.side[k].labels, t.placed[k], true);
    for (size_t i = 0; i < t.side[k].labels.size(); ++i)
      if (!t.placed[k].labels[i].shown() && !t.unnumbered.count(t.side[k].pair[i]))
        ++(t.side[k].labels[i].group == 0 ? out.numbers : out.confidences);
  }
  return out;
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

PairsLayout draw_pairs_figure(DisplayList& out, const SceneFigureInput& in, const FigureOptions& o) {
  o.check();
  const double W = o.width_pt(), F = o.font_pt;
  const double gap = std::max(4.0, 0.5 * F);
  double y = draw_title(out, title_of(in, scene_numbers(in)), o) + 0.3 * F;
  const double pw = (W - 2 * kMargin - gap) / 2, ph = pw / aspect_of(in, o.crop);
  const TextStyle caption = style(F, kInk, true);
  out.text({kMargin, y}, Anchor::kTopLeft, caption, in.a);
  out.text({kMargin + pw + gap, y}, Anchor::kTopLeft, caption, in.b);
  y += out.measure(caption, "Ag").y + 0.15 * F;
  const PanelMap left{{kMargin, y, kMargin + pw, y + ph}, o.crop};
  const PanelMap right{{kMargin + pw + gap, y, kMargin + 2 * pw + gap, y + ph}, o.crop};
  // The GUI's numbers (a pair is named by its left rock), so a figure and the screen agree.
  const std::vector<int> num_a = pair_numbers(in.pairs, in.gt_a.size(), true);
  const std::vector<int> num_b = pair_numbers(in.pairs, in.gt_b.size(), false);
  const PtRect notice_a =
      draw_side_boxes(out, left, in.picture_a, in.problem_a, in.gt_a, in.pred_a, in.task, num_a, in.excluded_a, o);
  const PtRect notice_b =
      draw_side_boxes(out, right, in.picture_b, in.problem_b, in.gt_b, in.pred_b, in.task, num_b, in.excluded_b, o);
  const PairsLeftOut left_out = draw_pair_labels(out, left, right, in, num_a, num_b, notice_a, notice_b, o);
  y += ph + 0.35 * F;
  if (o.layers.legend) {
    std::vector<LegendItem> items;
    if (o.layers.gt)
      items.push_back(
          {Swatch::kBox, kGtC, o.layers.indices && o.layers.pairs ? "GT rock (pair number)" : "GT rock", kDarkHalo});
    // Only when the figure shows one: a legend entry for nothing on the page reads as a rendering error.
    const auto unpaired = [](const std::vector<int>& nums) { return std::count(nums.begin(), nums.end(), 0) > 0; };
    if (o.layers.gt && o.layers.pairs && (unpaired(num_a) || unpaired(num_b)))
      items.push_back({Swatch::kBox, kGtUnpairedC, "unpaired GT (x index)", kDarkHalo});
    if (o.layers.gt && (!in.excluded_a.empty() || !in.excluded_b.empty()))
      items.push_back({Swatch::kStruckBox, kGtC, "excluded from the IPD (by hand)", kDarkHalo});
    if (o.layers.pred)
      items.push_back(
          {Swatch::kDashedBox, kPredC, o.layers.conf ? "prediction (confidence)" : "prediction", kLightHalo});
    y += draw_legend(out, {kMargin, y}, W - 2 * kMargin, style(F, kInk), items);
  }
  // Footnotes 0.2 font sizes below the legend; none: the page ends at the legend (the same 4 pt margin).
  double note_gap = o.layers.legend ? 0.2 * F : 0;
  const auto note = [&](const std::string& text) {
    y += note_gap + draw_wrapped(out, {kMargin, y + note_gap}, style(secondary_pt(F), kGrey), text, W - 2 * kMargin);
    note_gap = 0;
  };
  const std::string wider = wider_hint(o.width_in);
  if (const int n = left_out.unnumbered_pairs; n > 0) note(unnumbered_note(n, o));
  if (const int n = left_out.numbers; n > 0)
    note(fmt::format("{} rock number{} left out: no free spot clear of the other rocks' boxes (try --crop or {})", n,
                     n == 1 ? "" : "s", wider));
  if (const int n = left_out.confidences; n > 0)
    note(fmt::format("{} confidence label{} left out: no free spot clearly beside {} own box (try --crop or {})", n,
                     n == 1 ? "" : "s", n == 1 ? "its" : "their", wider));
  out.width_pt = W;
  out.height_pt = std::ceil(y + kMargin);
  return {left.panel, right.panel};
}

void draw_registration_figure(DisplayList& out, const SceneFigureInput& in, const FigureOptions& o) {
  o.check();
  const double W = o.width_pt(), F = o.font_pt;
  const double gap = std::max(4.0, 0.5 * F);
  const std::string title = fmt::format("{}: GT box centres of {} and {}, {} ({} pair{})", in.stem, in.a, in.b,
                                        in.pairs_fixed ? "pairs fixed by hand" : "registration: " + in.method,
                                        in.pairs.size(), in.pairs.size() == 1 ? "" : "s");
  double y = draw_title(out, title, o) + 0.3 * F;
  const double pw = (W - 2 * kMargin - gap) / 2, ph = pw / aspect_of(in, o.crop);
  const TextStyle caption = style(F, kInk, true);
  out.text({kMargin, y}, Anchor::kTopLeft, caption, "before registration");
  out.text({kMargin + pw + gap, y}, Anchor::kTopLeft, caption,
           in.pairs_fixed ? "aligned by the pairs" : "after registration");
  y += out.measure(caption, "Ag").y + 0.15 * F;
  SideLabels all[2];  // every pair number of each panel
  PtRect panels[2];
  for (int k = 0; k < 2; ++k) {
    const PanelMap m{{kMargin + k * (pw + gap), y, kMargin + k * (pw + gap) + pw, y + ph}, o.crop};
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
  y += ph + 0.35 * F;
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
}

}  // namespace ipd::ui
