#include "ui/figures/figure_scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>

#include "core/ipd/ipd.h"
#include "core/session/audit.h"
#include "ui/figures/figure_common.h"
#include "ui/figures/scene_panels.h"

namespace ipd::ui {

using namespace fig;
using namespace scene;

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
  // Two empty prediction sets are not a perfect match: no number, and why (no_predictions_reason); nor is a
  // study without any detector's predictions.
  const std::string none =
      in.model.empty() ? std::string("the study has no predictions")
                       : no_predictions_reason(static_cast<long>(in.pred_a.size()), static_cast<long>(in.pred_b.size()),
                                               in.a, in.b, in.conf_threshold);
  const std::string value = !none.empty()       ? "not a number (" + none + ")"
                            : std::isnan(n.ipd) ? std::string("n/a")
                                                : fmt::format("{:.4f}", n.ipd);
  return fmt::format("{}: {} vs {}, model {}, scene IPD{} {} ({} pair{}){}{}", in.stem, in.a, in.b,
                     in.model.empty() ? "none" : in.model, in.task == Task::kSegment ? " (mask IoU)" : "", value,
                     n.pairs, n.pairs == 1 ? "" : "s",
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

// What Fig. 1's labels left out, by kind.
struct PairsLeftOut {
  int unnumbered_pairs = 0;  // pairs numbered on neither picture (no spot on one of them)
  int numbers = 0;           // other rock numbers (unpaired rocks, plain indices) with no spot
  int confidences = 0;       // confidences with no spot clearly beside their own box
};

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

}  // namespace

namespace {

// Fig. 1 with its panels side by side or stacked; the counts decide which (scene::choose_stacked).
struct DrawnPairs {
  PairsLayout layout;
  Numbered numbered;
};
DrawnPairs draw_pairs(DisplayList& out, const SceneFigureInput& in, const FigureOptions& o, bool stacked) {
  const double W = o.width_pt(), F = o.font_pt;
  double y = draw_title(out, title_of(in, scene_numbers(in)), o) + 0.3 * F;
  const PanelPlan plan = plan_panels(out, in, o, y, stacked);
  const TextStyle caption = style(F, kInk, true);
  out.text(plan.caption[0], Anchor::kTopLeft, caption, in.a);
  out.text(plan.caption[1], Anchor::kTopLeft, caption, in.b);
  const PanelMap left{plan.panel[0], o.crop};
  const PanelMap right{plan.panel[1], o.crop};
  y = plan.bottom;
  // The GUI's numbers (a pair is named by its left rock), so a figure and the screen agree.
  const std::vector<int> num_a = pair_numbers(in.pairs, in.gt_a.size(), true);
  const std::vector<int> num_b = pair_numbers(in.pairs, in.gt_b.size(), false);
  const PtRect notice_a =
      draw_side_boxes(out, left, in.picture_a, in.problem_a, in.gt_a, in.pred_a, in.task, num_a, in.excluded_a, o);
  const PtRect notice_b =
      draw_side_boxes(out, right, in.picture_b, in.problem_b, in.gt_b, in.pred_b, in.task, num_b, in.excluded_b, o);
  const PairsLeftOut left_out = draw_pair_labels(out, left, right, in, num_a, num_b, notice_a, notice_b, o);
  y += 0.35 * F;
  if (o.layers.legend) {
    // Outlines (masks) are named by line samples (solid GT, dashed prediction), boxes by boxes.
    const auto has_outline = [](const std::vector<Box>& v) {
      return std::any_of(v.begin(), v.end(), [](const Box& b) { return b.outline != nullptr; });
    };
    const bool outlines =
        has_outline(in.gt_a) || has_outline(in.gt_b) || has_outline(in.pred_a) || has_outline(in.pred_b);
    const Swatch gt_swatch = outlines ? Swatch::kOutline : Swatch::kBox;
    std::vector<LegendItem> items;
    if (o.layers.gt)
      items.push_back(
          {gt_swatch, kGtC, o.layers.indices && o.layers.pairs ? "GT rock (pair number)" : "GT rock", kDarkHalo});
    // Only when the figure shows one: a legend entry for nothing on the page reads as a rendering error.
    const auto unpaired = [](const std::vector<int>& nums) { return std::count(nums.begin(), nums.end(), 0) > 0; };
    if (o.layers.gt && o.layers.pairs && (unpaired(num_a) || unpaired(num_b)))
      items.push_back({gt_swatch, kGtUnpairedC, "unpaired GT (x index)", kDarkHalo});
    if (o.layers.gt && (!in.excluded_a.empty() || !in.excluded_b.empty()))
      items.push_back({Swatch::kStruckBox, kGtC, "excluded from the IPD (by hand)", kDarkHalo});
    if (o.layers.pred)
      items.push_back({outlines ? Swatch::kDashedOutline : Swatch::kDashedBox, kPredC,
                       o.layers.conf ? "prediction (confidence)" : "prediction", kLightHalo});
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
  return {{left.panel, right.panel, stacked, left_out.unnumbered_pairs},
          {int(in.pairs.size()), left_out.unnumbered_pairs}};
}

}  // namespace

PairsLayout draw_pairs_figure(DisplayList& out, const SceneFigureInput& in, const FigureOptions& options) {
  options.check();
  FigureOptions o = options;
  if (o.crop_auto) o.crop = rocks_crop(in, false);
  const bool stacked =
      choose_stacked(out.metrics(), o, [&](DisplayList& d, bool s) { return draw_pairs(d, in, o, s).numbered; });
  return draw_pairs(out, in, o, stacked).layout;
}

}  // namespace ipd::ui
