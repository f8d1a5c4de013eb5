// The ImGui figure canvas on 16-bit indices (Debian's Dear ImGui, the OpenGL 2 renderer of `ipd figure
// --out x.png`): a figure of any size is split over draw lists of at most 65,536 vertices each, in drawing
// order, with the clip rectangles carried over to every new list.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "ui/gui/canvas_imgui.h"

namespace ipd::ui {
namespace {

// An ImGui frame and the draw lists a canvas asks for, as the off-screen renderer makes them.
class ImGuiFrame {
 public:
  ImGuiFrame() {
    ctx_ = ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.DisplaySize = ImVec2(4000, 3000);
    io.DeltaTime = 1.0f / 60;
    unsigned char* pixels = nullptr;
    int w = 0, h = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
    ImGui::NewFrame();
  }
  ~ImGuiFrame() {
    ImGui::EndFrame();
    lists.clear();
    ImGui::DestroyContext(ctx_);
  }
  ImDrawList* more() {
    lists.push_back(std::make_unique<ImDrawList>(ImGui::GetDrawListSharedData()));
    ImDrawList* dl = lists.back().get();
    dl->_ResetForNewFrame();
    dl->PushTextureID(ImGui::GetIO().Fonts->TexID);
    dl->PushClipRectFullScreen();
    return dl;
  }
  std::vector<std::unique_ptr<ImDrawList>> lists;

 private:
  ImGuiContext* ctx_ = nullptr;
};

TEST(ImGuiCanvasLists, ManyBoxesSplitOverListsOfAtMost64kVertices) {
  ImGuiFrame f;
  ImGuiCanvas c(f.more(), {0, 0}, 4, {}, nullptr, nullptr, [&] { return f.more(); });
  // One box first: the vertices a box costs (4 path points, 2 each with ImGui's textured anti-aliased lines).
  c.rect({1, 1, 5, 5}, rgb(0, 0, 0), 1);
  const int per_box = f.lists[0]->VtxBuffer.Size;
  ASSERT_EQ(per_box, 8);
  c.push_clip({10, 10, 500, 400});
  for (int i = 1; i < 30000; ++i)
    c.rect({10.0 + i % 400, 10.0 + i / 100, 14.0 + i % 400, 14.0 + i / 100}, rgb(0, 0, 0), 1);
  c.pop_clip();
  // 30,000 x 8 = 240,000 vertices: 4 lists at the least.
  ASSERT_GE(f.lists.size(), 4u);
  int total = 0;
  for (const auto& dl : f.lists) {
    EXPECT_LT(dl->_VtxCurrentIdx, 1u << 16);
    EXPECT_LT(dl->VtxBuffer.Size, 1 << 16);
    total += dl->VtxBuffer.Size;
  }
  EXPECT_EQ(total, 30000 * per_box);
  // Every later list starts inside the figure's clip (4 px per point), not the full screen.
  for (size_t k = 1; k < f.lists.size(); ++k) {
    const ImVec4 clip = f.lists[k]->CmdBuffer[0].ClipRect;
    EXPECT_FLOAT_EQ(clip.x, 40);
    EXPECT_FLOAT_EQ(clip.y, 40);
    EXPECT_FLOAT_EQ(clip.z, 2000);
    EXPECT_FLOAT_EQ(clip.w, 1600);
  }
}

TEST(ImGuiCanvasLists, APolylineLongerThanAListIsDrawnInPieces) {
  ImGuiFrame f;
  ImGuiCanvas c(f.more(), {0, 0}, 1, {}, nullptr, nullptr, [&] { return f.more(); });
  std::vector<Pt> points;
  for (int i = 0; i < 150000; ++i) points.push_back({double(i % 1000), double(i / 1000 * 2 + (i % 2))});
  c.polyline(points, rgb(0, 0, 0), 2, false);
  ASSERT_GE(f.lists.size(), 4u);  // 150,000 points x 2 vertices
  int total = 0;
  for (const auto& dl : f.lists) {
    EXPECT_LT(dl->_VtxCurrentIdx, 1u << 16);
    total += dl->VtxBuffer.Size;
  }
  // The pieces share their end points: 2 vertices per point, one point drawn twice per extra piece.
  EXPECT_EQ(total, 2 * (150000 + (150000 - 2) / 4095));
}

TEST(ImGuiCanvasLists, WithoutMoreListsEverythingStaysOnTheOneList) {
  // The GUI's OpenGL 3 renderer offsets vertices itself: its window list is never swapped.
  ImGuiFrame f;
  ImDrawList* dl = f.more();
  dl->Flags |= ImDrawListFlags_AllowVtxOffset;
  ImGuiCanvas c(dl, {0, 0}, 1, {});
  for (int i = 0; i < 5000; ++i) c.rect({0, 0, 4, 4}, rgb(0, 0, 0), 2);
  EXPECT_EQ(f.lists.size(), 1u);
  EXPECT_EQ(dl->VtxBuffer.Size, 5000 * 8);
}

}  // namespace
}  // namespace ipd::ui
