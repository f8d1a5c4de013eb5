#include "app/cli/offscreen_renderer.h"

#include <GL/osmesa.h>
#include <backends/imgui_impl_opengl2.h>

#include "core/picture/picture_codec.h"
#include "ui/canvas/png_text.h"
#include "ui/gui/canvas_imgui.h"

#include <cmath>
#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <vector>

namespace ipd::figure {

struct OffscreenRenderer::Impl {
  OSMesaContext ctx = nullptr;
  std::vector<unsigned char> buffer;
  int width = 0, height = 0;
  ImGuiContext* imgui = nullptr;
  std::vector<GLuint> textures;
  ImFont* bold = nullptr;
  ImVector<ImWchar> ranges;  // the atlas's glyphs: must live until the atlas is built
};

OffscreenRenderer::OffscreenRenderer(int width, int height, float font_px, const std::string& font_file,
                                     const std::string& bold_file, const std::string& glyph_text)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.width = width;
  m.height = height;
  m.ctx = OSMesaCreateContextExt(OSMESA_RGBA, 0, 0, 0, nullptr);
  if (!m.ctx) throw std::runtime_error("OSMesa: cannot create an off-screen GL context");
  m.buffer.resize(static_cast<size_t>(width) * height * 4);
  if (!OSMesaMakeCurrent(m.ctx, m.buffer.data(), GL_UNSIGNED_BYTE, width, height)) {
    OSMesaDestroyContext(m.ctx);
    throw std::runtime_error("OSMesa: cannot make a " + std::to_string(width) + " x " + std::to_string(height) +
                             " buffer current (too large?)");
  }
  OSMesaPixelStore(OSMESA_Y_UP, 0);  // row 0 at the top, as in the PNG
  m.imgui = ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;
  io.DisplaySize = ImVec2(static_cast<float>(width), static_cast<float>(height));
  io.DeltaTime = 1.0f / 60.0f;
  // Latin-1, the dashes, minus and comparison signs figures print, and whatever else the figure's text uses.
  static const ImWchar common[] = {0x0020, 0x00FF, 0x2009, 0x2027, 0x2212, 0x2212, 0x2264, 0x2265, 0};
  ImFontGlyphRangesBuilder glyphs;
  glyphs.AddRanges(common);
  glyphs.AddText(glyph_text.c_str(), glyph_text.c_str() + glyph_text.size());
  glyphs.BuildRanges(&m.ranges);
  const ImWchar* ranges = m.ranges.Data;
  if (font_file.empty() || !io.Fonts->AddFontFromFileTTF(font_file.c_str(), font_px, nullptr, ranges)) {
    ImFontConfig cfg;
    cfg.SizePixels = font_px;
    io.Fonts->AddFontDefault(&cfg);
  }
  if (!bold_file.empty()) m.bold = io.Fonts->AddFontFromFileTTF(bold_file.c_str(), font_px, nullptr, ranges);
  ImGui_ImplOpenGL2_Init();
}

ImFont* OffscreenRenderer::bold_font() const { return impl_->bold; }

OffscreenRenderer::~OffscreenRenderer() {
  Impl& m = *impl_;
  for (GLuint t : m.textures) glDeleteTextures(1, &t);
  ImGui_ImplOpenGL2_Shutdown();
  ImGui::DestroyContext(m.imgui);
  OSMesaDestroyContext(m.ctx);
}

ImTextureID OffscreenRenderer::upload(const cv::Mat& bgr, int max_width) {
  cv::Mat img = bgr;
  if (img.cols > max_width) {
    const double k = static_cast<double>(max_width) / img.cols;
    cv::resize(img, img, cv::Size(), k, k, cv::INTER_AREA);
  }
  cv::Mat rgba;
  cv::cvtColor(img, rgba, cv::COLOR_BGR2RGBA);
  GLuint id = 0;
  glGenTextures(1, &id);
  glBindTexture(GL_TEXTURE_2D, id);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, rgba.cols, rgba.rows, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data);
  impl_->textures.push_back(id);
  return reinterpret_cast<ImTextureID>(static_cast<intptr_t>(id));
}

cv::Mat OffscreenRenderer::render(const std::function<void(const std::function<ImDrawList*()>&)>& draw) {
  Impl& m = *impl_;
  ImGui_ImplOpenGL2_NewFrame();
  ImGui::NewFrame();
  // Draw lists of our own, in drawing order: the OpenGL 2 renderer can't offset 16-bit indices, so a
  // figure with more than 65,536 vertices needs several lists (ImGuiCanvas asks for the next).
  std::vector<std::unique_ptr<ImDrawList>> lists;
  const auto more = [&]() {
    lists.push_back(std::make_unique<ImDrawList>(ImGui::GetDrawListSharedData()));
    ImDrawList* dl = lists.back().get();
    dl->_ResetForNewFrame();
    dl->PushTextureID(ImGui::GetIO().Fonts->TexID);
    dl->PushClipRectFullScreen();
    return dl;
  };
  draw(more);
  ImGui::Render();
  std::vector<ImDrawList*> cmd_lists;
  ImDrawData data;
  for (const auto& dl : lists) {
    dl->_PopUnusedDrawCmd();
    if (dl->CmdBuffer.Size == 0) continue;
    cmd_lists.push_back(dl.get());
    data.TotalVtxCount += dl->VtxBuffer.Size;
    data.TotalIdxCount += dl->IdxBuffer.Size;
  }
  data.Valid = true;
  data.CmdLists = cmd_lists.data();
  data.CmdListsCount = int(cmd_lists.size());
  data.DisplayPos = ImVec2(0, 0);
  data.DisplaySize = ImVec2(static_cast<float>(m.width), static_cast<float>(m.height));
  data.FramebufferScale = ImVec2(1, 1);
  glViewport(0, 0, m.width, m.height);
  glClearColor(1, 1, 1, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  ImGui_ImplOpenGL2_RenderDrawData(&data);
  glFinish();
  cv::Mat rgba(m.height, m.width, CV_8UC4, m.buffer.data());
  cv::Mat bgr;
  cv::cvtColor(rgba, bgr, cv::COLOR_RGBA2BGR);
  return bgr;
}

std::string render_png(const ui::DisplayList& fig, const ui::FontMetrics& metrics, double dpi) {
  const float px_per_pt = static_cast<float>(dpi / 72.0);
  const int w = static_cast<int>(std::lround(fig.width_pt * px_per_pt));
  const int h = static_cast<int>(std::ceil(fig.height_pt * px_per_pt));
  // ImGui's font atlas at the line height of the largest text figures use (--font-pt).
  double largest = 6;
  std::string all_text;
  for (const auto& t : fig.texts()) largest = std::max(largest, t.box.height()), all_text += t.text;
  OffscreenRenderer r(w, h, static_cast<float>(largest) * px_per_pt, metrics.file(), metrics.bold_file(), all_text);
  const cv::Mat bgr = r.render([&](const std::function<ImDrawList*()>& more) {
    ui::ImGuiCanvas canvas(
        more(), {0, 0}, px_per_pt, [&](const cv::Mat& img) { return r.upload(img, w); }, &metrics, r.bold_font(), more);
    fig.replay(canvas);
  });
  std::vector<uchar> png;
  if (!encode_picture(".png", bgr, &png)) throw std::runtime_error("PNG encoding failed");
  const std::string bytes(png.begin(), png.end());
  return fig.description.empty() ? bytes : ui::png_with_text(bytes, "Description", fig.description);
}

}  // namespace ipd::figure
