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

TEST(PaneZoom, TheSelectedRocksPartnerSitsWhereTheRockSits) {
  // Left view zoom 2.5, pan (-0.1, 0.05), the rock at (0.3, 0.4) off the pane's centre. Its partner is at
  // (0.7, 0.25): the right view is panned by the offset (0.4, -0.15), to (0.3, -0.1), the same zoom.
  const CanvasView left{2.5f, {-0.1f, 0.05f}};
  const CanvasView right = view_on_partner(left, {0.3f, 0.4f}, {0.7f, 0.25f});
  EXPECT_FLOAT_EQ(right.zoom, 2.5f);
  EXPECT_NEAR(right.pan.x, 0.3f, 1e-6);
  EXPECT_NEAR(right.pan.y, -0.1f, 1e-6);
  // Both points land on the same spot of their panes (400 x 250, a 1600 x 1000 picture shown 1000 x 625):
  // 200 + (0.3 - 0.5 + 0.1) x 1000 = 100 px, 125 + (0.4 - 0.5 - 0.05) x 625 = 31.25 px.
  const Placement pl = place({0, 0}, {400, 250}, 1600, 1000, left), pr = place({0, 0}, {400, 250}, 1600, 1000, right);
  EXPECT_NEAR(pl.to_screen(0.3, 0.4).x, 100, 1e-3);
  EXPECT_NEAR(pl.to_screen(0.3, 0.4).y, 31.25, 1e-3);
  EXPECT_NEAR(pr.to_screen(0.7, 0.25).x, 100, 1e-3);
  EXPECT_NEAR(pr.to_screen(0.7, 0.25).y, 31.25, 1e-3);
}

TEST(BlinkView, TheRightPictureIsLaidOverTheLeftThroughTheAffine) {
  // left_from_right: scale 0.5 about the origin, then shift (0.1, 0.2): the right picture's corners land at
  // (0.1, 0.2), (0.6, 0.2), (0.6, 0.7), (0.1, 0.7) of the left one.
  PaneAffine m;
  m.m[0] = 0.5, m.m[2] = 0.1, m.m[4] = 0.5, m.m[5] = 0.2;
  const Quad q = warped_corners(m);
  const float want[4][2] = {{0.1f, 0.2f}, {0.6f, 0.2f}, {0.6f, 0.7f}, {0.1f, 0.7f}};
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(q.p[k].x, want[k][0], 1e-6) << k;
    EXPECT_NEAR(q.p[k].y, want[k][1], 1e-6) << k;
  }
  // A rotation by 90 degrees (x, y) -> (1 - y, x) turns the rectangle, corner (1, 0) to (1, 1).
  PaneAffine r;
  r.m[0] = 0, r.m[1] = -1, r.m[2] = 1, r.m[3] = 1, r.m[4] = 0, r.m[5] = 0;
  EXPECT_NEAR(warped_corners(r).p[1].x, 1, 1e-6);
  EXPECT_NEAR(warped_corners(r).p[1].y, 1, 1e-6);
}

TEST(BlinkView, AlternatesAtTheRateOrShowsWhatTheKeyChose) {
  // 2 flips a second: [0, 0.5) the left picture, [0.5, 1) the right, [1, 1.5) the left again.
  EXPECT_FALSE(blink_shows_right(0.2, 2, true));
  EXPECT_TRUE(blink_shows_right(0.7, 2, false));
  EXPECT_FALSE(blink_shows_right(1.2, 2, true));
  EXPECT_TRUE(blink_shows_right(1.6, 2, false));
  // No rate: the key's choice, whatever the time.
  EXPECT_TRUE(blink_shows_right(0.7, 0, true));
  EXPECT_FALSE(blink_shows_right(0.7, 0, false));
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
