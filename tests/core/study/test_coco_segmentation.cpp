// COCO segmentations are read and checked, never silently dropped: a polygon needs x, y pairs and three points,
// a run-length mask must cover its image exactly; a bad one is refused by its entry with nothing written.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "core/geometry/outline.h"
#include "core/study/coco_segmentation.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

std::string problem(const std::string& segmentation) {
  CocoSegmentation s;
  return read_coco_segmentation(nlohmann::json::parse(segmentation), 4, 4, &s);
}

TEST(CocoSegmentation, PolygonsAreNormalisedByTheImage) {
  CocoSegmentation s;
  ASSERT_EQ(read_coco_segmentation(nlohmann::json::parse("[[0, 0, 4, 0, 2, 2]]"), 4, 4, &s), "");
  ASSERT_EQ(s.polygons.size(), 1u);
  EXPECT_EQ(s.polygons[0], (std::vector<double>{0, 0, 1, 0, 0.5, 0.5}));
  EXPECT_FALSE(s.rle);
  EXPECT_EQ(problem("[]"), "");  // no segmentation
}

TEST(CocoSegmentation, APolygonWithAnOddNumberOfCoordinatesOrTooFewPointsIsRefused) {
  EXPECT_EQ(problem("[[0, 0, 4, 0, 2]]"),
            "segmentation[0]: a polygon has an odd number of coordinates (5); expected x, y pairs");
  EXPECT_EQ(problem("[[0, 0, 4, 0, 2, 2], [1, 1, 2, 2]]"),
            "segmentation[1]: a polygon of 2 point(s); expected at least 3 (x, y pairs)");
  EXPECT_EQ(problem("[[0, 0, 9, 0, 2, 2]]"), "segmentation[0]: point 2 (9, 0) is outside the 4x4 image");
}

// Two unit squares side by side, 1 apart: one contour through both, the bridge between their nearest corners
// ((1, 0) and (2, 0)) walked there and back; its shoelace area is the two squares', 2.
TEST(CocoSegmentation, PartsOfOneObjectBecomeOneContourJoinedWhereTheyAreNearest) {
  const std::vector<double> a = {0, 0, 1, 0, 1, 1, 0, 1}, b = {2, 0, 3, 0, 3, 1, 2, 1};
  const std::vector<double> merged = merge_polygon_parts({a, b});
  EXPECT_EQ(merged, (std::vector<double>{1, 0, 1, 1, 0, 1, 0, 0, 1, 0, 2, 0, 3, 0, 3, 1, 2, 1, 2, 0}));
  double twice_area = 0;
  for (size_t k = 0; k < merged.size(); k += 2) {
    const size_t next = (k + 2) % merged.size();
    twice_area += merged[k] * merged[next + 1] - merged[next] * merged[k + 1];
  }
  EXPECT_DOUBLE_EQ(twice_area / 2, 2.0);
  EXPECT_EQ(merge_polygon_parts({a}), a);
}

// A middle part whose nearest corner to the part before and to the part after is one corner is walked whole (on
// the way there), not left out: squares A (0,0)-(1,1), B (2,2)-(3,3) and C (1.5,0)-(1.8,0.5) meet B at (2, 2).
TEST(CocoSegmentation, APartJoinedToBothNeighboursAtOneCornerIsKept) {
  const std::vector<double> a = {0, 0, 1, 0, 1, 1, 0, 1}, b = {2, 2, 3, 2, 3, 3, 2, 3},
                            c = {1.5, 0, 1.8, 0, 1.8, 0.5, 1.5, 0.5};
  const std::vector<double> merged = merge_polygon_parts({a, b, c});
  std::vector<Eigen::Vector2d> points;
  for (size_t k = 0; k + 1 < merged.size(); k += 2) points.emplace_back(merged[k] / 4, merged[k + 1] / 4);
  Outline o;
  ASSERT_EQ(make_outline(points, &o), "");
  EXPECT_NEAR(o.area * 16, 1 + 1 + 0.15, 1e-12);
}

// Hand-encoded with pycocotools' rule: from the fourth count on, the difference from the count two before.
TEST(CocoSegmentation, CompressedRunLengthsDecodeAsPycocotoolsWritesThem) {
  std::vector<long long> counts;
  ASSERT_TRUE(decode_rle_counts("3521", &counts));
  EXPECT_EQ(counts, (std::vector<long long>{3, 5, 2, 6}));
  ASSERT_TRUE(decode_rle_counts(":23O", &counts));  // 'O' is -1: 1 = 2 - 1
  EXPECT_EQ(counts, (std::vector<long long>{10, 2, 3, 1}));
  EXPECT_FALSE(decode_rle_counts("3 5", &counts));
}

TEST(CocoSegmentation, RunLengthsThatDoNotCoverTheImageAreRefused) {
  EXPECT_EQ(problem("{\"counts\": [3, 5, 2, 6], \"size\": [4, 4]}"), "");
  EXPECT_EQ(problem("{\"counts\": \"3521\", \"size\": [4, 4]}"), "");
  EXPECT_EQ(problem("{\"counts\": [3, 5, 2], \"size\": [4, 4]}"),
            "RLE counts cover 10 pixels; expected the 4x4 image's 16 (height x width)");
  EXPECT_EQ(problem("{\"counts\": \"352\", \"size\": [4, 4]}"),
            "RLE counts cover 10 pixels; expected the 4x4 image's 16 (height x width)");
  EXPECT_EQ(problem("{\"counts\": [16], \"size\": [4, 5]}"),
            "RLE size [4, 5] is not the image's [height, width] [4, 4]");
}

TEST(CocoSegmentation, ABadSegmentationIsAnErrorOfItsEntryAndNothingIsWritten) {
  test::TempDir t;
  test::write_text(t / "gt.json",
                   "{\"images\": [{\"id\": 1, \"file_name\": \"s1.png\", \"width\": 100, \"height\": 100}],"
                   " \"categories\": [{\"id\": 0, \"name\": \"rock\"}],"
                   " \"annotations\": [{\"image_id\": 1, \"category_id\": 0, \"bbox\": [40, 40, 20, 20],"
                   " \"segmentation\": [[40, 40, 60, 40, 60]]}]}");
  const auto r = test::run_ipd("import coco " + t / "gt.json" + " --images " + t.path() + " --out " + t / "study/real");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, t / "gt.json" +
                       ": annotations[0]: segmentation[0]: a polygon has an odd number of coordinates (5); expected "
                       "x, y pairs\nerror: 1 malformed entry; nothing written (--skip-bad-lines skips them)\n");
  EXPECT_FALSE(fs::exists(t / "study"));
}

}  // namespace
}  // namespace ipd
