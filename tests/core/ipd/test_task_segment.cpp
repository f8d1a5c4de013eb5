// The segment task: a performance value is a mask IoU, through the same IPD as boxes, and a number never mixes
// box and mask IoU unasked.
#include <gtest/gtest.h>

#include "core/ipd/ipd.h"
#include "core/ipd/study_cache.h"
#include "core/registration/registration_cache.h"
#include "core/report/provenance.h"
#include "core/stats/detection_metrics.h"
#include "core/study/study.h"
#include "core/util/errors.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

// Three rocks, the same outlines in both domains: a square R1 ([0.1, 0.3]^2), an L-shape R2 (the square
// [0.5, 0.7]^2 without its top-right quarter, area 0.03) and a triangle R3 (area 0.02). real's predictions: R1's
// square shifted by half its side (mask IoU 1/3), R2's and R3's bounding squares (mask IoU 0.03 / 0.04 = 0.75 and
// 0.02 / 0.04 = 0.5; box IoU 1 both). synth's predictions are the outlines themselves (IoU 1).
// Mask IPD: (2/3 + 1/4 + 1/2) / 3 = 17/36. Box IPD: (2/3 + 0 + 0) / 3 = 2/9.
const char* const kGt =
    "0 0.1 0.1 0.3 0.1 0.3 0.3 0.1 0.3\n"
    "0 0.5 0.5 0.7 0.5 0.7 0.6 0.6 0.6 0.6 0.7 0.5 0.7\n"
    "0 0.1 0.6 0.3 0.6 0.1 0.8\n";

void write_segment_study(const test::TempDir& d, const std::string& yaml = "task: segment\n") {
  test::write_text(d / "real/labels/s1.txt", kGt);
  test::write_text(d / "synth/labels/s1.txt", kGt);
  test::write_text(d / "real/predictions/det/s1.txt",
                   "0 0.2 0.1 0.4 0.1 0.4 0.3 0.2 0.3 0.9\n"
                   "0 0.5 0.5 0.7 0.5 0.7 0.7 0.5 0.7 0.8\n"
                   "0 0.1 0.6 0.3 0.6 0.3 0.8 0.1 0.8 0.7\n");
  test::write_text(d / "synth/predictions/det/s1.txt",
                   "0 0.1 0.1 0.3 0.1 0.3 0.3 0.1 0.3 0.9\n"
                   "0 0.5 0.5 0.7 0.5 0.7 0.6 0.6 0.6 0.6 0.7 0.5 0.7 0.9\n"
                   "0 0.1 0.6 0.3 0.6 0.1 0.8 0.9\n");
  test::write_text(d / "study.yaml", "domains: [real, synth]\nmodels: {det: {trained_on: real}}\n" + yaml);
}

double ipd_of(const StudyLabels& labels) {
  require_choices(labels);
  return compute_cross_table(labels, {}).cell("det", "real", "synth")->ipd;
}

TEST(TaskSegment, TheIpdIsTheMeanDifferenceOfMaskIous) {
  test::TempDir d;
  write_segment_study(d);
  const StudyLabels labels = load_labels(open_study(d.path()));
  EXPECT_NEAR(ipd_of(labels), 17.0 / 36.0, 1e-12);
  EXPECT_EQ(labels.task_note, "");
  EXPECT_EQ(provenance_note(table_provenance(compute_cross_table(labels, {}), labels))
                .rfind("Mask IoU (task "
                       "segment). Label files ",
                       0),
            0u);
}

TEST(TaskSegment, OutlinesUnderTheDetectTaskAreScoredByTheirBoundsAndSaidSo) {
  test::TempDir d;
  write_segment_study(d, "");
  const StudyLabels labels = load_labels(open_study(d.path()));
  EXPECT_NEAR(ipd_of(labels), 2.0 / 9.0, 1e-12);
  EXPECT_EQ(labels.task_note,
            "12 of the instances have outlines (masks); every number here is about their boxes (the outlines' "
            "bounds) as task detect; --task segment (or task: segment in study.yaml) scores them by mask IoU");
}

TEST(TaskSegment, AWarmLoadFromTheParsedStudyCacheScoresTheSameMasks) {
  test::TempDir d;
  write_segment_study(d);
  for (int run = 0; run < 2; ++run) {
    const Study study = open_study(d.path());
    StudyCache cache(parsed_study_cache_path(d.path()), study.root);
    const StudyLabels labels = cache.load_labels(study);
    EXPECT_EQ(cache.stats().files_reused, run == 0 ? 0 : 4);
    EXPECT_NEAR(ipd_of(labels), 17.0 / 36.0, 1e-12);
    EXPECT_NEAR(labels.gt_of("real", "s1").boxes[1].outline->area, 0.03, 1e-12);
    RegistrationCache registration("");
    cache.save(labels, registration);
  }
}

TEST(TaskSegment, ABoxWithoutAnOutlineIsRefusedNamingWhereItIs) {
  test::TempDir d;
  write_segment_study(d);
  test::write_text(d / "synth/predictions/det/s1.txt", "0 0.2 0.2 0.2 0.2 0.9\n0 0.1 0.6 0.3 0.6 0.1 0.8 0.9\n");
  const StudyLabels labels = load_labels(open_study(d.path()));
  try {
    require_choices(labels);
    FAIL() << "a box scored as its rectangle under task segment";
  } catch (const StudyError& e) {
    EXPECT_EQ(std::string(e.what()),
              d.path() + ": task segment scores each instance by mask IoU, but 1 of 5 predictions (first: " +
                  (d / "synth/predictions/det/s1.txt") +
                  ":1) are boxes without an outline (a YOLO-seg line `class x1 y1 ... xn yn`); give them outlines, "
                  "or use --task detect for box IoU");
  }
}

TEST(TaskSegment, StudyYamlNamesTheTaskAsDetectOrSegment) {
  test::TempDir d;
  write_segment_study(d, "task: masks\n");
  try {
    open_study(d.path());
    FAIL();
  } catch (const StudyError& e) {
    EXPECT_EQ(std::string(e.what()),
              (d / "study.yaml") + ":3: task must be detect (box IoU) or segment (mask IoU), found 'masks'");
  }
}

// pycocotools' iouType 'segm' through the same matching: the square [0, 0.4]^2 with a notch 0.2 wide and 0.224
// deep (area 0.1152) against a detection of its bounding square has mask IoU 0.72, box IoU 1. Mask AP50 is 1,
// and AP at 0.50:0.95 counts the match at 0.50 ... 0.70 only: 5 of 10 thresholds, 0.5. Box AP50:95 is 1.
TEST(TaskSegment, MaskApMatchesDetectionsByMaskIou) {
  const LabelFile gt = parse_labels("0 0 0 0.4 0 0.4 0.4 0.3 0.4 0.3 0.176 0.1 0.176 0.1 0.4 0 0.4\n", "a.txt",
                                    {LabelKind::kGroundTruth});
  const LabelFile det = parse_labels("0 0 0 0.4 0 0.4 0.4 0 0.4 0.9\n", "p.txt", {LabelKind::kPrediction});
  ASSERT_TRUE(gt.errors.empty() && det.errors.empty());
  ASSERT_NEAR(mask_iou(*gt.boxes[0].outline, *det.boxes[0].outline), 0.72, 1e-12);
  const std::vector<DetectionImage> masks = {{gt.boxes, det.boxes, Task::kSegment}};
  const std::vector<DetectionImage> boxes = {{gt.boxes, det.boxes, Task::kDetect}};
  EXPECT_NEAR(average_precision(masks, 0.5), 1.0, 1e-12);
  EXPECT_NEAR(average_precision(masks, 0.75), 0.0, 1e-12);
  EXPECT_NEAR(average_precision_50_95(masks), 0.5, 1e-12);
  EXPECT_NEAR(average_precision_50_95(boxes), 1.0, 1e-12);
}

}  // namespace
}  // namespace ipd
