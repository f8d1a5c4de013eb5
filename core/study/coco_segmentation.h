// A COCO annotation's "segmentation", checked against its image: polygons (`[[x1, y1, x2, y2, ...], ...]`, in
// pixels) or a run-length mask (RLE: `{"counts": [...] or "...", "size": [height, width]}`, pycocotools'
// encodings). A malformed one (a polygon with an odd number of coordinates or fewer than three points, RLE
// counts that do not cover the image) is an error of its entry, never silently dropped. A run-length mask is
// decoded at the image's resolution (its `size`) and traced into contours along its pixels' edges
// (mask_outline.h): the outline covers exactly the mask's pixels, with holes filled, when the mask is one piece;
// of several pieces, the one whose contour encloses the most is kept and the others are counted as left out.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "core/geometry/mask_outline.h"

namespace ipd {

struct CocoSegmentation {
  // Each part's x1 y1 x2 y2 ..., normalised by the image's size: the polygons as given, or a run-length mask's
  // one contour: the outer contour (clockwise, y down) of its 4-connected piece that encloses the most, holes
  // filled.
  std::vector<std::vector<double>> polygons;
  bool rle = false;               // the polygons are a run-length mask's contour
  long long mask_pixels = 0;      // a run-length mask's pixels set
  long long pixels_left_out = 0;  // of them, in pieces outside the contour (left out of the outline)
  int pieces_left_out = 0;
};

// The largest mask a run-length segmentation may have, in pixels (height x width): the pictures' limit.
constexpr long long kMaxRleMaskPixels = 50'000'000;

// A decoded run-length mask, cropped to the bounds of the pixels it sets (their top-left pixel at x, y).
struct RleMask {
  PixelMask pixels;
  int x = 0, y = 0;
  long long area = 0;  // pixels set
};

// Decodes run lengths (COCO's order: column by column, top to bottom, the first run of 0s) of a mask of
// `height` x `width` pixels; the counts must be non-negative and sum to height x width (read_coco_segmentation
// checks both first).
RleMask decode_rle_mask(const std::vector<long long>& counts, long long height, long long width);

// Reads `segmentation` of an image `width` x `height` pixels into `out`; "" when it is fine (or empty), else
// what is wrong, in one sentence naming what was expected.
std::string read_coco_segmentation(const nlohmann::json& segmentation, double width, double height,
                                   CocoSegmentation* out);

// One contour for a segmentation of several polygons (an object cut in two by an occluder), as a YOLO-seg line
// holds one: each part joined to the next at their nearest points by a bridge walked there and back, which
// encloses nothing, so the filled region is the parts' (Ultralytics' merge of COCO's multi-part masks). Points are
// x, y pairs; one part is returned as it is.
std::vector<double> merge_polygon_parts(const std::vector<std::vector<double>>& parts);

// The counts of a compressed RLE string (pycocotools' rleFrString); false when it is not one.
bool decode_rle_counts(const std::string& text, std::vector<long long>* counts);

}  // namespace ipd
