#include "ui/gui/scene_canvas.h"

#include "ui/gui/rock_numbers.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace ipd::ui {

Placement place(ImVec2 area_min, ImVec2 area_size, int image_w, int image_h, const CanvasView& view) {
  const float aspect = (image_w > 0 && image_h > 0) ? float(image_w) / float(image_h) : 1936.0f / 1216.0f;
  float w = area_size.x, h = w / aspect;
  if (h > area_size.y) h = area_size.y, w = h * aspect;
  w *= view.zoom;
  h *= view.zoom;
  Placement p;
  p.size = {w, h};
  p.origin = {area_min.x + 0.5f * area_size.x - (0.5f + view.pan.x) * w,
              area_min.y + 0.5f * area_size.y - (0.5f + view.pan.y) * h};
  return p;
}

void draw_closed_path(ImDrawList* dl, const std::vector<ImVec2>& q, ImU32 colour, float thickness, bool dashed) {
  if (!dashed) {
    dl->AddPolyline(q.data(), static_cast<int>(q.size()), colour, ImDrawFlags_Closed, thickness);
    return;
  }
  // Dashes of 6 px with gaps of 4 px, continued from one edge to the next so corners don't bunch them up.
  constexpr float kDash = 6, kPeriod = 10;
  float phase = 0;
  for (size_t k = 0; k < q.size(); ++k) {
    const ImVec2 a = q[k], b = q[(k + 1) % q.size()];
    const float dx = b.x - a.x, dy = b.y - a.y, len = std::sqrt(dx * dx + dy * dy);
    if (len <= 0) continue;
    for (float t = -phase; t < len; t += kPeriod) {
      const float t0 = std::max(t, 0.0f), t1 = std::min(t + kDash, len);
      if (t1 > t0)
        dl->AddLine({a.x + dx * t0 / len, a.y + dy * t0 / len}, {a.x + dx * t1 / len, a.y + dy * t1 / len}, colour,
                    thickness);
    }
    phase = std::fmod(phase + len, kPeriod);
  }
}

namespace {

void text_with_backdrop(ImDrawList* dl, ImVec2 at, ImU32 colour, const char* text, float scale) {
  ImFont* font = ImGui::GetFont();
  const float size = ImGui::GetFontSize() * scale;
  const ImVec2 ext = font->CalcTextSizeA(size, FLT_MAX, 0.0f, text);
  dl->AddRectFilled({at.x - 1, at.y}, {at.x + ext.x + 1, at.y + ext.y}, IM_COL32(0, 0, 0, 170));
  dl->AddText(font, size, at, colour, text);
}

// An instance's outline on screen: solid (ground truth) or dashed (a prediction), closed.
void draw_outline(ImDrawList* dl, const Placement& pl, const Outline& o, ImU32 colour, float thickness, bool dashed) {
  std::vector<ImVec2> q;
  q.reserve(o.points.size());
  for (const Eigen::Vector2d& p : o.points) q.push_back(pl.to_screen(p.x(), p.y()));
  draw_closed_path(dl, q, colour, thickness, dashed);
}

// The outline's region filled with a translucent colour (the hovered rock's mask).
void fill_outline(ImDrawList* dl, const Placement& pl, const Outline& o, ImU32 colour) {
  const std::vector<int> t = outline_triangles(o);
  for (size_t k = 0; k + 2 < t.size(); k += 3) {
    const Eigen::Vector2d &a = o.points[t[k]], &b = o.points[t[k + 1]], &c = o.points[t[k + 2]];
    dl->AddTriangleFilled(pl.to_screen(a.x(), a.y()), pl.to_screen(b.x(), b.y()), pl.to_screen(c.x(), c.y()), colour);
  }
}

}  // namespace

int draw_side(ImDrawList* dl, ImVec2 a0, ImVec2 asz, const CanvasView& view, const SideInput& in,
              const SideLayers& layers, ImVec2 mouse, float ts) {
  const ImVec2 a1{a0.x + asz.x, a0.y + asz.y};
  dl->PushClipRect(a0, a1, true);
  if (in.fill_background) dl->AddRectFilled(a0, a1, IM_COL32(30, 30, 34, 255));
  const Placement pl = place(a0, asz, in.image_w, in.image_h, view);
  const ImVec2 p1{pl.origin.x + pl.size.x, pl.origin.y + pl.size.y};
  if (in.texture) {
    dl->AddImage(in.texture, pl.origin, p1);
  } else {
    dl->AddRectFilled(pl.origin, p1, IM_COL32(70, 70, 76, 255));
    if (!in.placeholder.empty()) {  // centred, clear of the caption in the corner
      const float w = ImGui::GetFont()->CalcTextSizeA(ImGui::GetFontSize() * ts, FLT_MAX, 0, in.placeholder.c_str()).x;
      text_with_backdrop(dl, {pl.origin.x + 0.5f * (pl.size.x - w), pl.origin.y + 0.5f * pl.size.y},
                         IM_COL32(255, 200, 120, 255), in.placeholder.c_str(), ts);
    }
  }
  const float thick = std::max(1.0f, 1.5f * ts);
  char buf[32];
  int hovered = -1;
  // Confidence labels are drawn last, where they hide no rock number and no number hides them.
  struct Pending {
    ImVec2 q0, q1;
    double conf;
    size_t prediction;
  };
  std::vector<Pending> confidences;
  std::vector<LabelRect> number_rects;
  struct Number {
    RockNumberTag tag;
    std::string text;
    ImU32 colour;
  };
  std::vector<Number> numbers;
  if (layers.predictions && in.predictions) {
    // Which predictions are some rock's best, marked once: a search per prediction is predictions x rocks a
    // frame (4 million on a dense scene of 2,000 a side).
    std::vector<char> is_best(in.predictions->size(), 0);
    if (in.gt)
      for (const int k : in.best_prediction)
        if (k >= 0 && k < static_cast<int>(is_best.size())) is_best[k] = 1;
    for (size_t k = 0; k < in.predictions->size(); ++k) {
      const Box& b = (*in.predictions)[k];
      const ImVec2 q0 = pl.to_screen(b.x0(), b.y0()), q1 = pl.to_screen(b.x1(), b.y1());
      const bool best = is_best[k] != 0;
      const ImU32 colour = best ? kRed : IM_COL32(235, 40, 40, 140);
      if (b.outline)
        draw_outline(dl, pl, *b.outline, colour, best ? 2 * thick : thick, true);
      else
        draw_closed_path(dl, {q0, {q1.x, q0.y}, q1, {q0.x, q1.y}}, colour, best ? 2 * thick : thick, true);
      if (layers.confidences && q1.x - q0.x >= in.min_box_px_for_confidence) confidences.push_back({q0, q1, b.conf, k});
    }
  }
  if (layers.gt && in.gt) {
    for (size_t k = 0; k < in.gt->size(); ++k) {
      const Box& b = (*in.gt)[k];
      const ImVec2 q0 = pl.to_screen(b.x0(), b.y0()), q1 = pl.to_screen(b.x1(), b.y1());
      if (mouse.x >= q0.x && mouse.x <= q1.x && mouse.y >= q0.y && mouse.y <= q1.y && mouse.x >= a0.x &&
          mouse.x <= a1.x && mouse.y >= a0.y && mouse.y <= a1.y)
        hovered = int(k);
      const int number = k < in.number.size() ? in.number[k] : 0;
      const bool excluded = k < in.excluded.size() && in.excluded[k];
      const bool suspect = k < in.suspect.size() && in.suspect[k];
      const bool sampled = std::find(in.sample.begin(), in.sample.end(), int(k)) != in.sample.end();
      ImU32 colour = number > 0 ? (suspect ? kSuspect : kPink) : kGreyUnpaired;
      if (sampled) colour = kTriple;
      if (int(k) == in.highlight) colour = kHighlight;
      if (int(k) == in.selected) colour = kSelected;
      const bool wide = int(k) == in.highlight || int(k) == in.selected || sampled || suspect;
      if (b.outline) {
        if (hovered == int(k)) fill_outline(dl, pl, *b.outline, (colour & ~IM_COL32_A_MASK) | IM_COL32(0, 0, 0, 70));
        draw_outline(dl, pl, *b.outline, colour, wide ? 2.5f * thick : thick, false);
      } else {
        dl->AddRect(q0, q1, colour, 0, 0, wide ? 2.5f * thick : thick);
      }
      if (excluded) dl->AddLine(q0, q1, colour, thick);
      if (layers.indices) {
        // Partners share their pair's number; an unpaired rock shows its own 1-based index after an "x".
        std::string text = number > 0 ? std::to_string(number) : "x" + std::to_string(k + 1);
        const ImVec2 ext = ImGui::GetFont()->CalcTextSizeA(ImGui::GetFontSize() * ts, FLT_MAX, 0.0f, text.c_str());
        // Rocks wholly outside the pane (zoomed in) need no number and would only slow the placer down.
        if (q1.x >= a0.x && q0.x <= a1.x && q1.y >= a0.y && q0.y <= a1.y)
          numbers.push_back({{{q0.x, q0.y, q1.x, q1.y}, ext.x + 2, ext.y}, std::move(text), colour});
      }
    }
  }
  // The figures' placer: no number under another, none over a rock while a free spot exists.
  std::vector<RockNumberTag> tags;
  for (const Number& n : numbers) tags.push_back(n.tag);
  const LabelPlacement placed = asz.x > 0 && asz.y > 0 ? place_rock_numbers(tags, {a0.x, a0.y, a1.x, a1.y})
                                                       : LabelPlacement{std::vector<PlacedLabel>(tags.size())};
  for (size_t i = 0; i < numbers.size(); ++i) {
    const PlacedLabel& l = placed.labels[i];
    if (!l.shown()) continue;
    if (l.position == LabelPosition::kLeader)
      dl->AddLine({float(l.leader_x0), float(l.leader_y0)}, {float(l.leader_x1), float(l.leader_y1)}, numbers[i].colour,
                  thick);
    number_rects.push_back(l.box);
    text_with_backdrop(dl, {float(l.box.x0) + 1, float(l.box.y0)}, numbers[i].colour, numbers[i].text.c_str(), ts);
  }
  // Confidences with the same placer, after the numbers: clear of them, of other predictions' boxes and of
  // every GT box but the one the prediction matches, so none reads as a neighbour's; left out otherwise.
  if (!confidences.empty() && asz.x > 0 && asz.y > 0) {
    std::stable_sort(confidences.begin(), confidences.end(),
                     [](const Pending& x, const Pending& y) { return x.conf > y.conf; });  // the surest first
    std::vector<LabelRect> gt_rects;
    if (in.gt)
      for (const Box& g : *in.gt) {
        const ImVec2 q0 = pl.to_screen(g.x0(), g.y0()), q1 = pl.to_screen(g.x1(), g.y1());
        gt_rects.push_back({q0.x, q0.y, q1.x, q1.y});
      }
    const float conf_size = 0.85f * ImGui::GetFontSize() * ts;
    std::vector<ConfidenceTag> tags;
    std::vector<std::string> texts;
    for (const Pending& p : confidences) {
      std::snprintf(buf, sizeof buf, "%.2f", p.conf);
      texts.emplace_back(buf);
      const ImVec2 ext = ImGui::GetFont()->CalcTextSizeA(conf_size, FLT_MAX, 0.0f, buf);
      int matched = -1;  // the GT box of highest IoU with the prediction
      double best_iou = 0;
      if (in.gt)
        for (size_t j = 0; j < in.gt->size(); ++j) {
          if ((*in.gt)[j].cls != (*in.predictions)[p.prediction].cls) continue;  // a rock matches its own class
          if (const double v = iou((*in.gt)[j], (*in.predictions)[p.prediction]); v > best_iou)
            best_iou = v, matched = static_cast<int>(j);
        }
      tags.push_back({{p.q0.x, p.q0.y, p.q1.x, p.q1.y}, ext.x + 2, ext.y, matched});
    }
    const LabelPlacement placed_conf = place_confidences(tags, gt_rects, number_rects, {a0.x, a0.y, a1.x, a1.y});
    for (size_t i = 0; i < tags.size(); ++i) {
      const PlacedLabel& l = placed_conf.labels[i];
      if (!l.shown()) continue;
      if (l.position == LabelPosition::kLeader)
        dl->AddLine({float(l.leader_x0), float(l.leader_y0)}, {float(l.leader_x1), float(l.leader_y1)}, kRed, thick);
      text_with_backdrop(dl, {float(l.box.x0) + 1, float(l.box.y0)}, kRed, texts[i].c_str(), 0.85f * ts);
    }
  }
  if (!in.caption.empty())
    text_with_backdrop(dl, {a0.x + 6, a0.y + 4}, IM_COL32(255, 255, 255, 255), in.caption.c_str(), 1.1f * ts);
  dl->PopClipRect();
  return hovered;
}

}  // namespace ipd::ui
