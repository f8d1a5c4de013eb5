#include "ui/gui/pane_zoom.h"

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

CanvasView view_after_scene_change(const CanvasView& view, ZoomOnSceneChange rule) {
  return rule == ZoomOnSceneChange::kKeep ? view : CanvasView{};
}

}  // namespace ipd::ui
