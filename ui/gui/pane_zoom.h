// Zoom and pan of the two picture panes that need no ImGui context, so tests can check them with
// hand-computed numbers: syncing one pane's view to the other through the scene's registration affine
// (the partner of the point under the cursor lands under the same spot of the other pane), and what a
// view becomes when the scene changes.
#pragma once

#include <functional>

#include "ui/gui/scene_canvas.h"

namespace ipd::ui {

// Maps a normalised picture point of the pane the user zooms to the matching point of the other picture
// (the registration's b_from_a, or its inverse when the left side is B).
using PictureMap = std::function<ImVec2(ImVec2)>;

// The other pane's view: the same zoom, panned so that map(p), p being the picture point under `cursor`
// in this pane, sits under the same offset from the other pane's origin. Both panes have `pane_size` and
// show pictures of `image_w` x `image_h` (the pair's pictures share a resolution).
CanvasView partner_view(const CanvasView& self, ImVec2 cursor_in_pane, ImVec2 pane_size, int image_w, int image_h,
                        const PictureMap& map);

// The normalised picture point under `cursor_in_pane` (pane origin at 0, 0) for `view`.
ImVec2 picture_point(const CanvasView& view, ImVec2 cursor_in_pane, ImVec2 pane_size, int image_w, int image_h);

// A 2x3 affine on normalised points (row-major a, b, tx / c, d, ty) and its inverse; a singular affine
// (a registration that collapsed) maps through unchanged, so zoom falls back to the picture coordinates.
struct PaneAffine {
  double m[6] = {1, 0, 0, 0, 1, 0};
  ImVec2 operator()(ImVec2 p) const {
    return {float(m[0] * p.x + m[1] * p.y + m[2]), float(m[3] * p.x + m[4] * p.y + m[5])};
  }
  PaneAffine inverse() const;
};

// Zooms `view` by `factor` (kept within 0.25-40) about the screen point `mouse`: the picture point under it stays
// under it. The pane is at `p0` with `size`, showing a picture of `w` x `h`.
void zoom_at(CanvasView& view, float factor, ImVec2 mouse, ImVec2 p0, ImVec2 size, int w, int h);

// The other pane's view showing `partner` (a normalised point of its picture) where `self_view` shows `self`:
// the same zoom, panned by the points' offset, so a selected rock's partner sits where the rock sits.
CanvasView view_on_partner(const CanvasView& self_view, ImVec2 self, ImVec2 partner);

// The blink view draws the right picture over the left one through the scene's registration. The right picture's
// corners (0,0), (1,0), (1,1), (0,1) in the left picture's normalised coordinates, through `left_from_right`
// (an affine maps the rectangle onto a parallelogram, so four corners place the whole picture exactly).
struct Quad {
  ImVec2 p[4];
};
Quad warped_corners(const PaneAffine& left_from_right);

// Which picture the blink view shows when it alternates: the right one on odd half-periods of `flips_per_second`
// flips a second, counted from `seconds` = 0; with no rate (<= 0), `manual` (the key's choice).
bool blink_shows_right(double seconds, float flips_per_second, bool manual);

// What the panes' views become on a scene change: reset to the whole picture unless the user asked to keep
// the zoom across scenes.
enum class ZoomOnSceneChange { kReset, kKeep };
CanvasView view_after_scene_change(const CanvasView& view, ZoomOnSceneChange rule);

}  // namespace ipd::ui
