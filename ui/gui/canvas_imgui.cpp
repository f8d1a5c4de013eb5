#include "ui/gui/canvas_imgui.h"

#include <algorithm>

namespace ipd::ui {

namespace {
ImU32 col(Colour c) { return IM_COL32(c.r, c.g, c.b, c.a); }
}  // namespace

ImGuiCanvas::ImGuiCanvas(ImDrawList* dl, ImVec2 origin, float px_per_pt, Upload upload, const FontMetrics* metrics,
                         ImFont* bold)
    : dl_(dl), origin_(origin), scale_(px_per_pt), upload_(std::move(upload)), metrics_(metrics), bold_(bold) {}

void ImGuiCanvas::rect(const PtRect& r, Colour c, double w) {
  dl_->AddRect(px({r.x0, r.y0}), px({r.x1, r.y1}), col(c), 0, 0, std::max(1.0f, float(w) * scale_));
}
void ImGuiCanvas::fill_rect(const PtRect& r, Colour c) { dl_->AddRectFilled(px({r.x0, r.y0}), px({r.x1, r.y1}), col(c)); }
void ImGuiCanvas::line(Pt a, Pt b, Colour c, double w) {
  dl_->AddLine(px(a), px(b), col(c), std::max(1.0f, float(w) * scale_));
}
void ImGuiCanvas::polyline(const std::vector<Pt>& pts, Colour c, double w, bool closed) {
  std::vector<ImVec2> p;
  for (const Pt& q : pts) p.push_back(px(q));
  dl_->AddPolyline(p.data(), int(p.size()), col(c), closed ? ImDrawFlags_Closed : ImDrawFlags_None,
                   std::max(1.0f, float(w) * scale_));
}
void ImGuiCanvas::circle(Pt c, double r, Colour colour, double w) {
  dl_->AddCircle(px(c), float(r) * scale_, col(colour), 0, std::max(1.0f, float(w) * scale_));
}
void ImGuiCanvas::fill_circle(Pt c, double r, Colour colour) { dl_->AddCircleFilled(px(c), float(r) * scale_, col(colour), 0); }

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
  dl_->AddText(font, size, p, col(st.colour), s.c_str());
  if (st.bold && !bold_) dl_->AddText(font, size, {p.x + std::max(1.0f, size * 0.05f), p.y}, col(st.colour), s.c_str());
}

void ImGuiCanvas::image(const FigurePicture& pic, const PtRect& where) {
  if (pic.pixels.empty() || !upload_) return;
  auto it = textures_.find(pic.pixels.data);
  if (it == textures_.end()) it = textures_.emplace(pic.pixels.data, upload_(pic.pixels)).first;
  dl_->AddImage(it->second, px({where.x0, where.y0}), px({where.x1, where.y1}));
}

void ImGuiCanvas::push_clip(const PtRect& r) { dl_->PushClipRect(px({r.x0, r.y0}), px({r.x1, r.y1}), true); }
void ImGuiCanvas::pop_clip() { dl_->PopClipRect(); }

}  // namespace ipd::ui
