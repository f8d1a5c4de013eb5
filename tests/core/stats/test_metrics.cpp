// AP worked out by hand (pycocotools' rules), SSIM / PSNR against scikit-image, and the rock export
// reproducing the table.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <opencv2/core.hpp>

#include "core/demo/demo_study.h"
#include "core/report/rock_export.h"
#include "core/stats/detection_metrics.h"
#include "core/stats/image_metrics.h"
#include "core/stats/study_statistics.h"
#include "tests/support/stats_study.h"
#include "tests/support/test_support.h"

namespace ipd {
namespace {

using test::box;

// Image 1: GT g1 (0.2, 0.2), g2 (0.6, 0.6), 0.1 wide; d1 = g1 (conf 0.9, IoU 1), d2 shifted 0.02 off g2
// (conf 0.6, IoU 0.008 / 0.012 = 2/3). Image 2: GT g3 (0.5, 0.5, 0.2 wide); d3 far away (conf 0.6, a tie with
// d2), d4 = g3 (conf 0.3).
std::vector<DetectionImage> two_images() {
  return {{{box(0.2, 0.2, 0.1, 0.1), box(0.6, 0.6, 0.1, 0.1)},
           {box(0.2, 0.2, 0.1, 0.1, 0.9), box(0.62, 0.6, 0.1, 0.1, 0.6)}},
          {{box(0.5, 0.5, 0.2, 0.2)}, {box(0.1, 0.9, 0.1, 0.1, 0.6), box(0.5, 0.5, 0.2, 0.2, 0.3)}}};
}

TEST(Metrics, AveragePrecisionWorkedByHandWithATie) {
  // IoU 0.5: the stable order is d1 TP, d2 TP (image 1 before image 2 in the tie), d3 FP, d4 TP over 3 GT:
  // recall 1/3, 2/3, 2/3, 1; precision 1, 1, 2/3, 3/4 -> monotone 1, 1, 3/4, 3/4. Recall points 0..0.33
  // (34) and 0.34..0.66 (33) read 1, 0.67..1 (34) read 3/4: AP = (67 + 34 * 0.75) / 101.
  const auto images = two_images();
  EXPECT_NEAR(average_precision(images, 0.5), 92.5 / 101, 1e-12);
  // The other order of the tie (d3 first) would give (34 + 67 * 0.75) / 101 = 0.834: the tie order matters.
  // IoU >= 0.7 (six thresholds): d2 is a FP: TP, FP, FP, TP -> recall 1/3, 1/3, 1/3, 2/3, monotone precision
  // 1, 1/2, 1/2, 1/2: 34 points read 1, 33 read 1/2, 34 read 0 -> AP = 50.5 / 101 = 0.5.
  EXPECT_NEAR(average_precision(images, 0.7), 0.5, 1e-12);
  EXPECT_NEAR(average_precision(images, 0.65), 92.5 / 101, 1e-12);  // 0.65 < 2/3: still a TP
  EXPECT_NEAR(average_precision_50_95(images), (4 * 92.5 / 101 + 6 * 0.5) / 10, 1e-12);
  // At confidence >= 0.5: d1, d2, d3 kept: 2 TP of 3 detections and 3 GT.
  const DetectionMetrics m = detection_metrics(images, 0.5);
  EXPECT_EQ(m.detections, 3);
  EXPECT_EQ(m.gt, 3);
  EXPECT_EQ(m.true_positives, 2);
  EXPECT_NEAR(m.precision, 2.0 / 3, 1e-15);
  EXPECT_NEAR(m.recall, 2.0 / 3, 1e-15);
  EXPECT_NEAR(m.f1, 2.0 / 3, 1e-15);
  EXPECT_NEAR(m.ap50, 92.5 / 101, 1e-12);  // AP uses every detection, whatever the threshold
}

TEST(Metrics, GreedyMatchingTakesTheBestFreeGt) {
  // One detection overlapping two GT boxes: it takes the one with the higher IoU; the second detection
  // (lower score) gets the other if it overlaps enough.
  std::vector<DetectionImage> im = {{{box(0.5, 0.5, 0.2, 0.2), box(0.56, 0.5, 0.2, 0.2)},
                                     {box(0.55, 0.5, 0.2, 0.2, 0.9), box(0.5, 0.5, 0.2, 0.2, 0.8)}}};
  EXPECT_NEAR(average_precision(im, 0.5), 1.0, 1e-12);
  EXPECT_TRUE(std::isnan(average_precision({{{}, {box(0.5, 0.5, 0.1, 0.1, 0.5)}}}, 0.5)));  // no GT: COCO's -1
  EXPECT_EQ(average_precision({{{box(0.5, 0.5, 0.1, 0.1)}, {}}}, 0.5), 0.0);                // no detections
}

// a(x, y) = (7x + 13y) mod 256; b adds ((x² + 3y) mod 23) - 11 (mod 256). 64 x 48.
void test_pair(cv::Mat* a, cv::Mat* b) {
  *a = cv::Mat(48, 64, CV_8U);
  *b = cv::Mat(48, 64, CV_8U);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      a->at<uchar>(y, x) = static_cast<uchar>((x * 7 + y * 13) % 256);
      b->at<uchar>(y, x) = static_cast<uchar>(((x * 7 + y * 13 + (x * x + 3 * y) % 23 - 11) % 256 + 256) % 256);
    }
}

// The footnote said AP was over "every detection" while pycocotools' cap of 100 a picture applies: one GT, 100
// detections far from it at 0.9 and the exact one at 0.1. AP ranks only the first 100 (AP 0); precision,
// recall and F1 count all 101 (1 of 101 true, the one GT found).
TEST(Metrics, ApCountsTheHundredMostConfidentDetectionsOfAPictureAndThePrintedNoteSaysSo) {
  DetectionImage im;
  im.gt = {box(0.5, 0.5, 0.1, 0.1)};
  for (int k = 0; k < 100; ++k) im.detections.push_back(box(0.05 + 0.001 * k, 0.05, 0.01, 0.01, 0.9));
  im.detections.push_back(box(0.5, 0.5, 0.1, 0.1, 0.1));
  const DetectionMetrics m = detection_metrics({im}, 0);
  EXPECT_EQ(m.ap50, 0.0);
  EXPECT_EQ(m.detections, 101);
  EXPECT_NEAR(m.precision, 1.0 / 101, 1e-15);
  EXPECT_EQ(m.recall, 1.0);
  test::TempDir d;
  test::write_two_rock_study(d);
  const auto r = test::run_ipd("metrics " + d.path() + " --bootstrap 0");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("(class 0; AP: pycocotools' rules over the 100 most confident detections of each picture, "
                       "within a class; precision/recall/F1 over every detection at confidence >= 0 and IoU 0.5)\n"),
            std::string::npos)
      << r.out;
}

TEST(Metrics, SsimAndPsnrAgreeWithScikitImage) {
  cv::Mat a, b;
  test_pair(&a, &b);
  EXPECT_NEAR(ssim(a, a), 1.0, 1e-12);
  EXPECT_TRUE(std::isinf(psnr(a, a)));
  // skimage.metrics.structural_similarity(a, b, gaussian_weights=True, sigma=1.5,
  //     use_sample_covariance=False, data_range=255) with scikit-image 0.19.3
  EXPECT_NEAR(ssim(a, b), 0.8312071567064814, 1e-9);
  // 10 log10(255² / mean((a - b)²)) with numpy
  EXPECT_NEAR(psnr(a, b), 16.85975140497631, 1e-9);
  EXPECT_THROW(ssim(a, b(cv::Rect(0, 0, 10, 10))), std::invalid_argument);
}

TEST(Metrics, WarpingBackByTheAffineRecoversThePicture) {
  cv::Mat a, unused;
  test_pair(&a, &unused);
  // B is A shifted right by 8 pixels: B(x) = A(x - 8). b_from_a maps A's normalised x to x + 8/64.
  cv::Mat b(a.size(), CV_8U, cv::Scalar(0));
  a(cv::Rect(0, 0, 56, 48)).copyTo(b(cv::Rect(8, 0, 56, 48)));
  Affine2 m = identity_affine();
  m(0, 2) = 8.0 / 64;
  const AlignedPictures al = align_pictures(a, b, m);
  EXPECT_EQ(cv::countNonZero(al.overlap), 56 * 48);  // A's columns 56..63 fall outside B
  EXPECT_TRUE(std::isinf(psnr(al.a, al.b_on_a, al.overlap)));
  EXPECT_NEAR(ssim(al.a, al.b_on_a, al.overlap), 1.0, 1e-12);
}

TEST(Metrics, ExportRowsReproduceTheTable) {
  test::TempDir d;
  test::write_stats_study(d.path(), test::StatsStudyVariant::kDistinct);
  test::write_text(d / "pairs/real__hapke/s03.json", R"({"pairs": [[0, 0], [1, 1], [2, 2], [3, 3]]})");
  const StudyLabels labels = load_labels(open_study(d.path()));
  const CrossTable t = compute_cross_table(labels, {});
  RockExportOptions o;
  o.unpaired = true;
  const auto rows = rock_rows(labels, t, o);
  std::map<std::string, std::pair<double, long>> by_cell;
  int hand = 0, unpaired = 0;
  for (const auto& r : rows) {
    if (r.index_a < 0 || r.index_b < 0) {
      ++unpaired;
      EXPECT_TRUE(std::isnan(r.diff));
      continue;
    }
    auto& [sum, n] = by_cell[r.model + "|" + r.a + "|" + r.b];
    sum += r.diff;
    ++n;
    hand += r.source == "hand";
    EXPECT_LT(r.residual_px, 10.0) << r.scene;  // jitter of at most 0.2% of 1000 px, and hand pairs fit well
  }
  ASSERT_EQ(by_cell.size(), t.cells.size());
  for (const auto& c : t.cells) {
    const auto& [sum, n] = by_cell[cell_key(c)];
    EXPECT_EQ(n, c.pairs) << cell_key(c);
    EXPECT_NEAR(sum / n, c.ipd, 1e-12) << cell_key(c);
  }
  EXPECT_EQ(hand, 4);
  EXPECT_EQ(unpaired, 6 + 6);  // s03 of real-hapke: 6 rocks a side left unpaired by hand
  const std::string csv = rock_rows_csv(rows);
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "model,trained_on,a,b,scene,class,index_a,index_b,perf_a,perf_b,diff,cx_a,cy_a,w_a,h_a,cx_b,cy_b,w_b,h_b,"
            "residual_px,source,excluded,mask_area_a,mask_area_b");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), static_cast<long>(rows.size()) + 1);
}

// `metrics --images` over three domains: each of the 2 scenes' 3 pictures is decoded once (6), not once per
// domain pair it is in (12), and every column's numbers are those of comparing that pair on its own.
TEST(Metrics, EachPictureIsDecodedOnceForAllItsDomainPairs) {
  test::TempDir d;
  DemoStudyOptions demo;
  demo.scenes = 2;
  demo.width = 96;
  demo.height = 64;
  write_demo_study(d.path(), demo);
  const StudyLabels labels = load_labels(open_study(d.path()));
  ASSERT_EQ(labels.study.domains.size(), 3u);
  const CrossTable t = compute_cross_table(labels, {});
  ASSERT_EQ(t.columns.size(), 3u);
  std::vector<std::string> problems;
  const StudyPixelMetrics all = pixel_metrics_all_columns(labels, t, 2, &problems);
  EXPECT_TRUE(problems.empty());
  EXPECT_EQ(all.pictures_decoded, 6);
  ASSERT_EQ(all.columns.size(), 3u);
  for (size_t c = 0; c < 3; ++c) {
    const auto one = pixel_metrics(labels, t, c, 1, &problems);
    ASSERT_EQ(all.columns[c].size(), 2u);
    ASSERT_EQ(one.size(), 2u);
    for (size_t k = 0; k < 2; ++k) {
      EXPECT_EQ(all.columns[c][k].stem, one[k].stem);
      EXPECT_EQ(all.columns[c][k].ssim, one[k].ssim);
      EXPECT_EQ(all.columns[c][k].psnr, one[k].psnr);
    }
  }
}

}  // namespace
}  // namespace ipd
