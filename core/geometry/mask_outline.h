// A pixel mask (a COCO run-length mask, decoded) as polygon contours along the pixels' edges, so that an
// outline made of them covers exactly the mask's pixels, not a contour through pixel centres that loses half a
// pixel all around (cv::findContours' convention).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace ipd {

// Pixels row by row, `on[y * width + x]` non-zero for the mask's pixels (a mask whose `on` is not width x height
// pixels has no contours).
struct PixelMask {
  int width = 0, height = 0;
  std::vector<uint8_t> on;
};

// The outer contour of each 4-connected component of `mask`, in pixel-corner coordinates (pixel (x, y) covers
// [x, x + 1] x [y, y + 1]), only the corners where the contour turns, every contour drawn the same way round
// (clockwise with y down). A contour encloses its component and the component's holes: a hole is filled. Two
// pixels that touch only at a corner are two components. Components are in the order of their first pixel row
// by row. At most `max_points` corners in all: past it, `*too_many` is set and the contours found so far are
// returned (a noise mask of a million specks is refused, not traced whole).
// `pixels`, when given, gets each component's pixel count.
std::vector<std::vector<Eigen::Vector2i>> mask_component_contours(const PixelMask& mask, size_t max_points,
                                                                  bool* too_many,
                                                                  std::vector<long long>* pixels = nullptr);

}  // namespace ipd
