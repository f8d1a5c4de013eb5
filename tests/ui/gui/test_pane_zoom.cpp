// Focus layout and zoom syncing of the picture panes (ui/gui/pane_zoom.h, focus_columns), with
// hand-computed numbers.
#include <gtest/gtest.h>

#include "ui/gui/pane_zoom.h"
#include "ui/gui/studio_layout.h"

namespace ipd::ui {
namespace {

TEST(FocusColumns, PicturesGetAtLeastSixtyPercentOf1600x900) {
  // 1600 - 2 strips of 28 - 2 gaps of 8 = 1528 px for the pictures; the window's content is 900 less the
  // menu bar and status line (~2 x 19 px) and the 8 px margin: 854 px. 1528 x 854 / (1600 x 900) = 0.906.
  const StudioColumns c = focus_columns(1600, 8);
  EXPECT_FLOAT_EQ(c.left, 28);
  EXPECT_FLOAT_EQ(c.right, 28);
  EXPECT_FLOAT_EQ(c.centre, 1528);
  EXPECT_FALSE(c.tabbed_centre);
  EXPECT_GE(c.centre * 854 / (1600.0f * 900.0f), 0.6f);
  // The normal layout at the same width leaves the centre 1600 - 16 - 380 - 400 = 804 px: half as much.
  EXPECT_FLOAT_EQ(studio_columns(1600, 380, 400, 8).centre, 804);
}

TEST(FocusColumns, NeverNegativeInATinyWindow) {
  EXPECT_FLOAT_EQ(focus_columns(50, 8).centre, 0);
  EXPECT_TRUE(focus_columns(50, 8).tabbed_centre);
}

TEST(PaneZoom, PicturePointUnderTheCursor) {
  // A 1600x1000 picture fits a 400x250 pane exactly; zoom 2 about the centre: 800x500 at (-200, -125).
  const CanvasView v{2.0f, {0, 0}};
  const ImVec2 p = picture_point(v, {100, 50}, {400, 250}, 1600, 1000);
  EXPECT_FLOAT_EQ(p.x, 0.375f);  // (100 + 200) / 800
  EXPECT_FLOAT_EQ(p.y, 0.35f);   // (50 + 125) / 500
}

TEST(PaneZoom, PartnerLandsUnderTheSameSpotOfTheOtherPane) {
  // The affine moves the point under the cursor (0.375, 0.35) to (0.475, 0.3): the other pane is panned by
  // (100 - 200)/800... = x: (200 - 100) / 800 + 0.475 - 0.5 = 0.1, y: (125 - 50) / 500 + 0.3 - 0.5 = -0.05.
  PaneAffine shift;
  shift.m[2] = 0.1, shift.m[5] = -0.05;
  const CanvasView self{2.0f, {0, 0}};
  const CanvasView other = partner_view(self, {100, 50}, {400, 250}, 1600, 1000, shift);
  EXPECT_FLOAT_EQ(other.zoom, 2.0f);
  EXPECT_NEAR(other.pan.x, 0.1f, 1e-6);
  EXPECT_NEAR(other.pan.y, -0.05f, 1e-6);
  const ImVec2 under = picture_point(other, {100, 50}, {400, 250}, 1600, 1000);
  EXPECT_NEAR(under.x, 0.475f, 1e-6);
  EXPECT_NEAR(under.y, 0.3f, 1e-6);
}

TEST(PaneZoom, SyncingPictureCoordinatesLeavesThePartnerOffByTheShift) {
  // Copying the view (what matching picture coordinates does) puts (0.375, 0.35) of the other picture under
  // the cursor, 0.1 x 800 = 80 px left of the partner.
  const CanvasView self{2.0f, {0, 0}};
  const ImVec2 copied = picture_point(self, {100, 50}, {400, 250}, 1600, 1000);
  EXPECT_NEAR((0.475f - copied.x) * 800, 80, 1e-3);
}

TEST(PaneZoom, AffineInverseUndoesIt) {
  PaneAffine a;
  a.m[0] = 2, a.m[2] = 0.1, a.m[4] = 0.5, a.m[5] = -0.2;
  const PaneAffine inv = a.inverse();
  EXPECT_DOUBLE_EQ(inv.m[0], 0.5);
  EXPECT_DOUBLE_EQ(inv.m[4], 2);
  EXPECT_DOUBLE_EQ(inv.m[2], -0.05);
  EXPECT_DOUBLE_EQ(inv.m[5], 0.4);
  const ImVec2 q = a({0.3f, 0.4f});
  EXPECT_NEAR(q.x, 0.7f, 1e-6);
  EXPECT_NEAR(q.y, 0.0f, 1e-6);
  const ImVec2 back = inv(q);
  EXPECT_NEAR(back.x, 0.3f, 1e-6);
  EXPECT_NEAR(back.y, 0.4f, 1e-6);
}

TEST(PaneZoom, SingularAffineFallsBackToPictureCoordinates) {
  PaneAffine collapsed;
  collapsed.m[0] = collapsed.m[1] = collapsed.m[3] = collapsed.m[4] = 0;
  const ImVec2 p = collapsed.inverse()({0.25f, 0.75f});
  EXPECT_FLOAT_EQ(p.x, 0.25f);
  EXPECT_FLOAT_EQ(p.y, 0.75f);
}

TEST(PaneZoom, SceneChangeResetsUnlessKept) {
  const CanvasView zoomed{3.0f, {0.2f, -0.1f}};
  const CanvasView reset = view_after_scene_change(zoomed, ZoomOnSceneChange::kReset);
  EXPECT_FLOAT_EQ(reset.zoom, 1.0f);
  EXPECT_FLOAT_EQ(reset.pan.x, 0.0f);
  EXPECT_FLOAT_EQ(reset.pan.y, 0.0f);
  const CanvasView kept = view_after_scene_change(zoomed, ZoomOnSceneChange::kKeep);
  EXPECT_FLOAT_EQ(kept.zoom, 3.0f);
  EXPECT_FLOAT_EQ(kept.pan.x, 0.2f);
}

}  // namespace
}  // namespace ipd::ui
