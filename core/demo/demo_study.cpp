#include "core/demo/demo_study.h"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <random>
#include <stdexcept>

#include "core/demo/demo_files.h"
#include "core/demo/demo_rng.h"
#include "core/detect/rock_detector.h"
#include "core/io/label_io.h"
#include "core/picture/picture_codec.h"

namespace ipd {

namespace {

struct Rock {
  double x, y, rx, ry, angle_deg, albedo;
};

struct Scene {
  std::vector<Rock> rocks;
  double sun_deg;
  cv::Point2d wall_a, wall_b;  // the wall's shadow: the half-plane left of the line a->b, near the top-left
  std::uint64_t texture_seed;
};

struct DomainLook {
  const char* name;
  double ground, ground_contrast, noise, shade_ambient, shadow_factor, blur;
  bool camera_offset, wall_shadow;
};

const DomainLook kLooks[] = {
    {"real", 96, 12, 8, 0.25, 0.40, 1.2, true, true},
    {"principled", 100, 11, 4, 0.28, 0.45, 0.0, false, false},
    {"hapke", 124, 7, 3, 0.62, 0.72, 0.0, false, false},
};

Scene make_scene(DemoRng& rng, int w, int h, int min_rocks, int max_rocks) {
  Scene s;
  s.sun_deg = rng.uniform(0, 360);
  s.texture_seed = rng.g();
  const int n = min_rocks + rng.below(std::max(1, max_rocks - min_rocks + 1));
  // Smaller rocks when there are many, so they still fit.
  const double shrink = std::sqrt(18.0 / std::max(18, n));
  for (int k = 0; k < n; ++k) {
    Rock r;
    for (int attempt = 0; attempt < 50; ++attempt) {
      const double size = shrink * std::min(w, h) * std::exp(rng.uniform(std::log(0.025), std::log(0.08)));
      r = {rng.uniform(0.06, 0.94) * w,   rng.uniform(0.08, 0.92) * h, size,
           size * rng.uniform(0.55, 0.9), rng.uniform(-30, 30),        rng.uniform(1.1, 1.6)};
      bool clear = true;
      for (const auto& o : s.rocks)
        if (std::hypot(o.x - r.x, o.y - r.y) < 1.3 * (o.rx + r.rx)) clear = false;
      if (clear) break;
    }
    s.rocks.push_back(r);
  }
  s.wall_a = {0, rng.uniform(0.15, 0.35) * h};
  s.wall_b = {rng.uniform(0.25, 0.45) * w, 0};
  return s;
}

bool in_wall_shadow(const Scene& s, double x, double y) {
  const cv::Point2d d = s.wall_b - s.wall_a, p = cv::Point2d(x, y) - s.wall_a;
  return d.x * p.y - d.y * p.x < 0;  // the side containing the top-left corner
}

// The real camera sits slightly off the simulated one.
cv::Matx23d camera_offset(int scene_index, int w, int h) {
  const double rot = (0.8 + 0.3 * scene_index) * M_PI / 180.0, scale = 1.015;
  const double tx = 10 + 2 * scene_index, ty = -7 + scene_index;
  const double c = scale * std::cos(rot), s = scale * std::sin(rot);
  const double cx = 0.5 * w, cy = 0.5 * h;
  return {c, -s, cx - c * cx + s * cy + tx, s, c, cy - s * cx - c * cy + ty};
}

// A rock as the domain's camera sees it: moved by `cam` (and 1.5% larger) when the domain has a camera offset.
Rock seen_through(const Rock& r0, const DomainLook& look, const cv::Matx23d& cam) {
  Rock r = r0;
  if (look.camera_offset) {
    r.x = cam(0, 0) * r0.x + cam(0, 1) * r0.y + cam(0, 2);
    r.y = cam(1, 0) * r0.x + cam(1, 1) * r0.y + cam(1, 2);
    r.rx *= 1.015;
    r.ry *= 1.015;
  }
  return r;
}

// Ground: two octaves of smoothed noise, the same field for every domain of a scene (drawn from `tex` first).
cv::Mat ground(const DomainLook& look, int w, int h, cv::RNG& tex) {
  cv::Mat coarse(h / 16 + 1, w / 16 + 1, CV_32F), fine(h / 4 + 1, w / 4 + 1, CV_32F);
  tex.fill(coarse, cv::RNG::NORMAL, 0, 1);
  tex.fill(fine, cv::RNG::NORMAL, 0, 1);
  cv::resize(coarse, coarse, cv::Size(w, h), 0, 0, cv::INTER_CUBIC);
  cv::resize(fine, fine, cv::Size(w, h), 0, 0, cv::INTER_LINEAR);
  return look.ground + look.ground_contrast * (0.7 * coarse + 0.3 * fine);
}

// A rock's shadow, cast away from the sun; drawn only in the patch it can cover.
void draw_shadow(const Rock& r, const DomainLook& look, const cv::Point2d& light, cv::Mat& img) {
  const int w = img.cols, h = img.rows;
  const cv::Point2d sc(r.x - 0.7 * r.rx * light.x, r.y - 0.7 * r.rx * light.y);
  const int reach = static_cast<int>(std::ceil(r.rx * 1.15)) + 3;
  const cv::Rect patch =
      cv::Rect(static_cast<int>(sc.x) - reach, static_cast<int>(sc.y) - reach, 2 * reach + 1, 2 * reach + 1) &
      cv::Rect(0, 0, w, h);
  if (patch.area() <= 0) return;
  cv::Mat shadow = cv::Mat::zeros(patch.size(), CV_8U);
  cv::ellipse(shadow, sc - cv::Point2d(patch.x, patch.y), cv::Size2d(r.rx * 1.15, r.ry * 1.05), r.angle_deg, 0, 360,
              255, cv::FILLED, cv::LINE_AA);
  cv::Mat sh_f;
  shadow.convertTo(sh_f, CV_32F, 1.0 / 255);
  cv::Mat roi = img(patch);
  roi = roi.mul(1.0 - (1.0 - look.shadow_factor) * sh_f);
}

// The rock as a shaded half-ellipsoid; returns the pixels it covers (empty when outside the frame).
cv::Rect draw_rock(const Rock& r, const DomainLook& look, const cv::Point2d& light, cv::Mat& img) {
  const int w = img.cols, h = img.rows;
  const double ca = std::cos(r.angle_deg * M_PI / 180), sa = std::sin(r.angle_deg * M_PI / 180);
  const int x0 = std::max(0, static_cast<int>(r.x - r.rx - 2)), x1 = std::min(w - 1, static_cast<int>(r.x + r.rx + 2));
  const int y0 = std::max(0, static_cast<int>(r.y - r.rx - 2)), y1 = std::min(h - 1, static_cast<int>(r.y + r.rx + 2));
  int bx0 = w, by0 = h, bx1 = -1, by1 = -1;
  for (int y = y0; y <= y1; ++y) {
    float* row = img.ptr<float>(y);
    for (int x = x0; x <= x1; ++x) {
      const double dx = x - r.x, dy = y - r.y;
      const double u = (ca * dx + sa * dy) / r.rx, v = (-sa * dx + ca * dy) / r.ry;
      const double q = u * u + v * v;
      if (q > 1) continue;
      const double nz = std::sqrt(1 - q);
      // normal in image axes
      const double nx = ca * u - sa * v, ny = sa * u + ca * v;
      const double lambert = std::max(0.0, 0.75 * (nx * light.x + ny * light.y) + 0.55 * nz);
      row[x] = static_cast<float>(look.ground * r.albedo * (look.shade_ambient + (1.2 - look.shade_ambient) * lambert));
      bx0 = std::min(bx0, x), bx1 = std::max(bx1, x), by0 = std::min(by0, y), by1 = std::max(by1, y);
    }
  }
  if (bx1 < bx0) return {};
  return {bx0, by0, bx1 - bx0 + 1, by1 - by0 + 1};
}

// The camera's finish: the wall's shadow, blur, sensor noise (drawn from `tex` after the ground), 8 bits and a
// faint warm tint, as lunar-analogue photos have.
cv::Mat finish(const Scene& scene, const DomainLook& look, cv::Mat img, cv::RNG& tex) {
  const int w = img.cols, h = img.rows;
  if (look.wall_shadow) {
    for (int y = 0; y < h; ++y) {
      float* row = img.ptr<float>(y);
      for (int x = 0; x < w; ++x)
        if (in_wall_shadow(scene, x, y)) row[x] *= 0.18f;
    }
  }
  if (look.blur > 0) cv::GaussianBlur(img, img, cv::Size(0, 0), look.blur);
  cv::Mat noise(h, w, CV_32F);
  tex.fill(noise, cv::RNG::NORMAL, 0, look.noise);
  img += noise;
  cv::Mat out8;
  img.convertTo(out8, CV_8U);
  cv::Mat bgr;
  cv::cvtColor(out8, bgr, cv::COLOR_GRAY2BGR);
  bgr.forEach<cv::Vec3b>([](cv::Vec3b& p, const int*) { p[2] = cv::saturate_cast<uchar>(p[2] * 1.04 + 2); });
  return bgr;
}

// The rock's outline as drawn: 24 points on its ellipse, inside the frame, normalised.
std::vector<Eigen::Vector2d> rock_outline(const Rock& r, int w, int h) {
  const double ca = std::cos(r.angle_deg * M_PI / 180), sa = std::sin(r.angle_deg * M_PI / 180);
  std::vector<Eigen::Vector2d> points;
  for (int k = 0; k < 24; ++k) {
    const double t = 2 * M_PI * k / 24, u = r.rx * std::cos(t), v = r.ry * std::sin(t);
    const Eigen::Vector2d p(std::clamp(r.x + ca * u - sa * v, 0.0, double(w)) / w,
                            std::clamp(r.y + sa * u + ca * v, 0.0, double(h)) / h);
    if (points.empty() || p != points.back()) points.push_back(p);  // points clamped onto one corner count once
  }
  return points;
}

cv::Mat render(const Scene& scene, const DomainLook& look, const cv::Matx23d& cam, int w, int h, bool outlines,
               std::vector<Box>* gt) {
  cv::RNG tex(scene.texture_seed);
  cv::Mat img = ground(look, w, h, tex);
  const double sun = scene.sun_deg * M_PI / 180.0;
  const cv::Point2d light(std::cos(sun), std::sin(sun));
  gt->clear();
  for (const auto& r0 : scene.rocks) {
    const Rock r = seen_through(r0, look, cam);
    draw_shadow(r, look, light, img);
    const cv::Rect covered = draw_rock(r, look, light, img);
    if (covered.empty()) continue;                                      // outside the frame
    if (look.wall_shadow && in_wall_shadow(scene, r.x, r.y)) continue;  // labellers can't see rocks in it
    const double cw = covered.width, ch = covered.height;
    if (cw < 4 || ch < 4) continue;
    Box b;
    b.cls = 0;
    b.cx = (covered.x + 0.5 * cw) / w;
    b.cy = (covered.y + 0.5 * ch) / h;
    b.w = cw / w;
    b.h = ch / h;
    if (outlines && !set_outline(rock_outline(r, w, h), &b).empty()) continue;  // no area inside the frame
    gt->push_back(b);
  }
  return finish(scene, look, img, tex);
}

void write_png(const std::string& dir, const std::string& relative, const cv::Mat& img) {
  std::vector<uchar> buf;
  if (!encode_picture(".png", img, &buf)) throw IoError(dir + "/" + relative + ": PNG encoding failed");
  write_demo_file(dir, relative, std::string(buf.begin(), buf.end()));
}

const char* kDemoReadme = R"(# IPD Studio demo study (generated)

This study was generated by `ipd demo`; nothing in it is real data. It exists so that every feature of
IPD Studio can be tried without downloading anything.

- `real/`, `principled/`, `hapke/`: six scenes each, drawn with OpenCV: lunar-like ground, shaded rocks and
  their shadows. `real` has a small camera offset, more noise, slight blur and a wall shadow in which rocks
  are unlabelled (as in the POLAR photos); `hapke` has flatter shading than `principled`.
- `labels/`: GT boxes (YOLO txt). Rows are shuffled per domain, so rock indices differ between domains
  and pairing needs registration.
- `predictions/det-<domain>/`: a classical OpenCV rock detector (background difference, threshold,
  contours) whose parameters were tuned on `<domain>`, run on every domain.
- Written by `ipd demo --task segment`: every label line is an outline (YOLO-seg), GT the drawn rock's
  ellipse and predictions the detector's contours, and study.yaml says `task: segment`: the IPD is about
  mask IoU.
)";

// The GT box of a rock as seen through `cam` (no picture): the rotated ellipse's bounding box, clipped.
bool geometric_box(const Rock& r0, const DomainLook& look, const Scene& scene, const cv::Matx23d& cam, int w, int h,
                   Box* out) {
  const Rock r = seen_through(r0, look, cam);
  if (look.wall_shadow && in_wall_shadow(scene, r.x, r.y)) return false;
  const double ca = std::cos(r.angle_deg * M_PI / 180), sa = std::sin(r.angle_deg * M_PI / 180);
  const double ex = std::hypot(r.rx * ca, r.ry * sa), ey = std::hypot(r.rx * sa, r.ry * ca);
  const double x0 = std::max(0.0, r.x - ex), x1 = std::min<double>(w, r.x + ex);
  const double y0 = std::max(0.0, r.y - ey), y1 = std::min<double>(h, r.y + ey);
  if (x1 - x0 < 4 || y1 - y0 < 4) return false;
  *out = Box{0, 0.5 * (x0 + x1) / w, 0.5 * (y0 + y1) / h, (x1 - x0) / w, (y1 - y0) / h, 1.0};
  return true;
}

// A detector that knows the GT: trained on its own domain it misses less and fits tighter.
std::vector<Box> synthetic_predictions(DemoRng& rng, const std::vector<Box>& gt, bool own_domain) {
  const double miss = own_domain ? 0.05 : 0.15, jitter = own_domain ? 0.08 : 0.18;
  std::vector<Box> out;
  for (const Box& g : gt) {
    if (rng.uniform(0, 1) < miss) continue;
    Box p = g;
    p.cx += rng.uniform(-jitter, jitter) * g.w;
    p.cy += rng.uniform(-jitter, jitter) * g.h;
    p.w *= 1 + rng.uniform(-jitter, jitter);
    p.h *= 1 + rng.uniform(-jitter, jitter);
    p.conf = rng.uniform(0.3, 0.99);
    out.push_back(p);
  }
  if (rng.uniform(0, 1) < 0.3)
    out.push_back(Box{0, rng.uniform(0.1, 0.9), rng.uniform(0.1, 0.9), 0.03, 0.03, rng.uniform(0.05, 0.5)});
  return out;
}

void write_labels_only_study(const std::string& dir, const DemoStudyOptions& o) {
  DemoRng rng(o.seed);
  const size_t n_looks = std::size(kLooks);
  auto stem = [&](int k) { return fmt::format("scene_{:05d}", k + 1); };
  for (int k = 0; k < o.scenes; ++k) {
    const Scene scene = make_scene(rng, o.width, o.height, o.min_rocks, o.max_rocks);
    const cv::Matx23d cam = camera_offset(k % 20, o.width, o.height);
    for (size_t d = 0; d < n_looks; ++d) {
      std::vector<Box> gt;
      Box b;
      for (const auto& r : scene.rocks)
        if (geometric_box(r, kLooks[d], scene, cam, o.width, o.height, &b)) gt.push_back(b);
      for (size_t i = gt.size(); i > 1; --i) std::swap(gt[i - 1], gt[rng.below(static_cast<int>(i))]);
      const std::string base = std::string(kLooks[d].name) + "/";
      write_demo_labels(dir, base + "labels/" + stem(k) + ".txt", gt, LabelKind::kGroundTruth);
      for (size_t m = 0; m < n_looks; ++m)
        write_demo_labels(dir, base + "predictions/det-" + kLooks[m].name + "/" + stem(k) + ".txt",
                          synthetic_predictions(rng, gt, m == d), LabelKind::kPrediction);
    }
  }
  std::string yaml =
      "# Generated by `ipd demo --labels-only`: a synthetic labels-only study (no pictures).\n"
      "domains: [real, principled, hapke]\n";
  yaml += fmt::format("image_size: [{}, {}]\nrock_class: 0\nmodels:\n", o.width, o.height);
  for (size_t m = 0; m < n_looks; ++m) yaml += fmt::format("  det-{0}: {{trained_on: {0}}}\n", kLooks[m].name);
  yaml += "registration: {method: consensus, seed: 0}\n";
  finish_demo_study(dir, yaml, "");
}

}  // namespace

std::string DemoStudyOptions::validate() const {
  if (scenes < 1) return fmt::format("scenes must be at least 1, got {}", scenes);
  if (!(min_rocks >= 0 && min_rocks <= max_rocks))
    return fmt::format("rocks per scene must satisfy 0 <= min_rocks <= max_rocks, got [{}, {}]", min_rocks, max_rocks);
  if (width < 64 || height < 64)
    return fmt::format("width and height must be at least 64 pixels, got {} x {}", width, height);
  if (segment && labels_only)
    return "the segmentation demo needs its pictures (its predictions are the detector's contours): not with "
           "labels_only";
  return {};
}

void DemoStudyOptions::check() const {
  if (const std::string problem = validate(); !problem.empty())
    throw std::invalid_argument("demo study options: " + problem);
}

void write_demo_study(const std::string& dir, const DemoStudyOptions& o) {
  o.check();
  if (o.labels_only) return write_labels_only_study(dir, o);
  const int w = o.width, h = o.height;
  DemoRng rng(o.seed);
  std::vector<Scene> scenes;
  for (int k = 0; k < o.scenes; ++k) scenes.push_back(make_scene(rng, w, h, o.min_rocks, o.max_rocks));
  const size_t n_looks = std::size(kLooks);
  std::vector<std::vector<cv::Mat>> pictures(n_looks);
  std::vector<std::vector<std::vector<Box>>> gts(n_looks);
  auto stem = [](int k) { return fmt::format("scene_{:02d}", k + 1); };
  for (size_t d = 0; d < n_looks; ++d) {
    for (int k = 0; k < o.scenes; ++k) {
      std::vector<Box> gt;
      pictures[d].push_back(render(scenes[k], kLooks[d], camera_offset(k, w, h), w, h, o.segment, &gt));
      // Shuffle rows so that indices differ between domains, as independent labelling does.
      for (size_t i = gt.size(); i > 1; --i) std::swap(gt[i - 1], gt[rng.below(static_cast<int>(i))]);
      gts[d].push_back(gt);
      const std::string base = std::string(kLooks[d].name) + "/";
      write_png(dir, base + "images/" + stem(k) + ".png", pictures[d].back());
      write_demo_labels(dir, base + "labels/" + stem(k) + ".txt", gt, LabelKind::kGroundTruth);
    }
  }
  std::string yaml =
      "# Generated by `ipd demo`: a small synthetic study for trying IPD Studio.\n"
      "domains: [real, principled, hapke]\n";
  yaml += fmt::format("image_size: [{}, {}]\nrock_class: 0\n", w, h);
  if (o.segment) yaml += "task: segment  # the IPD of mask IoU: GT outlines as drawn, the detector's contours\n";
  yaml += "models:\n";
  for (size_t m = 0; m < n_looks; ++m) {
    const RockDetectorParams params = tune_detector(pictures[m], gts[m]);
    const std::string model = std::string("det-") + kLooks[m].name;
    yaml += fmt::format("  {}: {{trained_on: {}}}  # threshold {}, background {}, close {}\n", model, kLooks[m].name,
                        params.threshold, params.background_kernel, params.close_kernel);
    for (size_t d = 0; d < n_looks; ++d)
      for (int k = 0; k < o.scenes; ++k)
        write_demo_labels(dir, std::string(kLooks[d].name) + "/predictions/" + model + "/" + stem(k) + ".txt",
                          detect_rocks(pictures[d][k], params, o.segment), LabelKind::kPrediction);
  }
  yaml += "registration: {method: consensus, seed: 0}\n";
  finish_demo_study(dir, yaml, kDemoReadme);
}

}  // namespace ipd
