#include "core/geometry/outline.h"

#include <fmt/format.h>
#include <polyclipping/clipper.hpp>

#include <algorithm>
#include <cmath>

namespace ipd {

namespace {

// Clipper works on integers. Normalised coordinates (at most 1.001 with the reader's rounding tolerance) scaled
// by 2^50 stay inside its 62-bit range, and rounding a vertex to 2^-50 moves an area by far less than a double's
// own rounding of the picture-sized numbers involved.
constexpr double kScale = 1125899906842624.0;  // 2^50

ClipperLib::Path to_path(const std::vector<Eigen::Vector2d>& points) {
  ClipperLib::Path path;
  path.reserve(points.size());
  for (const Eigen::Vector2d& p : points)
    path.emplace_back(static_cast<ClipperLib::cInt>(std::llround(p.x() * kScale)),
                      static_cast<ClipperLib::cInt>(std::llround(p.y() * kScale)));
  return path;
}

// Net area of the paths Clipper returns (outer contours positive, holes negative), in normalised units.
double net_area(const ClipperLib::Paths& paths) {
  double sum = 0;
  for (const ClipperLib::Path& p : paths) sum += ClipperLib::Area(p);
  return sum / (kScale * kScale);
}

}  // namespace

std::string make_outline(std::vector<Eigen::Vector2d> points, Outline* out) {
  if (points.size() < 3) return fmt::format("expected an outline of at least 3 points, found {}", points.size());
  if (points.size() > kMaxOutlinePoints)
    return fmt::format("expected an outline of at most {} points, found {}", kMaxOutlinePoints, points.size());
  Outline o;
  o.x0 = o.x1 = points[0].x();
  o.y0 = o.y1 = points[0].y();
  for (const Eigen::Vector2d& p : points) {
    o.x0 = std::min(o.x0, p.x()), o.x1 = std::max(o.x1, p.x());
    o.y0 = std::min(o.y0, p.y()), o.y1 = std::max(o.y1, p.y());
  }
  // The filled region by the non-zero rule, as non-crossing contours: its area and centroid are then sums of
  // shoelace terms (holes count negative), which a crossing contour's own shoelace sum would get wrong.
  ClipperLib::Paths filled;
  ClipperLib::SimplifyPolygon(to_path(points), filled, ClipperLib::pftNonZero);
  double area2 = 0, cx6 = 0, cy6 = 0;  // twice the area; six times area times the centroid
  for (const ClipperLib::Path& path : filled) {
    for (size_t i = 0; i < path.size(); ++i) {
      const ClipperLib::IntPoint& p = path[i];
      const ClipperLib::IntPoint& q = path[(i + 1) % path.size()];
      const double px = p.X / kScale, py = p.Y / kScale, qx = q.X / kScale, qy = q.Y / kScale;
      const double cross = px * qy - qx * py;
      area2 += cross;
      cx6 += (px + qx) * cross;
      cy6 += (py + qy) * cross;
    }
  }
  o.area = 0.5 * area2;
  if (!(o.area > 0))
    return fmt::format("expected an outline that encloses an area, found {} points with none (on one line)",
                       points.size());
  o.centroid = {cx6 / (3 * area2), cy6 / (3 * area2)};
  o.points = std::move(points);
  *out = std::move(o);
  return {};
}

std::vector<int> outline_triangles(const Outline& o) {
  const std::vector<Eigen::Vector2d>& p = o.points;
  if (p.size() < 3 || p.size() > kMaxTriangulatedPoints) return {};
  std::vector<int> left(p.size());
  for (size_t k = 0; k < p.size(); ++k) left[k] = static_cast<int>(k);
  double signed_area2 = 0;
  for (size_t k = 0; k < p.size(); ++k) {
    const Eigen::Vector2d& a = p[k];
    const Eigen::Vector2d& b = p[(k + 1) % p.size()];
    signed_area2 += a.x() * b.y() - b.x() * a.y();
  }
  const double turn = signed_area2 > 0 ? 1.0 : -1.0;  // ears turn the polygon's own way
  auto cross = [&](int a, int b, int c) {
    return ((p[b] - p[a]).x() * (p[c] - p[a]).y() - (p[b] - p[a]).y() * (p[c] - p[a]).x()) * turn;
  };
  std::vector<int> triangles;
  while (left.size() > 3) {
    bool clipped = false;
    for (size_t k = 0; k < left.size() && !clipped; ++k) {
      const int a = left[(k + left.size() - 1) % left.size()], b = left[k], c = left[(k + 1) % left.size()];
      if (cross(a, b, c) <= 0) continue;  // a reflex corner (or none): not an ear
      bool empty = true;                  // no other corner inside the ear
      for (const int q : left) {
        if (q == a || q == b || q == c) continue;
        if (cross(a, b, q) >= 0 && cross(b, c, q) >= 0 && cross(c, a, q) >= 0) empty = false;
      }
      if (!empty) continue;
      triangles.insert(triangles.end(), {a, b, c});
      left.erase(left.begin() + static_cast<long>(k));
      clipped = true;
    }
    if (!clipped) return {};  // no ear: the contour crosses itself
  }
  triangles.insert(triangles.end(), left.begin(), left.end());
  return triangles;
}

double outline_intersection_area(const Outline& a, const Outline& b) {
  if (a.x1 <= b.x0 || b.x1 <= a.x0 || a.y1 <= b.y0 || b.y1 <= a.y0) return 0.0;
  ClipperLib::Clipper clipper;
  clipper.AddPath(to_path(a.points), ClipperLib::ptSubject, true);
  clipper.AddPath(to_path(b.points), ClipperLib::ptClip, true);
  ClipperLib::Paths common;
  clipper.Execute(ClipperLib::ctIntersection, common, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  return std::max(0.0, net_area(common));
}

double mask_iou(const Outline& a, const Outline& b) {
  if (!(a.area > 0) || !(b.area > 0)) return 0.0;
  const double inter = outline_intersection_area(a, b);
  if (!(inter > 0)) return 0.0;
  const double uni = a.area + b.area - inter;
  if (!(uni > 0)) return 0.0;
  return std::clamp(inter / uni, 0.0, 1.0);
}

}  // namespace ipd
