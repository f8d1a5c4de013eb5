// Segmentation labels come in as they are: a YOLO-seg dataset and run import with their outlines (the segment
// task's numbers equal the hand-built study's), COCO polygons become YOLO-seg lines, and a bad outline is refused
// by its file and line (or entry) with nothing written.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/util/atomic_file.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

// Seven hexagonal rocks (a ring of six and one in the middle, of different sizes), moved by `dx`; a prediction
// line adds a confidence.
std::string hexagons(double dx, bool conf) {
  std::string out;
  const double cx[] = {0.2, 0.5, 0.8, 0.2, 0.5, 0.8, 0.5}, cy[] = {0.2, 0.15, 0.25, 0.75, 0.8, 0.7, 0.5};
  for (int k = 0; k < 7; ++k) {
    const double r = 0.03 + 0.008 * k;
    out += "0";
    for (int j = 0; j < 6; ++j)
      out += fmt::format(" {:.6f} {:.6f}", cx[k] + dx + r * std::cos(j * M_PI / 3), cy[k] + r * std::sin(j * M_PI / 3));
    out += conf ? fmt::format(" {:.4f}\n", 0.5 + 0.05 * k) : "\n";
  }
  return out;
}

std::string cells(const std::string& study) {
  const auto r = test::run_ipd("table " + study + " --task segment --format json --bootstrap 200");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out, nullptr, false);
  if (!j.is_object() || !j.contains("cells") || j["cells"].empty()) return "no table: " + r.err;
  EXPECT_TRUE(j["cells"][0]["ipd"].is_number()) << j["cells"][0].dump();
  EXPECT_GT(j["cells"][0]["pairs"].get<int>(), 10) << j["cells"][0].dump();
  return j["cells"].dump();
}

TEST(YoloSegImport, AYoloSegDatasetAndRunGiveTheHandBuiltStudysSegmentCells) {
  test::TempDir t;
  const std::vector<std::string> stems = {"s1", "s2", "s3"}, domains = {"real", "synth"};
  for (size_t d = 0; d < domains.size(); ++d)
    for (size_t k = 0; k < stems.size(); ++k) {
      const double shift = 0.01 * static_cast<double>(k) + 0.004 * static_cast<double>(d);
      const std::string gt = hexagons(shift, false), found = hexagons(shift + 0.006, true);
      test::write_text(t / ("flat/" + domains[d] + "/labels/" + stems[k] + ".txt"), gt);
      test::write_text(t / ("flat/" + domains[d] + "/predictions/seg/" + stems[k] + ".txt"), found);
      test::write_text(t / ("ds-" + domains[d] + "/labels/" + (k < 2 ? "train/" : "val/") + stems[k] + ".txt"), gt);
      test::write_text(t / ("runs/segment/predict-" + domains[d] + "/labels/" + stems[k] + ".txt"), found);
    }
  const std::string yaml = "models: {seg: {trained_on: real}}\ntask: segment\n";
  test::write_text(t / "flat/study.yaml", yaml);
  test::write_text(t / "flat/real/labels/classes.txt", "rock\n");
  test::write_text(t / "flat/synth/labels/classes.txt", "rock\n");
  for (const std::string& d : domains) {
    fs::create_directories(t / ("ds-" + d + "/images/train"));
    fs::create_directories(t / ("ds-" + d + "/images/val"));
    test::write_text(t / ("ds-" + d + "/data.yaml"), "train: images/train\nval: images/val\nnames: [rock]\n");
    auto r = test::run_ipd("import yolo " + t / ("ds-" + d + "/data.yaml") + " --out " + t / ("study/" + d));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = test::run_ipd("import predictions " + t / ("runs/segment/predict-" + d) + " --out " + t / ("study/" + d) +
                      " --model seg");
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  test::write_text(t / "study/study.yaml", yaml);
  EXPECT_EQ(read_file(t / "study/synth/labels/s3.txt"), read_file(t / "flat/synth/labels/s3.txt"));
  EXPECT_EQ(cells(t / "study"), cells(t / "flat"));
}

TEST(YoloSegImport, AnOutlineWithAnOddNumberOfCoordinatesIsRefusedWithItsLine) {
  test::TempDir t;
  test::write_text(t / "ls/classes.txt", "rock\n");
  test::write_text(t / "ls/labels/s1.txt", "0 0.1 0.1 0.3 0.1 0.2 0.3\n0 0.5 0.5 0.7 0.5 0.6 0.7 0.5\n");
  const auto r = test::run_ipd("import yolo " + t / "ls" + " --out " + t / "study/real");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, t / "ls/labels/s1.txt" +
                       ":2: expected an outline (class x1 y1 ... xn yn), found 8 columns: an odd number of "
                       "coordinates\nerror: 1 problem in the source's label files; nothing written (--skip-bad-lines "
                       "writes malformed lines as comments)\n");
  EXPECT_FALSE(fs::exists(t / "study"));
}

TEST(YoloSegImport, CocoPolygonsAndMasksBecomeYoloSegLines) {
  test::TempDir t;
  test::write_text(t / "gt.json",
                   "{\"images\": [{\"id\": 1, \"file_name\": \"s1.png\", \"width\": 100, \"height\": 50}],"
                   " \"categories\": [{\"id\": 0, \"name\": \"rock\"}],"
                   " \"annotations\": ["
                   "{\"image_id\": 1, \"category_id\": 0, \"bbox\": [10, 10, 20, 20],"
                   " \"segmentation\": [[10, 10, 30, 10, 20, 30]]},"
                   "{\"image_id\": 1, \"category_id\": 0, \"bbox\": [0, 0, 30, 10],"
                   " \"segmentation\": [[0, 0, 10, 0, 10, 10, 0, 10], [20, 0, 30, 0, 30, 10, 20, 10]]},"
                   "{\"image_id\": 1, \"category_id\": 0, \"bbox\": [50, 0, 50, 50],"
                   " \"segmentation\": {\"counts\": [2500, 2500], \"size\": [50, 100]}}]}");
  test::write_text(t / "res.json",
                   "[{\"image_id\": 1, \"category_id\": 0, \"bbox\": [10, 10, 20, 20], \"score\": 0.75,"
                   " \"segmentation\": [[10, 10, 30, 10, 20, 30]]}]");
  const auto r = test::run_ipd("import coco " + t / "gt.json" + " --images " + t.path() + " --out " + t / "study/real" +
                               " --results " + t / "res.json" + " --model m");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err,
            "note: 3 polygon segmentations and 1 run-length masks written as YOLO-seg outlines (a mask traced along "
            "its pixels' edges at the image's resolution, holes filled)\n");
  // The two squares of the second object joined at their nearest corners, (0.1, 0) and (0.2, 0).
  EXPECT_EQ(read_file(t / "study/real/labels/s1.txt"),
            "0 0.1 0.2 0.3 0.2 0.2 0.6\n"
            "0 0.1 0 0.1 0.2 0 0.2 0 0 0.1 0 0.2 0 0.3 0 0.3 0.2 0.2 0.2 0.2 0\n"
            "0 0.5 0 1 0 1 1 0.5 1\n");
  EXPECT_EQ(read_file(t / "study/real/predictions/m/s1.txt"), "0 0.1 0.2 0.3 0.2 0.2 0.6 0.75\n");
}

}  // namespace
}  // namespace ipd
