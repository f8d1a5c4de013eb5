#include "figures.h"

#include <algorithm>

namespace ipd::ui {

namespace {
constexpr ImU32 kInk = IM_COL32(20, 20, 20, 255);
constexpr ImU32 kBlue = IM_COL32(40, 110, 230, 255);

void text(ImDrawList* dl, ImVec2 at, float px, ImU32 colour, const std::string& s) {
  dl->AddText(ImGui::GetFont(), px, at, colour, s.c_str());
}
float text_width(float px, const std::string& s) {
  return ImGui::GetFont()->CalcTextSizeA(px, FLT_MAX, 0.0f, s.c_str()).x;
}
float aspect_of(int w, int h) { return (w > 0 && h > 0) ? float(w) / float(h) : 1936.0f / 1216.0f; }
}  // namespace

PairsLayout pairs_layout(ImVec2 size, float font_px) {
  PairsLayout l;
  l.title_height = font_px * 1.8f;
  const float gap = std::max(6.0f, size.x / 200.0f);
  l.side_size = {(size.x - gap) / 2, size.y - l.title_height};
  l.left_min = {0, l.title_height};
  l.right_min = {l.side_size.x + gap, l.title_height};
  return l;
}

float pairs_figure_height(float width, float font_px, int image_w, int image_h) {
  const float gap = std::max(6.0f, width / 200.0f);
  return font_px * 1.8f + (width - gap) / 2 / aspect_of(image_w, image_h);
}

void draw_pairs_figure(ImDrawList* dl, ImVec2 size, float font_px, const PairsFigure& fig) {
  const PairsLayout l = pairs_layout(size, font_px);
  text(dl, {font_px * 0.4f, font_px * 0.35f}, font_px * 1.1f, kInk, fig.title);
  const float scale = font_px / ImGui::GetFontSize();
  draw_side(dl, l.left_min, l.side_size, CanvasView{}, fig.left, SideLayers{}, {-1, -1}, scale);
  draw_side(dl, l.right_min, l.side_size, CanvasView{}, fig.right, SideLayers{}, {-1, -1}, scale);
}

float registration_figure_height(float width, float font_px, int image_w, int image_h) {
  const float panel_w = (width - font_px * 3) / 2;
  return font_px * 1.8f + font_px * 1.6f + panel_w / aspect_of(image_w, image_h) + font_px * 2.2f;
}

void draw_registration_figure(ImDrawList* dl, ImVec2 size, float px, const RegistrationFigure& fig) {
  text(dl, {px * 0.4f, px * 0.35f}, px * 1.1f, kInk, fig.title);
  const float panel_w = (size.x - px * 3) / 2, panel_h = panel_w / aspect_of(fig.image_w, fig.image_h);
  const float top = px * 1.8f + px * 1.6f;
  const float dot = std::max(3.0f, px * 0.28f), ring = dot * 1.9f, line = std::max(1.0f, px * 0.09f);
  for (int k = 0; k < 2; ++k) {
    const ImVec2 p0{px + k * (panel_w + px), top}, p1{p0.x + panel_w, p0.y + panel_h};
    text(dl, {p0.x, top - px * 1.4f}, px, kInk, k == 0 ? "before registration (raw centres)" : "after registration");
    dl->AddRectFilled(p0, p1, IM_COL32(248, 248, 248, 255));
    dl->AddRect(p0, p1, IM_COL32(120, 120, 120, 255), 0, 0, line);
    dl->PushClipRect(p0, p1, true);
    auto at = [&](const Eigen::Vector2d& q) { return ImVec2{p0.x + float(q.x()) * panel_w, p0.y + float(q.y()) * panel_h}; };
    std::vector<ImVec2> pa, pb;
    for (const auto& q : fig.a) pa.push_back(at(k == 0 ? q : apply(fig.affine, q)));
    for (const auto& q : fig.b) pb.push_back(at(q));
    for (const auto& [i, j] : fig.pairs)
      if (i < (int)pa.size() && j < (int)pb.size()) dl->AddLine(pa[i], pb[j], IM_COL32(40, 160, 80, 255), line);
    for (const auto& q : pb) dl->AddCircle(q, ring, kPink, 20, line * 1.5f);
    for (const auto& q : pa) dl->AddCircleFilled(q, dot, kBlue, 12);
    dl->PopClipRect();
  }
  // Legend.
  float x = px, y = top + panel_h + px * 0.6f;
  const float cy = y + px * 0.55f;
  dl->AddCircleFilled({x + dot, cy}, dot, kBlue, 12);
  text(dl, {x + px, y}, px, kInk, "GT centres of " + fig.name_a);
  x += px * 1.6f + text_width(px, "GT centres of " + fig.name_a) + px;
  dl->AddCircle({x + ring, cy}, ring, kPink, 20, line * 1.5f);
  text(dl, {x + ring * 2 + px * 0.4f, y}, px, kInk, "GT centres of " + fig.name_b);
  x += ring * 2 + px * 0.4f + text_width(px, "GT centres of " + fig.name_b) + px;
  dl->AddLine({x, cy}, {x + px * 1.5f, cy}, IM_COL32(40, 160, 80, 255), line * 1.5f);
  text(dl, {x + px * 1.9f, y}, px, kInk, "rock pairs");
}

float table_figure_height(float px, const TableFigure& fig) {
  return px * 1.8f + px * 1.9f * static_cast<float>(fig.rows.size() + 1) + px * 2.4f;
}

void draw_table_figure(ImDrawList* dl, ImVec2 size, float px, const TableFigure& fig) {
  text(dl, {px * 0.4f, px * 0.35f}, px * 1.1f, kInk, fig.title);
  const size_t cols = fig.header.size();
  std::vector<float> w(cols, 0);
  for (size_t c = 0; c < cols; ++c) {
    w[c] = text_width(px, fig.header[c]);
    for (const auto& r : fig.rows) w[c] = std::max(w[c], text_width(px, r[c]));
    w[c] += px * 1.4f;
  }
  float total = 0;
  for (float x : w) total += x;
  const float scale = std::min(1.0f, (size.x - px) / total);  // never wider than the figure
  const float row_h = px * 1.9f, top = px * 1.8f, x0 = px * 0.5f;
  const float line = std::max(1.0f, px * 0.07f);
  auto cell_x = [&](size_t c) {
    float x = x0;
    for (size_t k = 0; k < c; ++k) x += w[k] * scale;
    return x;
  };
  for (size_t r = 0; r <= fig.rows.size(); ++r) {
    const float y = top + row_h * r;
    if (r == 0) dl->AddRectFilled({x0, y}, {x0 + total * scale, y + row_h}, IM_COL32(235, 235, 240, 255));
    for (size_t c = 0; c < cols; ++c) {
      const std::string& s = r == 0 ? fig.header[c] : fig.rows[r - 1][c];
      const bool bold = r > 0 && r - 1 < fig.bold.size() && c < fig.bold[r - 1].size() && fig.bold[r - 1][c];
      const ImVec2 at{cell_x(c) + px * 0.7f * scale, y + (row_h - px) / 2};
      text(dl, at, px, kInk, s);
      if (bold) text(dl, {at.x + std::max(1.0f, px * 0.06f), at.y}, px, kInk, s);  // faux bold: a second pass
    }
  }
  const float y1 = top + row_h * (fig.rows.size() + 1);
  for (size_t r = 0; r <= fig.rows.size() + 1; ++r)
    dl->AddLine({x0, top + row_h * r}, {x0 + total * scale, top + row_h * r}, kInk, line);
  for (size_t c = 0; c <= cols; ++c) dl->AddLine({cell_x(c), top}, {cell_x(c), y1}, kInk, line);
  text(dl, {x0, y1 + px * 0.6f}, px * 0.85f, IM_COL32(80, 80, 80, 255), fig.note);
}

}  // namespace ipd::ui
