#include "core/session/audit.h"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ipd {

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  const size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + mid, v.end());
  if (v.size() % 2) return v[mid];
  const double hi = v[mid];
  return 0.5 * (hi + *std::max_element(v.begin(), v.begin() + mid));
}

}  // namespace

std::string AuditOptions::validate() const {
  if (!(residual_factor >= 1)) return fmt::format("residual_factor must be at least 1, got {}", residual_factor);
  if (!(noise_floor >= 0)) return fmt::format("noise_floor must be >= 0, got {}", noise_floor);
  if (!(min_residual_rock_fraction >= 0))
    return fmt::format("min_residual_rock_fraction must be >= 0, got {}", min_residual_rock_fraction);
  if (!(min_size_ratio > 0 && min_size_ratio <= 1 && max_size_ratio >= 1))
    return fmt::format("size ratios must satisfy 0 < min <= 1 <= max, got {} and {}", min_size_ratio, max_size_ratio);
  return {};
}

SceneAudit audit_pairs(const std::vector<Box>& a, const std::vector<Box>& b, const RockPairs& pairs,
                       const Affine2& b_from_a, int image_w, int image_h, const AuditOptions& o) {
  if (const std::string problem = o.validate(); !problem.empty()) throw std::invalid_argument("audit: " + problem);
  const double w = image_w > 0 ? image_w : 1, h = image_h > 0 ? image_h : 1;
  SceneAudit out;
  std::vector<double> residuals, sizes;
  for (const auto& [i, j] : pairs) {
    if (i < 0 || i >= static_cast<int>(a.size()) || j < 0 || j >= static_cast<int>(b.size()))
      throw std::invalid_argument(
          fmt::format("audit: pair ({}, {}) outside {} and {} rocks", i, j, a.size(), b.size()));
    PairAudit p;
    p.a = i;
    p.b = j;
    const Box moved = transform_box(b_from_a, a[i]);
    const Eigen::Vector2d c = apply(b_from_a, a[i].centre());
    p.residual_px = std::hypot((c.x() - b[j].cx) * w, (c.y() - b[j].cy) * h);
    p.aligned_iou = iou(moved, b[j]);
    p.size_ratio = b[j].area() > 0 ? std::sqrt(moved.area() / b[j].area()) : 0;
    residuals.push_back(p.residual_px);
    sizes.push_back(std::sqrt(b[j].w * w * b[j].h * h));
    out.pairs.push_back(p);
  }
  out.typical_residual_px = median(residuals);
  out.suspect_residual_px =
      std::max(o.residual_factor * out.typical_residual_px, o.min_residual_rock_fraction * median(sizes));
  for (auto& p : out.pairs) {
    std::vector<const char*> why;
    if (p.residual_px > out.suspect_residual_px) why.push_back("residual");
    if (p.size_ratio < o.min_size_ratio || p.size_ratio > o.max_size_ratio) why.push_back("size");
    if (p.aligned_iou <= 0 && p.residual_px >= o.noise_floor * w) why.push_back("no overlap");
    for (size_t k = 0; k < why.size(); ++k) p.why += (k ? ", " : "") + std::string(why[k]);
    p.suspect = !why.empty();
    out.suspects += p.suspect;
  }
  return out;
}

std::vector<int> pair_numbers(const RockPairs& pairs, size_t rocks, bool left_side) {
  std::vector<int> number(rocks, 0);
  for (const auto& [l, r] : pairs) {
    const int idx = left_side ? l : r;
    if (idx >= 0 && idx < static_cast<int>(rocks)) number[idx] = l + 1;
  }
  return number;
}

PairAuditIndex::PairAuditIndex(const SceneAudit& audit) {
  for (const PairAudit& p : audit.pairs) {
    if (p.a < 0) continue;
    if (static_cast<size_t>(p.a) >= by_a_.size()) by_a_.resize(p.a + 1, nullptr);
    by_a_[p.a] = &p;
  }
}

const PairAudit* PairAuditIndex::find(int a, int b) const {
  if (a < 0 || static_cast<size_t>(a) >= by_a_.size() || !by_a_[a] || by_a_[a]->b != b) return nullptr;
  return by_a_[a];
}

}  // namespace ipd
