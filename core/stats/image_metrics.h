// Pixel metrics beside IPD: SSIM and PSNR of a real picture and its synthetic twin warped onto it with the
// registration's affine, over the pictures' overlap. SSIM is Wang et al. 2004 as scikit-image computes it
// (structural_similarity with gaussian_weights=True: Gaussian window σ = 1.5, 11 taps, population
// covariance, data range 255, grey levels), PSNR = 10 log10(255² / MSE).
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/geometry/geometry.h"
#include "core/ipd/ipd.h"

namespace ipd {

// Mean SSIM of two CV_8U grey pictures of one size over the pixels where `mask` (CV_8U, optional) is set
// and the 11×11 window lies inside the picture (scikit-image crops the same 5-pixel border).
// Throws std::invalid_argument for mismatched or non-grey inputs.
double ssim(const cv::Mat& a, const cv::Mat& b, const cv::Mat& mask = cv::Mat());
// PSNR over the pixels where `mask` is set (all when empty); +inf for identical pictures.
double psnr(const cv::Mat& a, const cv::Mat& b, const cv::Mat& mask = cv::Mat());

struct AlignedPictures {
  cv::Mat a, b_on_a;  // grey, A's size
  cv::Mat overlap;    // CV_8U, 255 where b_on_a has picture content
};
// Warps B onto A: `b_from_a` maps normalised A coordinates to normalised B coordinates (as
// RegistrationReport::affine), so each A pixel samples B at the mapped position (bilinear).
AlignedPictures align_pictures(const cv::Mat& grey_a, const cv::Mat& grey_b, const Affine2& b_from_a);

// The affine a scene's pairs are measured against: registration's, or for hand-paired scenes a least-squares
// fit on the hand pairs (identity when fewer than three).
Affine2 scene_b_from_a(const ScenePairing& pairing, const std::vector<Box>& gt_a, const std::vector<Box>& gt_b);

struct ScenePixelMetrics {
  std::string stem;
  double ssim = 0, psnr = 0;
  double overlap = 0;  // fraction of A's pixels covered by the warped B
};
// Every scene of column `column` of the table whose pictures exist in both domains (read and compared in
// parallel; results in the table's scene order). Unreadable pictures are reported in `problems`.
std::vector<ScenePixelMetrics> pixel_metrics(const StudyLabels& labels, const CrossTable& table, size_t column,
                                             int threads, std::vector<std::string>* problems);

struct StudyPixelMetrics {
  std::vector<std::vector<ScenePixelMetrics>> columns;  // as pixel_metrics, one per column of the table
  int pictures_decoded = 0;                             // each picture once, whatever the number of domain pairs
};
// Every column's pixel_metrics, each scene's pictures decoded once for all the domain pairs they are in (a
// scene at a time, so memory stays at one scene's pictures per thread). An unreadable picture is one problem.
StudyPixelMetrics pixel_metrics_all_columns(const StudyLabels& labels, const CrossTable& table, int threads,
                                            std::vector<std::string>* problems);

}  // namespace ipd
