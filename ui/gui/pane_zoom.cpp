#include "ui/gui/pane_zoom.h"

#include <algorithm>
#include <cmath>

namespace ipd::ui {

ImVec2 picture_point(const CanvasView& view, ImVec2 cursor, ImVec2 pane_size, int image_w, int image_h) {
  const Placement p = place({0, 0}, pane_size, image_w, image_h, view);
  return {(cursor.x - p.origin.x) / p.size.x, (cursor.y - p.origin.y) / p.size.y};
}

CanvasView partner_view(const CanvasView& self, ImVec2 cursor, ImVec2 pane_size, int image_w, int image_h,
                        const PictureMap& map) {
  const ImVec2 q = map(picture_point(self, cursor, pane_size, image_w, image_h));
  CanvasView other;
  other.zoom = self.zoom;
  const Placement p = place({0, 0}, pane_size, image_w, image_h, other);  // size only: pan moves the origin
  // place(): origin = centre - (0.5 + pan) * size; want origin + q * size = cursor.
  other.pan = {(0.5f * pane_size.x - cursor.x) / p.size.x + q.x - 0.5f,
               (0.5f * pane_size.y - cursor.y) / p.size.y + q.y - 0.5f};
  return other;
}

PaneAffine PaneAffine::inverse() const {
  const double det = m[0] * m[4] - m[1] * m[3];
  if (!std::isfinite(det) || std::abs(det) < 1e-9) return PaneAffine{};
  PaneAffine r;
  r.m[0] = m[4] / det, r.m[1] = -m[1] / det, r.m[3] = -m[3] / det, r.m[4] = m[0] / det;
  r.m[2] = -(r.m[0] * m[2] + r.m[1] * m[5]);
  r.m[5] = -(r.m[3] * m[2] + r.m[4] * m[5]);
  return r;
}

void zoom_at(CanvasView& view, float factor, ImVec2 mouse, ImVec2 p0, ImVec2 size, int w, int h) {
  const Placement before = place(p0, size, w, h, view);
  const float u = (mouse.x - before.origin.x) / before.size.x, t = (mouse.y - before.origin.y) / before.size.y;
  view.zoom = std::clamp(view.zoom * factor, 0.25f, 40.0f);
  const Placement after = place(p0, size, w, h, view);
  const ImVec2 origin{mouse.x - u * after.size.x, mouse.y - t * after.size.y};
  view.pan.x = (p0.x + 0.5f * size.x - origin.x) / after.size.x - 0.5f;
  view.pan.y = (p0.y + 0.5f * size.y - origin.y) / after.size.y - 0.5f;
}

CanvasView view_on_partner(const CanvasView& self_view, ImVec2 self, ImVec2 partner) {
  // place(): a point p is at centre + (p - 0.5 - pan) * size; the same size on both sides, so equal offsets need
  // p_partner - pan_partner = p_self - pan_self.
  return {self_view.zoom, {self_view.pan.x + partner.x - self.x, self_view.pan.y + partner.y - self.y}};
}

Quad warped_corners(const PaneAffine& left_from_right) {
  return {{left_from_right({0, 0}), left_from_right({1, 0}), left_from_right({1, 1}), left_from_right({0, 1})}};
}

bool blink_shows_right(double seconds, float flips_per_second, bool manual) {
  if (!(flips_per_second > 0)) return manual;
  return static_cast<long long>(std::floor(seconds * flips_per_second)) % 2 == 1;
}

CanvasView view_after_scene_change(const CanvasView& view, ZoomOnSceneChange rule) {
  return rule == ZoomOnSceneChange::kKeep ? view : CanvasView{};
}

}  // namespace ipd::ui
