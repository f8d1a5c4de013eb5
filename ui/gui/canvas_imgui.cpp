#include "ui/gui/canvas_imgui.h"

#include <algorithm>
#include <utility>

namespace ipd::ui {

namespace {
ImU32 col(Colour c) { return IM_COL32(c.r, c.g, c.b, c.a); }

// Upper bounds of the vertices ImGui emits per primitive (anti-aliased thick strokes: 4 per path point; an
// auto-segmented circle: at most 512 points; a glyph: 4).
constexpr size_t kShapeVertices = 64, kCircleVertices = 4 * 512 + 16;
constexpr size_t kPolylineChunk = 4096;  // points per piece of a long polyline: each piece fits any list
}  // namespace

ImGuiCanvas::ImGuiCanvas(ImDrawList* dl, ImVec2 origin, float px_per_pt, Upload upload, const FontMetrics* metrics,
                         ImFont* bold, MoreLists more)
    : dl_(dl),
      more_(std::move(more)),
      origin_(origin),
      scale_(px_per_pt),
      upload_(std::move(upload)),
      metrics_(metrics),
      bold_(bold) {}

void ImGuiCanvas::reserve(size_t vertices) {
  if (!more_ || dl_->_VtxCurrentIdx + vertices < kMaxListVertices) return;
  dl_ = more_();
  for (const auto& [a, b] : clips_) dl_->PushClipRect(a, b, true);
}

void ImGuiCanvas::rect(const PtRect& r, Colour c, double w) {
  reserve(kShapeVertices);
  dl_->AddRect(px({r.x0, r.y0}), px({r.x1, r.y1}), col(c), 0, 0, std::max(1.0f, float(w) * scale_));
}
void ImGuiCanvas::fill_rect(const PtRect& r, Colour c) {
  reserve(kShapeVertices);
  dl_->AddRectFilled(px({r.x0, r.y0}), px({r.x1, r.y1}), col(c));
}
void ImGuiCanvas::line(Pt a, Pt b, Colour c, double w) {
  reserve(kShapeVertices);
  dl_->AddLine(px(a), px(b), col(c), std::max(1.0f, float(w) * scale_));
}
void ImGuiCanvas::polyline(const std::vector<Pt>& pts, Colour c, double w, bool closed) {
  std::vector<ImVec2> p;
  for (const Pt& q : pts) p.push_back(px(q));
  const float width = std::max(1.0f, float(w) * scale_);
  if (p.size() <= kPolylineChunk) {
    reserve(4 * p.size() + kShapeVertices);
    dl_->AddPolyline(p.data(), int(p.size()), col(c), closed ? ImDrawFlags_Closed : ImDrawFlags_None, width);
    return;
  }
  // Pieces sharing their end points, so a line of any length fits the lists.
  if (closed) p.push_back(p.front());
  for (size_t i = 0; i + 1 < p.size(); i += kPolylineChunk - 1) {
    const size_t n = std::min(kPolylineChunk, p.size() - i);
    reserve(4 * n + kShapeVertices);
    dl_->AddPolyline(p.data() + i, int(n), col(c), ImDrawFlags_None, width);
  }
}
void ImGuiCanvas::circle(Pt c, double r, Colour colour, double w) {
  reserve(kCircleVertices);
  dl_->AddCircle(px(c), float(r) * scale_, col(colour), 0, std::max(1.0f, float(w) * scale_));
}
void ImGuiCanvas::fill_circle(Pt c, double r, Colour colour) {
  reserve(kCircleVertices);
  dl_->AddCircleFilled(px(c), float(r) * scale_, col(colour), 0);
}

// ImGui sizes a font by its line height (ascent + descent); the layout used the em size.
float ImGuiCanvas::font_px(const TextStyle& st) const {
  const double line_pt = metrics_ ? metrics_->measure(st, "").y : st.size_pt * 1.164;  // DejaVu Sans' ratio
  return float(line_pt) * scale_;
}

Pt ImGuiCanvas::measure(const TextStyle& st, const std::string& s) {
  if (metrics_) return metrics_->measure(st, s);
  const float size = font_px(st);
  const ImVec2 e = ImGui::GetFont()->CalcTextSizeA(size, FLT_MAX, 0, s.c_str());
  return {e.x / scale_, size / scale_};
}

void ImGuiCanvas::text(Pt at, Anchor anchor, const TextStyle& st, const std::string& s) {
  const Pt m = measure(st, s);
  const PtRect box = text_box(at, anchor, m.x, m.y);
  const float size = font_px(st);
  ImFont* font = st.bold && bold_ ? bold_ : ImGui::GetFont();
  // Start where the laid-out box starts; centre the ImGui advance inside it when widths differ slightly.
  const float w = font->CalcTextSizeA(size, FLT_MAX, 0, s.c_str()).x;
  ImVec2 p = px({box.x0, box.y0});
  p.x += 0.5f * (float(m.x) * scale_ - w);
  reserve(2 * 4 * s.size() + kShapeVertices);  // a glyph per byte at most, twice for synthesised bold
  dl_->AddText(font, size, p, col(st.colour), s.c_str());
  if (st.bold && !bold_) dl_->AddText(font, size, {p.x + std::max(1.0f, size * 0.05f), p.y}, col(st.colour), s.c_str());
}

void ImGuiCanvas::image(const FigurePicture& pic, const PtRect& where) {
  if (pic.pixels.empty() || !upload_) return;
  auto it = textures_.find(pic.pixels.data);
  if (it == textures_.end()) it = textures_.emplace(pic.pixels.data, upload_(pic.pixels)).first;
  reserve(kShapeVertices);
  dl_->AddImage(it->second, px({where.x0, where.y0}), px({where.x1, where.y1}));
}

void ImGuiCanvas::push_clip(const PtRect& r) {
  dl_->PushClipRect(px({r.x0, r.y0}), px({r.x1, r.y1}), true);
  // Kept as ImGui clipped it (inside the enclosing clip), to re-push on a fresh list.
  clips_.emplace_back(ImVec2(dl_->GetClipRectMin()), ImVec2(dl_->GetClipRectMax()));
}
void ImGuiCanvas::pop_clip() {
  dl_->PopClipRect();
  if (!clips_.empty()) clips_.pop_back();
}

}  // namespace ipd::ui
