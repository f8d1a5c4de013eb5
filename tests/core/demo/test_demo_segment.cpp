// `ipd demo --task segment`: the pictured demo with an outline on every instance, GT the drawn rock's ellipse and
// predictions the classical detector's contours, so the studio and every figure show masks with no data.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/demo/demo_study.h"
#include "core/ipd/ipd.h"
#include "core/report/provenance.h"
#include "core/study/study.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

// An outlined instance is its outline's bounds, as a YOLO-seg line reads back.
void expect_outlined(const Box& b, const std::string& where, size_t max_points) {
  ASSERT_TRUE(b.outline) << where;
  const Outline& o = *b.outline;
  EXPECT_GE(o.points.size(), 3u) << where;
  EXPECT_LE(o.points.size(), max_points) << where;
  EXPECT_GT(o.area, 0) << where;
  EXPECT_NEAR(b.cx, 0.5 * (o.x0 + o.x1), 1e-5) << where;  // six decimals in the file
  EXPECT_NEAR(b.w, o.x1 - o.x0, 1e-5) << where;
}

TEST(DemoSegment, EveryInstanceIsOutlinedAndTheIpdIsAboutMasks) {
  const test::TempDir d;
  DemoStudyOptions o;
  o.scenes = 2;
  o.segment = true;
  write_demo_study(d / "demo", o);
  const Study study = open_study(d / "demo");
  EXPECT_EQ(study.config.task, Task::kSegment);
  const StudyLabels labels = load_labels(study);
  long gt = 0, predictions = 0, ellipses = 0;
  for (const auto& [domain, stems] : labels.gt)
    for (const auto& [stem, file] : stems)
      for (size_t k = 0; k < file.boxes.size(); ++k, ++gt) {
        expect_outlined(file.boxes[k], domain + "/" + stem + " GT " + std::to_string(k), 24);
        // A rock inside the frame keeps all 24 points of its ellipse, and a polygon of 24 points on an ellipse
        // of semi-axes a, b encloses 12 sin(pi/12) a b (0.989 of pi a b); the box's bounds hold that ellipse.
        const Outline& ol = *file.boxes[k].outline;
        if (ol.points.size() == 24) {
          ++ellipses;
          EXPECT_LE(ol.area, M_PI / 4 * (ol.x1 - ol.x0) * (ol.y1 - ol.y0) + 1e-9);
          EXPECT_GT(ol.area, 0.5 * (ol.x1 - ol.x0) * (ol.y1 - ol.y0));  // a rotated ellipse, not a sliver
        }
      }
  for (const auto& [domain, models] : labels.predictions)
    for (const auto& [model, stems] : models)
      for (const auto& [stem, file] : stems)
        for (size_t k = 0; k < file.boxes.size(); ++k, ++predictions)
          expect_outlined(file.boxes[k], domain + "/" + model + "/" + stem + " prediction " + std::to_string(k),
                          kMaxOutlinePoints);
  EXPECT_GE(gt, 3 * 2 * 9);  // three domains, two scenes, at least nine rocks (a few hide in the wall's shadow)
  EXPECT_GT(ellipses, gt / 2);
  EXPECT_GT(predictions, gt);  // three detectors on every domain
  const CrossTable table = compute_cross_table(labels, {});
  const TableCell* cell = table.cell("det-real", "real", "principled");
  ASSERT_NE(cell, nullptr);
  EXPECT_GT(cell->ipd, 0);
  EXPECT_LT(cell->ipd, 0.5);
  EXPECT_EQ(provenance_note(table_provenance(table, labels)).rfind("Mask IoU (task segment). ", 0), 0u);
}

TEST(DemoSegment, TheSegmentationDemoNeedsItsPictures) {
  DemoStudyOptions o;
  o.segment = true;
  o.labels_only = true;
  EXPECT_EQ(o.validate(),
            "the segmentation demo needs its pictures (its predictions are the detector's contours): not with "
            "labels_only");
  const test::TempDir d;
  const auto r = test::run_ipd("demo " + d / "demo" + " --task segment --labels-only");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err,
            "error: --task segment writes the pictured demo (its predictions are the detector's contours): not with "
            "--labels-only or --variants\n");
}

}  // namespace
}  // namespace ipd
