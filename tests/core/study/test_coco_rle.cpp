// COCO run-length masks are read as masks, not as their boxes: decoded column by column at the image's
// resolution and traced along their pixels' edges into one outline that covers exactly the mask's pixels (holes
// filled; of several pieces the one enclosing the most), so the mask IoU of an RLE and a polygon of the same
// pixels is exact.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "core/geometry/mask_outline.h"
#include "core/geometry/outline.h"
#include "core/study/coco_segmentation.h"
#include "core/util/atomic_file.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

std::string rows(const RleMask& m) {
  std::string s;
  for (int y = 0; y < m.pixels.height; ++y) {
    for (int x = 0; x < m.pixels.width; ++x) s += m.pixels.on[size_t(y) * m.pixels.width + x] ? '#' : '.';
    s += '\n';
  }
  return s;
}

Outline outline_of_coco_rle(const CocoSegmentation& s) {
  const std::vector<double> merged = merge_polygon_parts(s.polygons);
  std::vector<Eigen::Vector2d> points;
  for (size_t k = 0; k + 1 < merged.size(); k += 2) points.emplace_back(merged[k], merged[k + 1]);
  Outline o;
  EXPECT_EQ(make_outline(points, &o), "");
  return o;
}

CocoSegmentation read(const std::string& json, double width, double height) {
  CocoSegmentation s;
  EXPECT_EQ(read_coco_segmentation(nlohmann::json::parse(json), width, height, &s), "");
  return s;
}

// [3, 5, 2, 6] over 4 x 4: 3 pixels off (column 0, rows 0-2), 5 on (column 0 row 3, column 1), 2 off (column 2,
// rows 0-1), 6 on (column 2 rows 2-3, column 3): 11 pixels.
TEST(CocoRle, RunsFillColumnsTopToBottom) {
  const RleMask m = decode_rle_mask({3, 5, 2, 6}, 4, 4);
  EXPECT_EQ(m.area, 11);
  EXPECT_EQ(m.x, 0);
  EXPECT_EQ(m.y, 0);
  EXPECT_EQ(rows(m), ".#.#\n.#.#\n.###\n####\n");
  // The outline along the pixels' edges, clockwise (y down) from the first pixel's top-left corner.
  bool too_many = false;
  const auto contours = mask_component_contours(m.pixels, 100, &too_many);
  EXPECT_FALSE(too_many);
  ASSERT_EQ(contours.size(), 1u);
  const std::vector<Eigen::Vector2i> expected = {{1, 0}, {2, 0}, {2, 2}, {3, 2}, {3, 0},
                                                 {4, 0}, {4, 4}, {0, 4}, {0, 3}, {1, 3}};
  EXPECT_EQ(contours[0], expected);
}

// Cropped to the pixels set: a 4 x 4 square at x 2-5, y 3-6 of a 10 x 10 image.
TEST(CocoRle, AMaskIsCroppedToItsPixels) {
  const RleMask m = decode_rle_mask({23, 4, 6, 4, 6, 4, 6, 4, 43}, 10, 10);
  EXPECT_EQ(m.area, 16);
  EXPECT_EQ(m.x, 2);
  EXPECT_EQ(m.y, 3);
  EXPECT_EQ(rows(m), "####\n####\n####\n####\n");
  // pycocotools' string of the same counts (rleToString), hand-encoded.
  std::vector<long long> counts;
  ASSERT_TRUE(decode_rle_counts("g04600000U1", &counts));
  EXPECT_EQ(counts, (std::vector<long long>{23, 4, 6, 4, 6, 4, 6, 4, 43}));
  // A run from the foot of one column to the top of the next: every row is in the bounds.
  const RleMask wrap = decode_rle_mask({3, 2, 11}, 4, 4);
  EXPECT_EQ(wrap.area, 2);
  EXPECT_EQ(rows(wrap), ".#\n..\n..\n#.\n");
}

TEST(CocoRle, AnRleSquareAndAPolygonSquareOfTheSamePixelsHaveMaskIouOne) {
  const std::string square = R"({"counts": [23, 4, 6, 4, 6, 4, 6, 4, 43], "size": [10, 10]})";
  const CocoSegmentation rle = read(square, 10, 10);
  EXPECT_TRUE(rle.rle);
  EXPECT_EQ(rle.mask_pixels, 16);
  const Outline a = outline_of_coco_rle(rle);
  EXPECT_NEAR(a.area, 0.16, 1e-12);
  const Outline same = outline_of_coco_rle(read("[[2, 3, 6, 3, 6, 7, 2, 7]]", 10, 10));
  EXPECT_NEAR(mask_iou(a, same), 1.0, 1e-9);
  // Offset by half the square: 8 pixels in common of 24 covered, 1/3.
  const Outline half = outline_of_coco_rle(read("[[4, 3, 8, 3, 8, 7, 4, 7]]", 10, 10));
  EXPECT_NEAR(mask_iou(a, half), 1.0 / 3.0, 1e-9);
  // The compressed string is the same mask.
  const Outline compressed = outline_of_coco_rle(read(R"({"counts": "g04600000U1", "size": [10, 10]})", 10, 10));
  EXPECT_NEAR(mask_iou(a, compressed), 1.0, 1e-9);
}

// A 3 x 3 ring (its centre pixel off): the outline fills the hole, 9 pixels for the mask's 8, so against the
// raster its IoU is 8/9.
TEST(CocoRle, HolesAreFilled) {
  // 5 x 5, columns 1-3 rows 1-3 on but (2, 2): column-major runs.
  const CocoSegmentation ring = read(R"({"counts": [6, 3, 2, 1, 1, 1, 2, 3, 6], "size": [5, 5]})", 5, 5);
  EXPECT_EQ(ring.mask_pixels, 8);
  EXPECT_EQ(ring.pixels_left_out, 0);
  ASSERT_EQ(ring.polygons.size(), 1u);
  EXPECT_NEAR(outline_of_coco_rle(ring).area * 25, 9.0, 1e-9);
}

// Of several pieces the outline keeps the one whose contour encloses the most; a piece in its hole is covered,
// the others are left out and counted.
TEST(CocoRle, OfSeveralPiecesTheOneEnclosingTheMostIsKept) {
  // Pixel (0, 0) and a 2 x 2 block at x 2-3, y 2-3 of a 4 x 4 image: the block.
  const CocoSegmentation two = read(R"({"counts": [0, 1, 9, 2, 2, 2], "size": [4, 4]})", 4, 4);
  EXPECT_EQ(two.mask_pixels, 5);
  ASSERT_EQ(two.polygons.size(), 1u);
  EXPECT_EQ(two.polygons[0], (std::vector<double>{0.5, 0.5, 1, 0.5, 1, 1, 0.5, 1}));
  EXPECT_EQ(two.pieces_left_out, 1);
  EXPECT_EQ(two.pixels_left_out, 1);
  // Pixels touching only at a corner are two pieces (4-connectivity); of two alike the first is kept.
  const CocoSegmentation diagonal = read(R"({"counts": [0, 1, 4, 1, 10], "size": [4, 4]})", 4, 4);
  ASSERT_EQ(diagonal.polygons.size(), 1u);
  EXPECT_EQ(diagonal.polygons[0], (std::vector<double>{0, 0, 0.25, 0, 0.25, 0.25, 0, 0.25}));
  EXPECT_EQ(diagonal.pixels_left_out, 1);
  // A 5 x 5 ring (x, y 1-5 of 7 x 7, 16 pixels) around a pixel of its own at (3, 3): the ring's contour covers
  // both, 25 pixels, nothing left out.
  const CocoSegmentation nested =
      read(R"({"counts": [8, 5, 2, 1, 3, 1, 2, 1, 1, 1, 1, 1, 2, 1, 3, 1, 2, 5, 8], "size": [7, 7]})", 7, 7);
  EXPECT_EQ(nested.mask_pixels, 17);
  EXPECT_EQ(nested.pieces_left_out, 0);
  EXPECT_NEAR(outline_of_coco_rle(nested).area * 49, 25.0, 1e-9);
}

TEST(CocoRle, MasksThatCannotBeAnOutlineAreRefused) {
  const auto problem = [](const std::string& json, double w, double h) {
    CocoSegmentation s;
    return read_coco_segmentation(nlohmann::json::parse(json), w, h, &s);
  };
  EXPECT_EQ(problem(R"({"counts": [16], "size": [4, 4]})", 4, 4),
            "RLE mask with no pixel set; expected the object's pixels");
  EXPECT_EQ(problem(R"({"counts": [3, 5, 2, 9], "size": [4, 4]})", 4, 4),
            "RLE counts cover more than the 4x4 image's 16 pixels (height x width)");
  EXPECT_EQ(problem(R"({"counts": [3, 5, 2, 9223372036854775807], "size": [4, 4]})", 4, 4),
            "RLE counts cover more than the 4x4 image's 16 pixels (height x width)");
  EXPECT_EQ(problem(R"({"counts": [1], "size": [10000, 10000]})", 10000, 10000),
            "RLE size [10000, 10000]: a mask of more than 50000000 pixels; expected a picture's (at most 50 "
            "megapixels)");
  // A checkerboard of 200 x 200: 20,000 one-pixel pieces, 80,000 corners.
  std::vector<long long> counts;
  for (int col = 0; col < 200; ++col)
    for (int row = 0; row < 200; ++row) {
      const bool on = (row + col) % 2 == 1;
      if (counts.size() % 2 == static_cast<size_t>(on)) counts.push_back(0);
      ++counts.back();
    }
  EXPECT_EQ(problem(nlohmann::json({{"counts", counts}, {"size", {200, 200}}}).dump(), 200, 200),
            "RLE mask's outline has more than 10000 corners (its 20000 pixels in 2501+ pieces); expected an "
            "object's mask");
}

TEST(CocoRle, WrongCountsAreAnErrorNamingTheFileAndTheAnnotationAndNothingIsWritten) {
  test::TempDir t;
  test::write_text(t / "gt.json",
                   "{\"images\": [{\"id\": 1, \"file_name\": \"s1.png\", \"width\": 4, \"height\": 4}],"
                   " \"categories\": [{\"id\": 0, \"name\": \"rock\"}],"
                   " \"annotations\": [{\"id\": 7, \"image_id\": 1, \"category_id\": 0, \"bbox\": [0, 0, 4, 4],"
                   " \"segmentation\": {\"counts\": [3, 5, 2], \"size\": [4, 4]}}]}");
  const auto r = test::run_ipd("import coco " + t / "gt.json" + " --images " + t.path() + " --out " + t / "study/real");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, t / "gt.json" +
                       ": annotations[0] (id 7): RLE counts cover 10 pixels; expected the 4x4 image's 16 (height x "
                       "width)\nerror: 1 malformed entry; nothing written (--skip-bad-lines skips them)\n");
  EXPECT_FALSE(fs::exists(t / "study"));
}

// Detectron2 / MMDetection results: an RLE per detection, read as its outline, scored by mask IoU.
TEST(CocoRle, PredictionMasksAreImportedAsOutlines) {
  test::TempDir t;
  test::write_text(t / "gt.json",
                   "{\"images\": [{\"id\": 1, \"file_name\": \"s1.png\", \"width\": 10, \"height\": 10}],"
                   " \"categories\": [{\"id\": 0, \"name\": \"rock\"}],"
                   " \"annotations\": [{\"id\": 1, \"image_id\": 1, \"category_id\": 0, \"bbox\": [2, 3, 4, 4],"
                   " \"segmentation\": [[2, 3, 6, 3, 6, 7, 2, 7]]}]}");
  test::write_text(t / "res.json",
                   "[{\"image_id\": 1, \"category_id\": 0, \"bbox\": [2, 3, 4, 4], \"score\": 0.5,"
                   " \"segmentation\": {\"counts\": \"g04600000U1\", \"size\": [10, 10]}}]");
  const auto gt =
      test::run_ipd("import coco " + t / "gt.json" + " --images " + t.path() + " --out " + t / "study/real");
  ASSERT_EQ(gt.exit_code, 0) << gt.err;
  const auto r = test::run_ipd("import predictions " + t / "res.json" + " --gt " + t / "gt.json" + " --out " +
                               t / "study/real --model mrcnn");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_file(t / "study/real/predictions/mrcnn/s1.txt"), "0 0.2 0.3 0.6 0.3 0.6 0.7 0.2 0.7 0.5\n");
}

}  // namespace
}  // namespace ipd
