#include "core/stats/image_metrics.h"

#include <fmt/format.h>
#include <atomic>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <stdexcept>

#include "core/geometry/affine_estimator.h"
#include "core/picture/picture_codec.h"
#include "core/util/parallel.h"

namespace ipd {

namespace {

void check_pair(const cv::Mat& a, const cv::Mat& b, const cv::Mat& mask) {
  if (a.empty() || a.type() != CV_8UC1 || b.type() != CV_8UC1 || a.size() != b.size())
    throw std::invalid_argument("ssim/psnr need two grey 8-bit pictures of one size");
  if (!mask.empty() && (mask.type() != CV_8UC1 || mask.size() != a.size()))
    throw std::invalid_argument("the mask must be 8-bit and the pictures' size");
}

constexpr int kRadius = 5;  // int(3.5 * 1.5 + 0.5): scikit-image's truncate = 3.5 with σ = 1.5 -> 11 taps

cv::Mat gaussian(const cv::Mat& m) {
  cv::Mat out;
  cv::GaussianBlur(m, out, cv::Size(2 * kRadius + 1, 2 * kRadius + 1), 1.5, 1.5, cv::BORDER_REFLECT);
  return out;
}

}  // namespace

double ssim(const cv::Mat& a8, const cv::Mat& b8, const cv::Mat& mask) {
  check_pair(a8, b8, mask);
  if (a8.rows <= 2 * kRadius || a8.cols <= 2 * kRadius)
    throw std::invalid_argument("ssim needs pictures of at least 11 x 11 pixels");
  cv::Mat a, b;
  a8.convertTo(a, CV_64F);
  b8.convertTo(b, CV_64F);
  const cv::Mat ux = gaussian(a), uy = gaussian(b);
  const cv::Mat vx = gaussian(a.mul(a)) - ux.mul(ux), vy = gaussian(b.mul(b)) - uy.mul(uy);
  const cv::Mat vxy = gaussian(a.mul(b)) - ux.mul(uy);
  const double c1 = std::pow(0.01 * 255, 2), c2 = std::pow(0.03 * 255, 2);
  const cv::Mat num = (2 * ux.mul(uy) + c1).mul(2 * vxy + c2);
  const cv::Mat den = (ux.mul(ux) + uy.mul(uy) + c1).mul(vx + vy + c2);
  cv::Mat s;
  cv::divide(num, den, s);
  // Only windows fully inside the picture (and the mask): erode with a zero border.
  cv::Mat valid = mask.empty() ? cv::Mat(a8.size(), CV_8U, cv::Scalar(255)) : mask.clone();
  cv::erode(valid, valid, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * kRadius + 1, 2 * kRadius + 1)),
            cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(0));
  if (cv::countNonZero(valid) == 0) return std::numeric_limits<double>::quiet_NaN();
  return cv::mean(s, valid)[0];
}

double psnr(const cv::Mat& a8, const cv::Mat& b8, const cv::Mat& mask) {
  check_pair(a8, b8, mask);
  cv::Mat a, b;
  a8.convertTo(a, CV_64F);
  b8.convertTo(b, CV_64F);
  cv::Mat d = a - b;
  d = d.mul(d);
  const int n = mask.empty() ? static_cast<int>(d.total()) : cv::countNonZero(mask);
  if (n == 0) return std::numeric_limits<double>::quiet_NaN();
  double total = 0;
  if (mask.empty()) {
    total = cv::sum(d)[0];
  } else {
    cv::Mat weight;
    mask.convertTo(weight, CV_64F, 1.0 / 255);
    cv::threshold(weight, weight, 0, 1, cv::THRESH_BINARY);  // any non-zero mask value counts fully
    total = cv::sum(d.mul(weight))[0];
  }
  const double mse = total / n;
  if (mse == 0) return std::numeric_limits<double>::infinity();
  return 10 * std::log10(255.0 * 255.0 / mse);
}

AlignedPictures align_pictures(const cv::Mat& grey_a, const cv::Mat& grey_b, const Affine2& b_from_a) {
  // Pixel centre x maps to normalised (x + 0.5) / W; compose pixel(A) -> normalised A -> normalised B -> pixel(B).
  const double wa = grey_a.cols, ha = grey_a.rows, wb = grey_b.cols, hb = grey_b.rows;
  Eigen::Matrix3d a_norm_from_px, b_px_from_norm, aff = Eigen::Matrix3d::Identity();
  a_norm_from_px << 1 / wa, 0, 0.5 / wa, 0, 1 / ha, 0.5 / ha, 0, 0, 1;
  b_px_from_norm << wb, 0, -0.5, 0, hb, -0.5, 0, 0, 1;
  aff.topRows<2>() = b_from_a;
  const Eigen::Matrix3d m = b_px_from_norm * aff * a_norm_from_px;
  cv::Mat map(2, 3, CV_64F);
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 3; ++c) map.at<double>(r, c) = m(r, c);
  AlignedPictures out;
  out.a = grey_a;
  cv::warpAffine(grey_b, out.b_on_a, map, grey_a.size(), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP, cv::BORDER_CONSTANT);
  const cv::Mat ones(grey_b.size(), CV_8U, cv::Scalar(255));
  cv::warpAffine(ones, out.overlap, map, grey_a.size(), cv::INTER_NEAREST | cv::WARP_INVERSE_MAP, cv::BORDER_CONSTANT);
  return out;
}

Affine2 scene_b_from_a(const ScenePairing& p, const std::vector<Box>& ga, const std::vector<Box>& gb) {
  if (!p.fixed) return p.registration.affine;
  std::vector<Eigen::Vector2d> src, dst;
  for (const auto& [i, j] : p.pairs) {
    src.push_back(ga[i].centre());
    dst.push_back(gb[j].centre());
  }
  Affine2 m = identity_affine();
  if (src.size() >= 3 && !affine_least_squares_trimmed(src, dst, &m)) m = identity_affine();
  return m;
}

namespace {

ScenePixelMetrics compare_pictures(const cv::Mat& ga, const cv::Mat& gb, const ScenePairing& p,
                                   const Affine2& b_from_a) {
  const AlignedPictures al = align_pictures(ga, gb, b_from_a);
  ScenePixelMetrics r;
  r.stem = p.stem;
  r.overlap = static_cast<double>(cv::countNonZero(al.overlap)) / al.overlap.total();
  r.ssim = ssim(al.a, al.b_on_a, al.overlap);
  r.psnr = psnr(al.a, al.b_on_a, al.overlap);
  return r;
}

}  // namespace

StudyPixelMetrics pixel_metrics_all_columns(const StudyLabels& labels, const CrossTable& table, int threads,
                                            std::vector<std::string>* problems) {
  // Every (column, scene) by stem, so a scene's pictures are decoded once for all its domain pairs.
  std::map<std::string, std::vector<std::pair<size_t, size_t>>> by_stem;
  for (size_t c = 0; c < table.columns.size() && c < table.pairings.size(); ++c)
    for (size_t k = 0; k < table.pairings[c].size(); ++k) by_stem[table.pairings[c][k].stem].emplace_back(c, k);
  std::vector<const std::pair<const std::string, std::vector<std::pair<size_t, size_t>>>*> stems;
  for (const auto& e : by_stem) stems.push_back(&e);
  StudyPixelMetrics out;
  std::vector<std::vector<std::optional<ScenePixelMetrics>>> results(table.pairings.size());
  for (size_t c = 0; c < table.pairings.size(); ++c) results[c].resize(table.pairings[c].size());
  std::vector<std::vector<std::string>> scene_problems(stems.size());
  std::atomic<int> decoded{0};
  parallel_for(stems.size(), threads, [&](size_t s) {
    const std::string& stem = stems[s]->first;
    std::map<std::string, cv::Mat> grey;  // domain -> its picture of this scene, decoded at first use
    auto picture = [&](const std::string& domain) -> const cv::Mat* {
      auto it = grey.find(domain);
      if (it == grey.end()) {
        const Domain* d = labels.study.domain(domain);
        const auto im = d->images.find(stem);
        cv::Mat m;
        if (im != d->images.end()) {
          PictureRead read = read_study_picture(labels.study.root, im->second, cv::IMREAD_GRAYSCALE);
          m = std::move(read.image);
          ++decoded;
          if (m.empty()) scene_problems[s].push_back(read.problem);
        }
        it = grey.emplace(domain, m).first;
      }
      return it->second.empty() ? nullptr : &it->second;
    };
    for (const auto& [c, k] : stems[s]->second) {
      const auto& [a, b] = table.columns[c];
      const cv::Mat* ga = picture(a);
      const cv::Mat* gb = ga ? picture(b) : nullptr;
      if (!ga || !gb) continue;
      const ScenePairing& p = table.pairings[c][k];
      const ScenePixelMetrics r =
          compare_pictures(*ga, *gb, p, scene_b_from_a(p, labels.gt_of(a, stem).boxes, labels.gt_of(b, stem).boxes));
      if (!std::isnan(r.ssim)) results[c][k] = r;
    }
  });
  for (const auto& v : scene_problems) problems->insert(problems->end(), v.begin(), v.end());
  out.pictures_decoded = decoded;
  out.columns.resize(results.size());
  for (size_t c = 0; c < results.size(); ++c)
    for (const auto& r : results[c])
      if (r) out.columns[c].push_back(*r);
  return out;
}

std::vector<ScenePixelMetrics> pixel_metrics(const StudyLabels& labels, const CrossTable& table, size_t column,
                                             int threads, std::vector<std::string>* problems) {
  // Named copies, not structured bindings: C++17 lambdas can't capture those (clang rejects it).
  const std::string& a = table.columns.at(column).first;
  const std::string& b = table.columns.at(column).second;
  const Domain* da = labels.study.domain(a);
  const Domain* db = labels.study.domain(b);
  const auto& pairings = table.pairings.at(column);
  std::vector<ScenePixelMetrics> results(pairings.size());
  std::vector<char> ok(pairings.size(), 0);
  std::mutex mu;
  parallel_for(pairings.size(), threads, [&](size_t k) {
    const ScenePairing& p = pairings[k];
    const auto ia = da->images.find(p.stem), ib = db->images.find(p.stem);
    if (ia == da->images.end() || ib == db->images.end()) return;
    const cv::Mat ga = read_study_picture(labels.study.root, ia->second, cv::IMREAD_GRAYSCALE).image,
                  gb = read_study_picture(labels.study.root, ib->second, cv::IMREAD_GRAYSCALE).image;
    if (ga.empty() || gb.empty()) {
      std::lock_guard<std::mutex> lock(mu);
      problems->push_back(fmt::format("{}: can't read the picture", ga.empty() ? ia->second : ib->second));
      return;
    }
    const AlignedPictures al =
        align_pictures(ga, gb, scene_b_from_a(p, labels.gt_of(a, p.stem).boxes, labels.gt_of(b, p.stem).boxes));
    ScenePixelMetrics& r = results[k];
    r.stem = p.stem;
    r.overlap = static_cast<double>(cv::countNonZero(al.overlap)) / al.overlap.total();
    r.ssim = ssim(al.a, al.b_on_a, al.overlap);
    r.psnr = psnr(al.a, al.b_on_a, al.overlap);
    ok[k] = !std::isnan(r.ssim);
  });
  std::vector<ScenePixelMetrics> out;
  for (size_t k = 0; k < results.size(); ++k)
    if (ok[k]) out.push_back(results[k]);
  return out;
}

}  // namespace ipd
