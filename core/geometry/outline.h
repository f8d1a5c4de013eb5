// Instance outlines (segmentation masks as polygons) and mask IoU: the performance value of the `segment` task.
#pragma once

#include <Eigen/Core>
#include <atomic>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace ipd {

// A polygon in normalised picture coordinates, as YOLO-seg and COCO write masks. The filled region is the set of
// points of non-zero winding number: a contour that crosses itself (a figure eight) fills both of its lobes, the
// way a polygon rasteriser with the non-zero rule draws it, so no line is refused for being drawn in two turns.
struct Outline {
  std::vector<Eigen::Vector2d> points;    // as read; not closed (the last point joins the first)
  double area = 0;                        // of the filled region (normalised: a picture is 1)
  Eigen::Vector2d centroid{0, 0};         // of the filled region
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // bounds of the points
};

// A box's outline, shared by every copy of the box (boxes are copied by every filter and view; an outline's points
// are not): a pointer with the count of its owners beside the outline, 8 bytes in each box where a shared_ptr took
// 16. A study's millions of boxes mostly have none, and a box of 64 bytes was 16 of them pointer; 56 now.
class OutlineRef {
 public:
  OutlineRef() = default;
  OutlineRef(std::nullptr_t) {}  // NOLINT: "no outline", as a pointer
  OutlineRef(const OutlineRef& o) : node_(o.node_) {
    if (node_) node_->owners.fetch_add(1, std::memory_order_relaxed);
  }
  OutlineRef(OutlineRef&& o) noexcept : node_(o.node_) { o.node_ = nullptr; }
  OutlineRef& operator=(OutlineRef o) noexcept {
    std::swap(node_, o.node_);
    return *this;
  }
  ~OutlineRef() {
    if (node_ && node_->owners.fetch_sub(1, std::memory_order_acq_rel) == 1) delete node_;
  }
  // A new, empty outline for its maker to fill through fill() before the box that holds it is copied.
  static OutlineRef make() {
    OutlineRef r;
    r.node_ = new Node;
    return r;
  }
  Outline* fill() { return node_ ? &node_->outline : nullptr; }
  const Outline* get() const { return node_ ? &node_->outline : nullptr; }
  const Outline* operator->() const { return get(); }
  const Outline& operator*() const { return node_->outline; }
  explicit operator bool() const { return node_ != nullptr; }
  bool operator==(std::nullptr_t) const { return node_ == nullptr; }
  bool operator!=(std::nullptr_t) const { return node_ != nullptr; }

 private:
  struct Node {
    std::atomic<long> owners{1};
    Outline outline;
  };
  Node* node_ = nullptr;
};

// More points than this in one outline is refused: clipping cost grows with the product of two outlines' sizes.
constexpr size_t kMaxOutlinePoints = 10000;

// Builds an outline from points, or returns why not: fewer than 3 points, more than kMaxOutlinePoints, or a
// filled region with no area (all points on one line).
std::string make_outline(std::vector<Eigen::Vector2d> points, Outline* out);

// Area of the intersection of two outlines' filled regions (exact up to rounding at 2^-50 of the picture).
double outline_intersection_area(const Outline& a, const Outline& b);

// The outline's region as triangles (indices into points, three per triangle), by ear clipping, to fill it
// where a drawing API fills only convex shapes; empty for a contour that crosses itself or has more than
// kMaxTriangulatedPoints points (drawn unfilled then: ear clipping's worst case grows with the cube of the points,
// and a fill is drawn within a frame).
constexpr size_t kMaxTriangulatedPoints = 256;
std::vector<int> outline_triangles(const Outline& o);

// Mask IoU: intersection over union of the filled regions; 0 when their bounds do not overlap (no clipping then).
double mask_iou(const Outline& a, const Outline& b);

}  // namespace ipd
