// A COCO annotation's "segmentation", checked against its image: polygons (`[[x1, y1, x2, y2, ...], ...]`, in
// pixels) or a run-length mask (RLE: `{"counts": [...] or "...", "size": [height, width]}`, pycocotools'
// encodings). A malformed one (a polygon with an odd number of coordinates or fewer than three points, RLE
// counts that do not cover the image) is an error of its entry, never silently dropped.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

namespace ipd {

struct CocoSegmentation {
  std::vector<std::vector<double>> polygons;  // each part's x1 y1 x2 y2 ..., normalised by the image's size
  bool rle = false;                           // a run-length mask (kept as the annotation's box)
};

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
