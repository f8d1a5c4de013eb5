#include "ui/figures/figure_gallery.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "core/picture/picture_codec.h"
#include "core/stats/study_statistics.h"
#include "core/util/errors.h"
#include "ui/figures/figure_common.h"

namespace ipd::ui {

using namespace fig;

namespace {

constexpr double kContext = 2.5;     // a crop spans this many times its rock's larger side
constexpr double kMinEntryPt = 110;  // an entry (two crops) is at least this wide: 2 per single column
constexpr Colour kPlain = rgb(92, 92, 98);

GalleryCrop crop_of(const std::vector<Box>& gt, const std::vector<Box>& pred, int rock, double perf, int w, int h,
                    Task task) {
  GalleryCrop c;
  c.rock = rock;
  c.perf = perf;
  c.mask = task == Task::kSegment;
  c.gt = gt[rock];
  const int best = performance_values(gt, pred, task).best_prediction[rock];
  if (best >= 0) c.pred = pred[best], c.has_pred = true;
  if (c.mask && c.has_pred) c.box_iou = instance_iou(c.gt, c.pred, Task::kDetect);
  c.region = gallery_crop_region(c.gt, w, h);
  return c;
}

// The pixels of `picture` inside `region` (on whole pixels) and the part of the region they cover.
void cut(const cv::Mat& picture, GalleryCrop& c) {
  const Crop& r = c.region;
  // A hair inside, so a region edge that rounds to just below a whole pixel takes no extra column.
  const int x0 = std::clamp(int(std::floor(r.x0 * picture.cols + 1e-6)), 0, picture.cols - 1);
  const int y0 = std::clamp(int(std::floor(r.y0 * picture.rows + 1e-6)), 0, picture.rows - 1);
  const int x1 = std::clamp(int(std::ceil(r.x1 * picture.cols - 1e-6)), x0 + 1, picture.cols);
  const int y1 = std::clamp(int(std::ceil(r.y1 * picture.rows - 1e-6)), y0 + 1, picture.rows);
  c.pixels = picture(cv::Rect(x0, y0, x1 - x0, y1 - y0)).clone();
  c.covered = {double(x0) / picture.cols, double(y0) / picture.rows, double(x1) / picture.cols,
               double(y1) / picture.rows};
}

// Normalised picture coordinates -> the crop's square on the page.
PtRect on_panel(const PtRect& panel, const Crop& region, double x0, double y0, double x1, double y1) {
  const auto px = [&](double x) { return panel.x0 + (x - region.x0) / (region.x1 - region.x0) * panel.width(); };
  const auto py = [&](double y) { return panel.y0 + (y - region.y0) / (region.y1 - region.y0) * panel.height(); };
  return {px(x0), py(y0), px(x1), py(y1)};
}

// One crop: background, picture, the best prediction dashed on a light halo, the GT box solid on a dark
// halo (the pairs figure's styles), a thin frame.
void draw_crop(Canvas& c, const PtRect& panel, const GalleryCrop& g, double font_pt) {
  c.fill_rect(panel, kPlain);
  c.push_clip(panel);
  if (!g.pixels.empty())
    c.image({g.pixels}, on_panel(panel, g.region, g.covered.x0, g.covered.y0, g.covered.x1, g.covered.y1));
  const double lw = std::max(0.35, font_pt * 0.07), dash = std::max(1.5, 4 * lw);
  const auto at = [&](double x, double y) {
    const PtRect r = on_panel(panel, g.region, x, y, x, y);
    return Pt{r.x0, r.y0};
  };
  draw_gallery_instances(c, at, g.gt, g.has_pred ? &g.pred : nullptr, 1.5 * lw, dash);
  c.pop_clip();
  c.rect(panel, kGrey, 0.4);
}

// Below a crop, a line each: its rock ("rock 3") and its performance value ("perf 0.818"), wrapped to the
// crop's width; returns the height used.
double draw_caption(Canvas& c, const PtRect& panel, const GalleryCrop& g, const TextStyle& st) {
  const Pt at{panel.x0, panel.y1 + 0.15 * st.size_pt};
  const std::string rock =
      g.pair >= 0 ? fmt::format("rock {} (pair {})", g.rock + 1, g.pair + 1) : fmt::format("rock {}", g.rock + 1);
  const double h = draw_wrapped(c, at, st, rock, panel.width());
  const std::string perf = fmt::format("{} {:.3f}", g.mask ? "mask IoU" : "perf", g.perf);
  double used = h + draw_wrapped(c, {at.x, at.y + h}, st, perf, panel.width());
  if (g.mask && std::isfinite(g.box_iou))
    used += draw_wrapped(c, {at.x, at.y + used}, st, fmt::format("box IoU {:.3f}", g.box_iou), panel.width());
  return used;
}

}  // namespace

void draw_gallery_instances(Canvas& c, const std::function<Pt(double x, double y)>& at, const Box& gt, const Box* pred,
                            double stroke, double dash) {
  const auto box = [&](const Box& b) {
    const Pt p0 = at(b.x0(), b.y0()), p1 = at(b.x1(), b.y1());
    return PtRect{p0.x, p0.y, p1.x, p1.y};
  };
  const auto outline = [&](const Outline& o) {
    std::vector<Pt> q;
    q.reserve(o.points.size());
    for (const Eigen::Vector2d& p : o.points) q.push_back(at(p.x(), p.y()));
    return q;
  };
  if (pred && pred->outline) {
    dashed_polygon(c, outline(*pred->outline), kLightHalo, stroke * kHaloRatio, dash);
    dashed_polygon(c, outline(*pred->outline), kPredC, stroke, dash);
  } else if (pred) {
    dashed_rect(c, box(*pred), kLightHalo, stroke * kHaloRatio, dash);
    dashed_rect(c, box(*pred), kPredC, stroke, dash);
  }
  if (gt.outline) {
    c.polyline(outline(*gt.outline), kDarkHalo, stroke * kHaloRatio, true);
    c.polyline(outline(*gt.outline), kGtC, stroke, true);
  } else {
    c.rect(box(gt), kDarkHalo, stroke * kHaloRatio);
    c.rect(box(gt), kGtC, stroke);
  }
}

Crop gallery_crop_region(const Box& gt, int w, int h) {
  const double side = std::max({gt.w * w, gt.h * h, 16.0}) * kContext;
  const double hx = side / 2 / w, hy = side / 2 / h;
  return {gt.cx - hx, gt.cy - hy, gt.cx + hx, gt.cy + hy};
}

std::pair<int, int> gallery_picture_size(int w, int h) {
  return w > 0 && h > 0 ? std::pair<int, int>{w, h} : std::pair<int, int>{1936, 1216};
}

GalleryInput gallery_input(const StudyLabels& labels, const TableCell& cell, int count, GallerySort sort,
                           const std::string& scene, int rock) {
  GalleryInput in;
  in.a = cell.a, in.b = cell.b, in.model = cell.model, in.sort = sort;
  std::vector<RockPairPoint> points = cell_pair_points(labels, cell);
  if (!scene.empty()) {
    std::vector<RockPairPoint> picked;
    std::string paired;  // the scene's paired rocks of a, to name in the error
    for (const RockPairPoint& p : points) {
      if (cell.per_scene[p.scene].stem != scene) continue;
      paired += (paired.empty() ? "" : ", ") + std::to_string(p.rock_a + 1);
      if (rock <= 0 || p.rock_a + 1 == rock) picked.push_back(p);
    }
    if (picked.empty())
      throw StudyError(
          paired.empty()
              ? fmt::format("--scene {}: no counted rock pair of {} | {} for model {} in that scene", scene, cell.a,
                            cell.b, cell.model)
              : fmt::format("--rock {}: rock {} of {} in {} is in no counted pair of {} | {} for model {} (its paired "
                            "rocks: {})",
                            rock, rock, cell.a, scene, cell.a, cell.b, cell.model, paired));
    points = std::move(picked);
    in.scene = scene, in.rock = rock;
  }
  in.counted_pairs = static_cast<int>(points.size());
  const auto size_of = [&](const std::string& d) {
    const auto [w, h] = domain_image_size(labels.study, d);
    return gallery_picture_size(w, h);
  };
  const auto [wa, ha] = size_of(cell.a);
  const auto [wb, hb] = size_of(cell.b);
  const std::vector<int> order = gallery_sorted(points, sort);
  for (size_t k = 0; k < order.size() && static_cast<int>(k) < count; ++k) {
    const RockPairPoint& p = points[order[k]];
    GalleryEntry e;
    e.stem = cell.per_scene[p.scene].stem;
    e.diff = p.abs_diff;
    e.a = crop_of(labels.gt_of(cell.a, e.stem).boxes, labels.predictions_of(cell.a, cell.model, e.stem).boxes, p.rock_a,
                  p.perf_a, wa, ha, labels.study.config.task);
    e.b = crop_of(labels.gt_of(cell.b, e.stem).boxes, labels.predictions_of(cell.b, cell.model, e.stem).boxes, p.rock_b,
                  p.perf_b, wb, hb, labels.study.config.task);
    if (p.rock_b != p.rock_a) e.b.pair = p.rock_a;  // a pair is numbered by its left rock on both pictures
    in.entries.push_back(std::move(e));
  }
  return in;
}

void load_gallery_pictures(GalleryInput& in, const Study& study) {
  std::map<std::pair<std::string, std::string>, cv::Mat> read;  // (domain, stem) -> picture, read once
  const auto load = [&](const std::string& domain, const std::string& stem, GalleryCrop& c) {
    const Domain* d = study.domain(domain);
    if (!d) return;
    const auto it = d->images.find(stem);
    if (it == d->images.end()) return;
    auto [at, fresh] = read.try_emplace({domain, stem});
    if (fresh) at->second = read_study_picture(study.root, it->second, cv::IMREAD_COLOR).image;
    if (at->second.empty()) {
      c.problem = "cannot decode " + it->second;
      return;
    }
    cut(at->second, c);
    in.pictures = true;
  };
  for (GalleryEntry& e : in.entries) {
    load(in.a, e.stem, e.a);
    load(in.b, e.stem, e.b);
  }
}

GalleryLayout draw_gallery_figure(DisplayList& out, const GalleryInput& in, const FigureOptions& o) {
  o.check();
  const double W = o.width_pt(), m = kFigureMargin, avail = W - 2 * m, F = o.font_pt, small = secondary_pt(F);
  const TextStyle body = style(F, kInk), bold = style(F, kInk, true), note = style(small, kGrey);
  double y = m;
  const std::string title =
      in.rock > 0
          ? fmt::format("Rock {} of {} in {} and its partner in {}, model {}", in.rock, in.a, in.scene, in.b, in.model)
      : !in.scene.empty() ? fmt::format("Rock pairs of {} by {} (largest first): {} | {}, model {}", in.scene,
                                        gallery_sort_label(in.sort, in.a, in.b), in.a, in.b, in.model)
                          : fmt::format("Rock pairs by {} (largest first): {} | {}, model {}",
                                        gallery_sort_label(in.sort, in.a, in.b), in.a, in.b, in.model);
  y += draw_wrapped(out, {m, y}, bold, title, avail) + 0.2 * F;
  // Outlines (masks) are named by line samples, boxes by boxes: a legend shows what the crops draw.
  const bool outlines = std::any_of(in.entries.begin(), in.entries.end(), [](const GalleryEntry& e) {
    return e.a.gt.outline || e.b.gt.outline || e.a.pred.outline || e.b.pred.outline;
  });
  y += draw_legend(
           out, {m, y}, avail, body,
           {{outlines ? Swatch::kOutline : Swatch::kBox, kGtC, "GT rock", kDarkHalo},
            {outlines ? Swatch::kDashedOutline : Swatch::kDashedBox, kPredC, "its best prediction", kLightHalo}}) +
       0.3 * F;
  const double gap = 0.8 * F, inner = 0.25 * F;
  // Fewer pairs than a row holds take the whole width: one rock pair (--scene --rock) spans the column.
  const int per_row = std::max(1, std::min(static_cast<int>(std::max<size_t>(1, in.entries.size())),
                                           static_cast<int>((avail + gap) / (kMinEntryPt + gap))));
  const double entry_w = (avail - (per_row - 1) * gap) / per_row, side = (entry_w - inner) / 2;
  GalleryLayout layout;
  for (size_t k = 0; k < in.entries.size(); k += per_row) {
    double row_h = 0;
    for (size_t j = k; j < std::min(in.entries.size(), k + per_row); ++j) {
      const GalleryEntry& e = in.entries[j];
      const double x = m + (j - k) * (entry_w + gap);
      double h = draw_wrapped(out, {x, y}, body, fmt::format("{}. {}, |diff| {:.3f}", j + 1, e.stem, e.diff), entry_w);
      const PtRect left{x, y + h, x + side, y + h + side}, right{x + side + inner, y + h, x + entry_w, y + h + side};
      draw_crop(out, left, e.a, F);
      draw_crop(out, right, e.b, F);
      h += side + 0.15 * small + std::max(draw_caption(out, left, e.a, note), draw_caption(out, right, e.b, note));
      layout.left.push_back(left);
      layout.right.push_back(right);
      row_h = std::max(row_h, h);
    }
    y += row_h + 0.6 * F;
  }
  std::string notes = in.rock > 0 ? fmt::format("Left {}, right {}.", in.a, in.b)
                                  : fmt::format("The first {} of {} counted pairs; left {}, right {}.",
                                                in.entries.size(), in.counted_pairs, in.a, in.b);
  if (in.entries.empty()) notes = fmt::format("No counted pairs for model {} in {} | {}.", in.model, in.a, in.b);
  if (!in.pictures && !in.entries.empty()) notes += " Labels-only study: boxes on a plain background.";
  for (const GalleryEntry& e : in.entries)
    for (const GalleryCrop* c : {&e.a, &e.b})
      if (!c->problem.empty() && notes.find(c->problem) == std::string::npos) notes += " " + c->problem + ".";
  y += draw_wrapped(out, {m, y}, note, notes, avail);
  out.width_pt = W;
  out.height_pt = std::ceil(y + m);
  return layout;
}

}  // namespace ipd::ui
