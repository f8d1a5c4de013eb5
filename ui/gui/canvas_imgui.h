// The ImGui draw-list backend of the figure canvas: the OSMesa PNG path of `ipd figure` (and any ImGui
// window). Points become pixels at `px_per_pt`; pictures become textures through `upload`.
// Debian's Dear ImGui indexes vertices with 16 bits and the OpenGL 2 renderer can't offset them, so one draw
// list holds at most 65,536 vertices: a figure with more (a 1,000-scene distribution) goes on to the next list
// `more` gives, with the clip rectangles carried over.
#pragma once

#include <imgui.h>

#include <functional>
#include <map>
#include <utility>
#include <vector>

#include "ui/canvas/canvas.h"

namespace ipd::ui {

class ImGuiCanvas : public Canvas {
 public:
  using Upload = std::function<ImTextureID(const cv::Mat& bgr)>;
  // A fresh draw list drawn after the previous ones (empty: the renderer offsets vertices itself, as the GUI's
  // OpenGL 3 renderer does, and one list holds any number).
  using MoreLists = std::function<ImDrawList*()>;
  // The most vertices one list gets before the canvas moves on (16-bit indices).
  static constexpr unsigned kMaxListVertices = 1u << 16;
  // `metrics` (optional) gives the line height of the figure font, so text has the size it was laid out at.
  // `bold` (optional): the bold face; without it bold text is drawn twice, slightly offset.
  ImGuiCanvas(ImDrawList* dl, ImVec2 origin, float px_per_pt, Upload upload, const FontMetrics* metrics = nullptr,
              ImFont* bold = nullptr, MoreLists more = {});
  void rect(const PtRect& r, Colour stroke, double width_pt) override;
  void fill_rect(const PtRect& r, Colour fill) override;
  void line(Pt a, Pt b, Colour colour, double width_pt) override;
  void polyline(const std::vector<Pt>& points, Colour colour, double width_pt, bool closed) override;
  void circle(Pt centre, double radius_pt, Colour stroke, double width_pt) override;
  void fill_circle(Pt centre, double radius_pt, Colour fill) override;
  void text(Pt at, Anchor anchor, const TextStyle& style, const std::string& s) override;
  void image(const FigurePicture& picture, const PtRect& where) override;
  void push_clip(const PtRect& r) override;
  void pop_clip() override;
  Pt measure(const TextStyle& style, const std::string& s) override;

 private:
  ImVec2 px(Pt p) const { return {origin_.x + float(p.x) * scale_, origin_.y + float(p.y) * scale_}; }
  float font_px(const TextStyle& style) const;
  // Makes room for `vertices` more: on a fresh list (its clips re-pushed) when this one would overflow.
  void reserve(size_t vertices);
  ImDrawList* dl_;
  MoreLists more_;
  std::vector<std::pair<ImVec2, ImVec2>> clips_;
  ImVec2 origin_;
  float scale_;
  Upload upload_;
  const FontMetrics* metrics_;
  ImFont* bold_;
  std::map<const void*, ImTextureID> textures_;
};

}  // namespace ipd::ui
