#include "core/study/coco_segmentation.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>

#include "core/geometry/outline.h"
#include "core/util/json_input.h"

namespace ipd {

namespace {

constexpr double kPixelSlack = 1.0;  // a pixel of rounding beyond the border is fine, as for a bbox

std::string read_polygons(const nlohmann::json& seg, double width, double height, CocoSegmentation* out) {
  for (size_t k = 0; k < seg.size(); ++k) {
    const nlohmann::json& part = seg[k];
    if (!part.is_array() ||
        !std::all_of(part.begin(), part.end(), [](const nlohmann::json& v) { return v.is_number(); }))
      return fmt::format("segmentation[{}]: expected a polygon [x1, y1, x2, y2, ...] of numbers, found {}", k,
                         describe_json(part));
    if (part.size() % 2 != 0)
      return fmt::format("segmentation[{}]: a polygon has an odd number of coordinates ({}); expected x, y pairs", k,
                         part.size());
    if (part.size() < 6)
      return fmt::format("segmentation[{}]: a polygon of {} point(s); expected at least 3 (x, y pairs)", k,
                         part.size() / 2);
    std::vector<double> points;
    for (size_t j = 0; j < part.size(); j += 2) {
      const double x = part[j], y = part[j + 1];
      if (!std::isfinite(x) || !std::isfinite(y) || x < -kPixelSlack || y < -kPixelSlack || x > width + kPixelSlack ||
          y > height + kPixelSlack)
        return fmt::format("segmentation[{}]: point {} ({}, {}) is outside the {}x{} image", k, j / 2 + 1, x, y, width,
                           height);
      points.push_back(std::clamp(x / width, 0.0, 1.0));
      points.push_back(std::clamp(y / height, 0.0, 1.0));
    }
    out->polygons.push_back(std::move(points));
  }
  return {};
}

// An outline is one ring: the piece whose outer contour encloses the most (holes filled). Pieces inside it (in
// a hole) are covered; the others are left out and counted. Joining them by bridges would make contours that
// run along each other's pixel edges, which polygon clipping does not fill reliably.
const std::vector<Eigen::Vector2i>& enclosing_piece(const std::vector<std::vector<Eigen::Vector2i>>& contours,
                                                    const std::vector<long long>& piece_pixels, long long* left_out,
                                                    int* pieces_left_out) {
  const auto twice_area = [](const std::vector<Eigen::Vector2i>& c) {
    long long a = 0;
    for (size_t k = 0; k < c.size(); ++k) {
      const Eigen::Vector2i& p = c[k];
      const Eigen::Vector2i& q = c[(k + 1) % c.size()];
      a += static_cast<long long>(p.x()) * q.y() - static_cast<long long>(q.x()) * p.y();
    }
    return a;
  };
  size_t best = 0;
  for (size_t k = 1; k < contours.size(); ++k)
    if (twice_area(contours[k]) > twice_area(contours[best])) best = k;
  const std::vector<Eigen::Vector2i>& ring = contours[best];
  const auto inside = [&](double px, double py) {  // crossing test of a pixel's centre, never on the ring
    bool in = false;
    for (size_t k = 0, j = ring.size() - 1; k < ring.size(); j = k++) {
      const double xk = ring[k].x(), yk = ring[k].y(), xj = ring[j].x(), yj = ring[j].y();
      if ((yk > py) != (yj > py) && px < (xj - xk) * (py - yk) / (yj - yk) + xk) in = !in;
    }
    return in;
  };
  for (size_t k = 0; k < contours.size(); ++k)
    if (k != best && !inside(contours[k][0].x() + 0.5, contours[k][0].y() + 0.5)) {
      *left_out += piece_pixels[k];
      ++*pieces_left_out;
    }
  return ring;
}

std::string read_rle(const nlohmann::json& seg, double width, double height, CocoSegmentation* out) {
  const auto size = seg.find("size");
  if (size == seg.end() || !size->is_array() || size->size() != 2 || !(*size)[0].is_number_integer() ||
      !(*size)[1].is_number_integer())
    return "expected an RLE {\"counts\", \"size\": [height, width]}, found " + describe_json(seg);
  const long long h = (*size)[0], w = (*size)[1];
  if (static_cast<double>(h) != height || static_cast<double>(w) != width)
    return fmt::format("RLE size [{}, {}] is not the image's [height, width] [{}, {}]", h, w, height, width);
  if (h > kMaxRleMaskPixels || w > kMaxRleMaskPixels || h * w > kMaxRleMaskPixels)
    return fmt::format("RLE size [{}, {}]: a mask of more than {} pixels; expected a picture's (at most 50 megapixels)",
                       h, w, kMaxRleMaskPixels);
  std::vector<long long> counts;
  const auto c = seg.find("counts");
  if (c != seg.end() && c->is_string()) {
    if (!decode_rle_counts(c->get<std::string>(), &counts))
      return "RLE counts: expected pycocotools' compressed counts, found " + describe_json(*c);
  } else if (c != seg.end() && c->is_array() &&
             std::all_of(c->begin(), c->end(), [](const nlohmann::json& v) { return v.is_number_integer(); })) {
    for (const auto& v : *c) counts.push_back(v.get<long long>());
  } else {
    return "RLE counts: expected a list of run lengths or a compressed string, found " +
           (c == seg.end() ? std::string("none") : describe_json(*c));
  }
  long long sum = 0;
  for (const long long n : counts) {
    if (n < 0) return fmt::format("RLE counts: a negative run length {}", n);
    if (n > h * w - sum) {
      sum = h * w + 1;  // more than the image: the exact excess is not the point
      break;
    }
    sum += n;
  }
  if (sum > h * w)
    return fmt::format("RLE counts cover more than the {}x{} image's {} pixels (height x width)", w, h, h * w);
  if (sum != h * w)
    return fmt::format("RLE counts cover {} pixels; expected the {}x{} image's {} (height x width)", sum, w, h, h * w);
  const RleMask mask = decode_rle_mask(counts, h, w);
  if (mask.area == 0) return "RLE mask with no pixel set; expected the object's pixels";
  bool too_many = false;
  std::vector<long long> piece_pixels;
  const auto contours = mask_component_contours(mask.pixels, kMaxOutlinePoints, &too_many, &piece_pixels);
  if (too_many)
    return fmt::format(
        "RLE mask's outline has more than {} corners (its {} pixels in {}+ pieces); expected an "
        "object's mask",
        kMaxOutlinePoints, mask.area, contours.size());
  if (contours.empty() || piece_pixels.size() != contours.size())
    return "RLE mask: no outline could be traced from its pixels";
  long long left_out = 0;
  int pieces_left_out = 0;
  const std::vector<Eigen::Vector2i>& ring = enclosing_piece(contours, piece_pixels, &left_out, &pieces_left_out);
  out->rle = true;
  out->mask_pixels = mask.area;
  out->pixels_left_out = left_out;
  out->pieces_left_out = pieces_left_out;
  std::vector<double> points;
  for (const Eigen::Vector2i& p : ring) {
    points.push_back((p.x() + mask.x) / width);
    points.push_back((p.y() + mask.y) / height);
  }
  out->polygons.push_back(std::move(points));
  return {};
}

}  // namespace

bool decode_rle_counts(const std::string& s, std::vector<long long>* counts) {
  // pycocotools' rleFrString: 5 bits a character (offset 48), bit 0x20 says "more", a sign bit in the last
  // character; from the third count on, each is stored as the difference from the one two before.
  // At most 9 characters a count (45 bits): far beyond any picture's pixels, and no shift or sum overflows.
  counts->clear();
  size_t p = 0;
  while (p < s.size()) {
    uint64_t bits = 0;
    int k = 0;
    bool more = true;
    while (more) {
      if (p >= s.size() || k >= 9) return false;
      const int ch = static_cast<unsigned char>(s[p]) - 48;
      if (ch < 0 || ch > 63) return false;
      bits |= static_cast<uint64_t>(ch & 0x1f) << (5 * k);
      more = (ch & 0x20) != 0;
      ++p;
      ++k;
      if (!more && (ch & 0x10)) bits |= ~uint64_t{0} << (5 * k);  // negative: the sign extended
    }
    long long x = static_cast<long long>(bits);
    if (counts->size() > 2) x += (*counts)[counts->size() - 2];
    counts->push_back(x);
  }
  return true;
}

RleMask decode_rle_mask(const std::vector<long long>& counts, long long height, long long width) {
  // The bounds of the pixels set, then the pixels in them. Runs alternate 0s and 1s, the first of 0s; pixel k
  // is at row k % height of column k / height.
  RleMask m;
  long long x0 = width, x1 = -1, y0 = height, y1 = -1, at = 0;
  for (size_t k = 0; k < counts.size(); at += counts[k], ++k) {
    if (k % 2 == 0 || counts[k] == 0) continue;
    const long long first = at, last = at + counts[k] - 1;
    x0 = std::min(x0, first / height), x1 = std::max(x1, last / height);
    if (first / height == last / height) {
      y0 = std::min(y0, first % height), y1 = std::max(y1, last % height);
    } else {  // the run goes from the bottom of one column to the top of the next: every row is in its bounds
      y0 = 0, y1 = height - 1;
    }
    m.area += counts[k];
  }
  if (m.area == 0) return m;
  m.x = static_cast<int>(x0), m.y = static_cast<int>(y0);
  m.pixels.width = static_cast<int>(x1 - x0 + 1), m.pixels.height = static_cast<int>(y1 - y0 + 1);
  m.pixels.on.assign(static_cast<size_t>(m.pixels.width) * m.pixels.height, 0);
  at = 0;
  for (size_t k = 0; k < counts.size(); at += counts[k], ++k) {
    if (k % 2 == 0) continue;
    for (long long p = at; p < at + counts[k]; ++p) {
      const long long col = p / height - x0, row = p % height - y0;
      m.pixels.on[static_cast<size_t>(row) * m.pixels.width + col] = 1;
    }
  }
  return m;
}

std::vector<double> merge_polygon_parts(const std::vector<std::vector<double>>& parts) {
  if (parts.size() <= 1) return parts.empty() ? std::vector<double>() : parts.front();
  const size_t n = parts.size();
  auto count = [&](size_t i) { return parts[i].size() / 2; };
  // out[i]: the point of part i joined to part i + 1; in[i]: the point of part i joined to part i - 1.
  std::vector<size_t> out(n, 0), in(n, 0);
  for (size_t i = 0; i + 1 < n; ++i) {
    double best = INFINITY;
    for (size_t a = 0; a < count(i); ++a)
      for (size_t b = 0; b < count(i + 1); ++b) {
        const double dx = parts[i][2 * a] - parts[i + 1][2 * b], dy = parts[i][2 * a + 1] - parts[i + 1][2 * b + 1];
        if (dx * dx + dy * dy < best) {
          best = dx * dx + dy * dy;
          out[i] = a;
          in[i + 1] = b;
        }
      }
  }
  std::vector<double> merged;
  auto walk = [&](size_t i, size_t from, size_t steps) {  // steps + 1 points of part i, from `from` on
    for (size_t k = 0; k <= steps; ++k) {
      const size_t at = (from + k) % count(i);
      const double x = parts[i][2 * at], y = parts[i][2 * at + 1];
      if (merged.size() >= 2 && merged[merged.size() - 2] == x && merged.back() == y) continue;
      merged.push_back(x);
      merged.push_back(y);
    }
  };
  walk(0, out[0], count(0));            // the first part whole, back to its bridge
  for (size_t i = 1; i + 1 < n; ++i) {  // there: in -> out, the whole part when it meets both at one point
    const size_t there = (out[i] + count(i) - in[i]) % count(i);
    walk(i, in[i], there == 0 ? count(i) : there);
  }
  walk(n - 1, in[n - 1], count(n - 1));                                                      // the last one whole
  for (size_t i = n - 1; i-- > 1;) walk(i, out[i], (in[i] + count(i) - out[i]) % count(i));  // back: out -> in
  if (merged.size() >= 4 && merged[0] == merged[merged.size() - 2] && merged[1] == merged.back())
    merged.resize(merged.size() - 2);
  return merged;
}

std::string read_coco_segmentation(const nlohmann::json& seg, double width, double height, CocoSegmentation* out) {
  *out = {};
  if (seg.is_null() || (seg.is_array() && seg.empty())) return {};
  if (seg.is_array()) return read_polygons(seg, width, height, out);
  if (seg.is_object()) return read_rle(seg, width, height, out);
  return "expected segmentation polygons [[x1, y1, ...]] or an RLE {counts, size}, found " + describe_json(seg);
}

}  // namespace ipd
