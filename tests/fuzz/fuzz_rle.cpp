// Fuzzes COCO run-length masks: the input is "H W\n" (a mask of up to 64 x 64 pixels) then the counts, a JSON list
// ("[3, 5, 2, 6]") or pycocotools' compressed string. Besides a crash or a hang: a mask read without a contour, an
// outline that is not its piece with the holes filled, pixels neither in the outline nor counted as left out, or a
// message that grows with the input.
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/geometry/outline.h"
#include "core/study/coco_segmentation.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const size_t eol = text.find('\n');
  if (eol == std::string::npos) return 0;
  int h = 0, w = 0;
  if (std::sscanf(text.substr(0, eol).c_str(), "%d %d", &h, &w) != 2 || h < 1 || w < 1 || h > 64 || w > 64) return 0;
  const std::string counts = text.substr(eol + 1);
  nlohmann::json seg = {{"size", {h, w}}};
  if (!counts.empty() && counts[0] == '[') {
    seg["counts"] = nlohmann::json::parse(counts, nullptr, false);
    if (seg["counts"].is_discarded()) return 0;
  } else {
    seg["counts"] = counts;
  }
  ipd::CocoSegmentation s;
  const std::string why = ipd::read_coco_segmentation(seg, w, h, &s);
  if (!why.empty()) {
    if (why.size() > ipd_fuzz::kMaxMessage) ipd_fuzz::fail("the error message grows with the input", why);
    return 0;
  }
  if (!s.rle || s.polygons.empty() || s.mask_pixels <= 0) ipd_fuzz::fail("a mask read without a contour", counts);
  const std::vector<double> merged = ipd::merge_polygon_parts(s.polygons);
  std::vector<Eigen::Vector2d> points;
  for (size_t k = 0; k + 1 < merged.size(); k += 2) points.emplace_back(merged[k], merged[k + 1]);
  ipd::Outline o;
  if (const std::string bad = ipd::make_outline(points, &o); !bad.empty())
    ipd_fuzz::fail("a mask's contour is no outline", bad);
  // The outline's region is the kept piece with its holes filled, exactly: the piece is the pixels 4-connected
  // to the contour's first corner's pixel; its region, the pixels not reached from outside the mask's bounds
  // through pixels of no other piece but stepping to any of 8 neighbours (a gap at a corner is no wall).
  std::vector<long long> runs;
  if (seg["counts"].is_string())
    ipd::decode_rle_counts(seg["counts"].get<std::string>(), &runs);
  else
    runs = seg["counts"].get<std::vector<long long>>();
  const ipd::RleMask m = ipd::decode_rle_mask(runs, h, w);
  const int cw = m.pixels.width, ch = m.pixels.height, pw = cw + 2, ph = ch + 2;  // a frame of background around
  const int sx = static_cast<int>(std::lround(s.polygons[0][0] * w)) - m.x;
  const int sy = static_cast<int>(std::lround(s.polygons[0][1] * h)) - m.y;
  const auto set = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < cw && y < ch && m.pixels.on[static_cast<size_t>(y) * cw + x] != 0;
  };
  if (!set(sx, sy)) ipd_fuzz::fail("the contour does not start at a pixel of the mask", counts);
  std::vector<char> piece(static_cast<size_t>(cw) * ch, 0);
  std::vector<std::pair<int, int>> stack = {{sx, sy}};
  piece[static_cast<size_t>(sy) * cw + sx] = 1;
  long long piece_pixels = 0;
  while (!stack.empty()) {
    const auto [x, y] = stack.back();
    stack.pop_back();
    ++piece_pixels;
    for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
      const int qx = x + dx, qy = y + dy;
      if (!set(qx, qy) || piece[static_cast<size_t>(qy) * cw + qx]) continue;
      piece[static_cast<size_t>(qy) * cw + qx] = 1;
      stack.emplace_back(qx, qy);
    }
  }
  const auto wall = [&](int x, int y) {  // padded coordinates
    return x >= 1 && y >= 1 && x <= cw && y <= ch && piece[static_cast<size_t>(y - 1) * cw + (x - 1)] != 0;
  };
  std::vector<char> outside(static_cast<size_t>(pw) * ph, 0);
  stack = {{0, 0}};
  outside[0] = 1;
  long long reached = 1;
  while (!stack.empty()) {
    const auto [x, y] = stack.back();
    stack.pop_back();
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int qx = x + dx, qy = y + dy;
        if (qx < 0 || qy < 0 || qx >= pw || qy >= ph || wall(qx, qy) || outside[size_t(qy) * pw + qx]) continue;
        outside[size_t(qy) * pw + qx] = 1;
        ++reached;
        stack.emplace_back(qx, qy);
      }
  }
  const long long filled = static_cast<long long>(pw) * ph - reached;
  if (std::fabs(o.area * h * w - static_cast<double>(filled)) > 1e-6)
    ipd_fuzz::fail("the outline is not its piece with the holes filled", counts);
  // Every pixel is the kept piece's, inside its contour, or counted as left out.
  if (s.mask_pixels - s.pixels_left_out > filled || s.pixels_left_out > s.mask_pixels - piece_pixels)
    ipd_fuzz::fail("pixels neither in the outline nor counted as left out", counts);
  return 0;
}
