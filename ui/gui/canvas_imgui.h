// The ImGui draw-list backend of the figure canvas: the OSMesa PNG path of `ipd figure` (and any ImGui
// window). Points become pixels at `px_per_pt`; pictures become textures through `upload`.
#pragma once

#include <imgui.h>

#include <functional>
#include <map>

#include "ui/canvas/canvas.h"

namespace ipd::ui {

class ImGuiCanvas : public Canvas {
 public:
  using Upload = std::function<ImTextureID(const cv::Mat& bgr)>;
  // `metrics` (optional) gives the line height of the figure font, so text has the size it was laid out at.
  // `bold` (optional): the bold face; without it bold text is drawn twice, slightly offset.
  ImGuiCanvas(ImDrawList* dl, ImVec2 origin, float px_per_pt, Upload upload, const FontMetrics* metrics = nullptr,
              ImFont* bold = nullptr);
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
  ImDrawList* dl_;
  ImVec2 origin_;
  float scale_;
  Upload upload_;
  const FontMetrics* metrics_;
  ImFont* bold_;
  std::map<const void*, ImTextureID> textures_;
};

}  // namespace ipd::ui
