#include "core/geometry/mask_outline.h"

#include <array>

namespace ipd {

namespace {

// Directions along pixel edges, y down: east, south, west, north; a right turn is +1.
constexpr std::array<int, 4> kDx = {1, 0, -1, 0};
constexpr std::array<int, 4> kDy = {0, 1, 0, -1};

// Marks the 4-connected component of pixel `first` traced (state 1 -> 2); returns its pixel count.
long long mark_traced(size_t first, int w, int h, std::vector<uint8_t>* state, std::vector<size_t>* stack) {
  stack->assign(1, first);
  (*state)[first] = 2;
  long long count = 0;
  while (!stack->empty()) {
    ++count;
    const size_t k = stack->back();
    stack->pop_back();
    const int px = static_cast<int>(k % w), py = static_cast<int>(k / w);
    for (int n = 0; n < 4; ++n) {
      const int qx = px + kDx[n], qy = py + kDy[n];
      if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
      const size_t q = size_t(qy) * w + qx;
      if ((*state)[q] == 1) {
        (*state)[q] = 2;
        stack->push_back(q);
      }
    }
  }
  return count;
}

}  // namespace

std::vector<std::vector<Eigen::Vector2i>> mask_component_contours(const PixelMask& mask, size_t max_points,
                                                                  bool* too_many, std::vector<long long>* pixels) {
  if (pixels) pixels->clear();
  *too_many = false;
  const int w = mask.width, h = mask.height;
  if (w <= 0 || h <= 0 || mask.on.size() != static_cast<size_t>(w) * static_cast<size_t>(h)) return {};
  // 0: background, 1: a pixel of a component not traced yet, 2: of one traced.
  std::vector<uint8_t> state(mask.on.size());
  for (size_t k = 0; k < state.size(); ++k) state[k] = mask.on[k] ? 1 : 0;
  const auto on = [&](int x, int y) { return x >= 0 && y >= 0 && x < w && y < h && state[size_t(y) * w + x] != 0; };
  // The pixels ahead of vertex (x, y) moving in direction d: on the right and on the left of the edge ahead.
  const auto ahead_right = [&](int x, int y, int d) {
    switch (d) {
      case 0:
        return on(x, y);
      case 1:
        return on(x - 1, y);
      case 2:
        return on(x - 1, y - 1);
      default:
        return on(x, y - 1);
    }
  };
  const auto ahead_left = [&](int x, int y, int d) {
    switch (d) {
      case 0:
        return on(x, y - 1);
      case 1:
        return on(x, y);
      case 2:
        return on(x - 1, y);
      default:
        return on(x - 1, y - 1);
    }
  };
  std::vector<std::vector<Eigen::Vector2i>> contours;
  size_t points = 0;
  std::vector<size_t> stack;
  for (int y0 = 0; y0 < h; ++y0)
    for (int x0 = 0; x0 < w; ++x0) {
      if (state[size_t(y0) * w + x0] != 1) continue;
      // The first pixel of its component row by row: its top edge is on the component's outer contour. Walk the
      // contour with the component on the right, turning right as soon as the pixel ahead-right is background (so
      // a pixel touching the current one only at a corner is never joined to it: 4-connectivity).
      std::vector<Eigen::Vector2i> contour;
      int x = x0, y = y0, d = 3;  // as the walk arrives at its start at the end: going north up the left edge
      for (size_t step = 0;; ++step) {
        if (points + contour.size() > max_points) {  // a speckle of thousands of pieces: the caller refuses it
          *too_many = true;
          contours.push_back(std::move(contour));
          return contours;
        }
        if (step > 4 * mask.on.size()) return {};  // never: each pixel edge is walked at most once
        const int next = !ahead_right(x, y, d) ? (d + 1) % 4 : !ahead_left(x, y, d) ? d : (d + 3) % 4;
        if (next != d) {
          // Back at the start, leaving along the top edge again: the contour is closed. (A walk through the start
          // corner at a pinch, where a pixel touches it diagonally, leaves another way.)
          if (x == x0 && y == y0 && next == 0 && !contour.empty()) break;
          contour.emplace_back(x, y);
        }
        d = next;
        x += kDx[d];
        y += kDy[d];
      }
      points += contour.size();
      contours.push_back(std::move(contour));
      const long long count = mark_traced(size_t(y0) * w + x0, w, h, &state, &stack);
      if (pixels) pixels->push_back(count);
    }
  return contours;
}

}  // namespace ipd
