#include "app/bench/registration_benchmark.h"

#include <fmt/format.h>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <numeric>
#include <regex>

#include "core/geometry/affine_estimator.h"
#include "core/io/label_io.h"
#include "core/registration/pairing.h"
#include "core/registration/registration_frame.h"

namespace fs = std::filesystem;

namespace ipd {

std::vector<LabelPair> polar_sim_label_pairs(const std::string& root, int min_true_pairs) {
  // NN_<cam>_<light>_<sun>_<LR>_<exposure>.txt
  const std::regex name(R"((\d+)_([ABC])_(on|off)_(\w+?)_([LR])_(\d+)\.txt)");
  std::map<std::string, std::map<std::string, std::string>> views;  // view -> sun -> first exposure's file
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(root))
    if (e.path().extension() == ".txt") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const auto& f : files) {
    std::smatch m;
    const std::string base = f.filename().string();
    if (!std::regex_match(base, m, name)) continue;
    const std::string view = m[1].str() + "_" + m[2].str() + "_" + m[3].str() + "_" + m[5].str();
    views[view].emplace(m[4].str(), f.string());  // emplace keeps the first exposure
  }
  std::vector<LabelPair> out;
  for (const auto& [view, suns] : views) {
    std::vector<std::pair<std::string, std::string>> list(suns.begin(), suns.end());
    for (size_t i = 0; i < list.size(); ++i)
      for (size_t j = i + 1; j < list.size(); ++j) {
        LabelPair p;
        p.file_a = list[i].second;
        p.file_b = list[j].second;
        LabelFile fa = read_labels(p.file_a, {}), fb = read_labels(p.file_b, {});
        keep_class(&fa, 0);
        keep_class(&fb, 0);
        p.a = fa.boxes;
        p.b = fb.boxes;
        p.truth = pair_aligned_boxes(identity_affine(), p.a, p.b, overlap_only(kTruthIou));
        p.strict_truth = pair_aligned_boxes(identity_affine(), p.a, p.b, overlap_only(kStrictTruthIou));
        if (static_cast<int>(p.truth.size()) >= min_true_pairs) out.push_back(std::move(p));
      }
  }
  return out;
}

int terrain_of(const std::string& file) {
  const std::string base = fs::path(file).filename().string();
  size_t digits = 0;
  while (digits < base.size() && digits < 4 && std::isdigit(static_cast<unsigned char>(base[digits]))) ++digits;
  if (digits == 0 || digits >= base.size() || base[digits] != '_') return -1;
  return std::stoi(base.substr(0, digits));
}

MisalignmentRange small_misalignment() { return {"small", 5, 0.9, 1.1, 0.05, 0.05, 0.10, 0.002}; }
MisalignmentRange large_misalignment() { return {"large", 25, 0.7, 1.4, 0.15, 0.25, 0.25, 0.004}; }
MisalignmentRange unequal_counts() {
  MisalignmentRange r = small_misalignment();
  r.name = "unequal";
  r.drop_smallest_min = 0.3;
  r.drop_smallest_max = 0.5;
  return r;
}
std::vector<MisalignmentRange> benchmark_tiers() {
  return {small_misalignment(), large_misalignment(), unequal_counts()};
}

bool least_squares_on_truth(const RegistrationCase& c, Affine2* out) {
  std::vector<Eigen::Vector2d> src, dst;
  for (const auto& [i, j] : c.truth) {
    src.push_back(c.a[i].centre());
    dst.push_back(c.b[j].centre());
  }
  return src.size() >= 3 && affine_least_squares(src, dst, out);
}

PairingRule overlap_only(double min_iou) {
  PairingRule rule;
  rule.min_iou = min_iou;
  rule.noise_floor = 0;
  return rule;
}

RockPairs pairs_under_true_affine(const RegistrationCase& c, const RegistrationOptions& o) {
  return pair_aligned_boxes(c.truth_affine, c.a, c.b, pairing_rule(o));
}

LabelPair synthetic_label_pair(int n, std::uint64_t seed) {
  detail::Rng rng(seed * 104729 + 3);
  auto u = [&](double lo, double hi) { return lo + (hi - lo) * rng.uniform(); };
  LabelPair p;
  p.file_a = fmt::format("synthetic-{}-a", n);
  p.file_b = fmt::format("synthetic-{}-b", n);
  const double size = 0.25 / std::sqrt(static_cast<double>(n));
  for (int k = 0; k < n; ++k) {
    Box a;
    a.cx = u(0.03, 0.97), a.cy = u(0.03, 0.97), a.w = size * u(0.4, 1.6), a.h = size * u(0.4, 1.6);
    Box b = a;  // labelled again: the centre moves by a tenth of the size, the extent by up to 10%
    b.cx += u(-0.1, 0.1) * a.w, b.cy += u(-0.1, 0.1) * a.h, b.w *= u(0.9, 1.1), b.h *= u(0.9, 1.1);
    p.a.push_back(a);
    p.b.push_back(b);
    p.truth.emplace_back(k, k);
  }
  return p;
}

RegistrationCase make_case(const LabelPair& pair, const MisalignmentRange& r, std::uint64_t seed, double W, double H) {
  detail::Rng rng(seed * 7919 + 17);
  auto u = [&](double lo, double hi) { return lo + (hi - lo) * rng.uniform(); };
  auto gauss = [&]() {  // Box-Muller
    const double u1 = std::max(rng.uniform(), 1e-300), u2 = rng.uniform();
    return std::sqrt(-2 * std::log(u1)) * std::cos(2 * M_PI * u2);
  };
  // The affine in pixels about the image centre: shift * rotation * shear * scale.
  const double th = u(-r.max_rotation_deg, r.max_rotation_deg) * M_PI / 180;
  const double sx = u(r.min_scale, r.max_scale), sy = u(r.min_scale, r.max_scale), k = u(-r.max_shear, r.max_shear);
  Eigen::Matrix2d rot, shear, scale;
  rot << std::cos(th), -std::sin(th), std::sin(th), std::cos(th);
  shear << 1, k, 0, 1;
  scale << sx, 0, 0, sy;
  const Eigen::Matrix2d lin_px = rot * shear * scale;
  const Eigen::Vector2d c(W / 2, H / 2), shift(u(-r.max_shift, r.max_shift) * W, u(-r.max_shift, r.max_shift) * H);
  const Eigen::Vector2d t_px = c + shift - lin_px * c;
  // In normalised coordinates: N = diag(1/W, 1/H).
  const Eigen::Matrix2d n = Eigen::Vector2d(1 / W, 1 / H).asDiagonal(), ni = Eigen::Vector2d(W, H).asDiagonal();
  RegistrationCase out;
  out.truth_affine.leftCols<2>() = n * lin_px * ni;
  out.truth_affine.col(2) = n * t_px;
  out.source = fs::path(pair.file_a).filename().string() + " vs " + fs::path(pair.file_b).filename().string();

  auto keep_mask = [&](size_t count) {
    std::vector<int> order(count);
    std::iota(order.begin(), order.end(), 0);
    for (size_t i = count; i > 1; --i) std::swap(order[i - 1], order[rng.below(static_cast<int>(i))]);
    const size_t hide = static_cast<size_t>(std::lround(r.hidden * static_cast<double>(count)));
    std::vector<char> keep(count, 1);
    for (size_t i = 0; i < hide && i < count; ++i) keep[order[i]] = 0;
    return keep;
  };
  auto keep_a = keep_mask(pair.a.size());
  const auto keep_b = keep_mask(pair.b.size());
  if (r.drop_smallest_max > 0) {  // A misses its smallest rocks
    std::vector<int> by_area;
    for (size_t i = 0; i < pair.a.size(); ++i)
      if (keep_a[i]) by_area.push_back(static_cast<int>(i));
    std::stable_sort(by_area.begin(), by_area.end(),
                     [&](int x, int y) { return pair.a[x].w * pair.a[x].h < pair.a[y].w * pair.a[y].h; });
    const double fraction = u(r.drop_smallest_min, r.drop_smallest_max);
    const size_t drop = static_cast<size_t>(std::lround(fraction * static_cast<double>(by_area.size())));
    for (size_t k = 0; k < drop && k < by_area.size(); ++k) keep_a[by_area[k]] = 0;
  }
  std::vector<int> new_a(pair.a.size(), -1), new_b(pair.b.size(), -1);
  for (size_t i = 0; i < pair.a.size(); ++i)
    if (keep_a[i]) {
      new_a[i] = static_cast<int>(out.a.size());
      out.a.push_back(pair.a[i]);
    }
  std::vector<int> kept_b;
  for (size_t j = 0; j < pair.b.size(); ++j)
    if (keep_b[j]) kept_b.push_back(static_cast<int>(j));
  for (size_t i = kept_b.size(); i > 1; --i) std::swap(kept_b[i - 1], kept_b[rng.below(static_cast<int>(i))]);
  for (int j : kept_b) {
    Box moved = transform_box(out.truth_affine, pair.b[j]);
    moved.cx += gauss() * r.noise;
    moved.cy += gauss() * r.noise * W / H;
    if (r.clip_to_image) {  // what a label of the moved picture holds: the visible part, if at least half
      const double x0 = std::max(0.0, moved.cx - moved.w / 2), x1 = std::min(1.0, moved.cx + moved.w / 2);
      const double y0 = std::max(0.0, moved.cy - moved.h / 2), y1 = std::min(1.0, moved.cy + moved.h / 2);
      if (!(x1 > x0 && y1 > y0) || (x1 - x0) * (y1 - y0) < 0.5 * moved.w * moved.h) continue;
      moved.cx = 0.5 * (x0 + x1), moved.cy = 0.5 * (y0 + y1), moved.w = x1 - x0, moved.h = y1 - y0;
    }
    new_b[j] = static_cast<int>(out.b.size());
    out.b.push_back(moved);
  }
  // B was moved, so the truth affine maps (original) A onto it as well: A and B share the original frame.
  for (const auto& [i, j] : pair.truth)
    if (new_a[i] >= 0 && new_b[j] >= 0) out.truth.emplace_back(new_a[i], new_b[j]);
  for (const auto& [i, j] : pair.strict_truth)
    if (new_a[i] >= 0 && new_b[j] >= 0) out.strict_truth.emplace_back(new_a[i], new_b[j]);
  std::sort(out.truth.begin(), out.truth.end());
  std::sort(out.strict_truth.begin(), out.strict_truth.end());
  return out;
}

std::vector<RegistrationCase> make_cases(const std::vector<LabelPair>& pairs, const MisalignmentRange& range, int count,
                                         std::uint64_t seed, double W, double H) {
  std::vector<RegistrationCase> cases;
  if (pairs.empty()) return cases;
  for (int k = 0; static_cast<int>(cases.size()) < count && k < 20 * count; ++k) {
    auto c = make_case(pairs[(k * 7919u) % pairs.size()], range, seed * 100003 + k, W, H);
    if (c.truth.size() >= 3) cases.push_back(std::move(c));
  }
  return cases;
}

PairScore score_pairs(const RockPairs& found, const RockPairs& truth) {
  PairScore s;
  RockPairs f = found, t = truth;
  std::sort(f.begin(), f.end());
  std::sort(t.begin(), t.end());
  RockPairs common;
  std::set_intersection(f.begin(), f.end(), t.begin(), t.end(), std::back_inserter(common));
  const double tp = static_cast<double>(common.size());
  s.precision = f.empty() ? (t.empty() ? 1.0 : 0.0) : tp / static_cast<double>(f.size());
  s.recall = t.empty() ? 1.0 : tp / static_cast<double>(t.size());
  s.f1 = (s.precision + s.recall) > 0 ? 2 * s.precision * s.recall / (s.precision + s.recall) : 0.0;
  return s;
}

int size_band(const Box& b, double W, double H) {
  const double px = std::sqrt(std::max(0.0, b.w * W) * std::max(0.0, b.h * H));
  return px < 30 ? 0 : px <= 70 ? 1 : 2;
}

const char* size_band_name(int band) {
  static const char* const names[kSizeBands] = {"< 30 px", "30-70 px", "> 70 px"};
  return band >= 0 && band < kSizeBands ? names[band] : "?";
}

void count_by_size_band(const RockPairs& found, const RockPairs& truth, const std::vector<Box>& a, double W, double H,
                        BandCounts* out) {
  RockPairs f = found, t = truth;
  std::sort(f.begin(), f.end());
  std::sort(t.begin(), t.end());
  for (const auto& [i, j] : f) out->found[size_band(a[i], W, H)] += 1;
  for (const auto& [i, j] : t) {
    const int band = size_band(a[i], W, H);
    out->truth[band] += 1;
    if (std::binary_search(f.begin(), f.end(), std::make_pair(i, j))) out->common[band] += 1;
  }
}

double transform_error(const Affine2& found, const Affine2& truth, const std::vector<Box>& a, double aspect) {
  if (a.empty()) return 0;
  std::vector<double> d;
  for (const auto& b : a) {
    const Eigen::Vector2d e = apply(found, b.centre()) - apply(truth, b.centre());
    d.push_back(std::hypot(e.x(), e.y() / aspect));
  }
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2];
}

}  // namespace ipd
