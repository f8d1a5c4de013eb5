// Headless drawing for `ipd figure`: an OSMesa (llvmpipe) buffer, Dear ImGui's OpenGL 2 backend and the
// ui/ drawing functions. Links libOSMesa, never libGL.
#pragma once

#include <imgui.h>

#include <functional>
#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "ui/canvas/canvas.h"

namespace ipd::figure {

class OffscreenRenderer {
 public:
  // A width x height RGBA buffer and an ImGui context whose font is `font_px` pixels tall, with Latin-1 and
  // every character of `glyph_text` (e.g. all the figure's text: Δ, −, thin spaces, accented domain names).
  // Throws std::runtime_error when OSMesa can't give a context of that size.
  OffscreenRenderer(int width, int height, float font_px, const std::string& font_file,
                    const std::string& bold_file = {}, const std::string& glyph_text = {});
  ImFont* bold_font() const;  // null when no bold file was given
  ~OffscreenRenderer();
  OffscreenRenderer(const OffscreenRenderer&) = delete;
  OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

  // Uploads a BGR picture (downscaled to at most max_width) and returns its texture.
  ImTextureID upload(const cv::Mat& bgr, int max_width);
  // Draws one frame on white with `draw(more)` and returns it as BGR: `more()` gives a fresh draw list,
  // drawn after the ones before (each holds at most 65,536 vertices: see ImGuiCanvas).
  cv::Mat render(const std::function<void(const std::function<ImDrawList*()>& more)>& draw);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// A figure as PNG bytes through OSMesa and ImGui's draw list (the raster path): width = width_pt / 72 * dpi.
std::string render_png(const ui::DisplayList& figure, const ui::FontMetrics& metrics, double dpi);

}  // namespace ipd::figure
