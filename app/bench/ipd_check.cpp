#include "app/bench/ipd_check.h"

#include <fmt/format.h>
#include <cmath>

#include "core/ipd/ipd.h"
#include "core/registration/pairing.h"
#include "core/registration/registration_frame.h"

namespace ipd {

std::vector<double> simulated_performance(const std::vector<Box>& gt, double W, double H, std::uint64_t seed,
                                          double sigma_px, double extent_sigma) {
  detail::Rng rng(seed * 2654435761u + 11);
  auto gauss = [&]() {  // Box-Muller
    const double u1 = std::max(rng.uniform(), 1e-300), u2 = rng.uniform();
    return std::sqrt(-2 * std::log(u1)) * std::cos(2 * M_PI * u2);
  };
  std::vector<Box> pred;
  pred.reserve(gt.size());
  for (const Box& g : gt) {
    Box p = g;
    p.cx += gauss() * sigma_px / W;
    p.cy += gauss() * sigma_px / H;
    p.w *= std::max(0.1, 1 + extent_sigma * gauss());
    p.h *= std::max(0.1, 1 + extent_sigma * gauss());
    pred.push_back(p);
  }
  return performance_values(gt, pred).value;
}

void add_to_ipd(const RockPairs& pairs, const std::vector<double>& perf_a, const std::vector<double>& perf_b,
                IpdCheck* into) {
  const SceneIpd s = scene_contribution("", pairs, {}, {}, perf_a, perf_b);
  into->sum += s.sum_abs_diff;
  into->pairs += s.pairs;
}

void print_ipd_check(const std::vector<LabelPair>& pairs, const std::vector<MisalignmentRange>& tiers, int cases,
                     std::uint64_t seed, double W, double H, double noise_floor) {
  const double aspect = W / H;
  fmt::print(
      "IPD on known pairs: a simulated detector (3 px localisation error per axis, 10% extent error) on both sides "
      "of {} cases per tier; IPD = mean |perf_A - perf_B| over the pairs. 'overlap' pairs by aligned IoU > 0.1 "
      "alone (noise floor 0, the default), 'floor' also near misses within {} of the width ({:.1f} px).\n\n",
      cases, noise_floor, noise_floor * W);
  fmt::print("{:<8} {:<22} {:>8} {:>8} {:>10}\n", "tier", "pairs", "count", "IPD", "IPD - true");
  for (const auto& tier : tiers) {
    RegistrationOptions fair, overlap;
    fair.aspect = aspect;
    overlap.aspect = aspect;
    overlap.pair_noise_floor = 0;
    fair.pair_noise_floor = noise_floor;
    IpdCheck truth, fair_true_camera, overlap_true_camera, fair_found, overlap_found;
    const auto list = make_cases(pairs, tier, cases, seed, W, H);
    for (size_t k = 0; k < list.size(); ++k) {
      const auto& c = list[k];
      const auto perf_a = simulated_performance(c.a, W, H, seed * 1000003 + 2 * k);
      const auto perf_b = simulated_performance(c.b, W, H, seed * 1000003 + 2 * k + 1);
      add_to_ipd(c.truth, perf_a, perf_b, &truth);
      add_to_ipd(pair_aligned_boxes(c.truth_affine, c.a, c.b, pairing_rule(fair)), perf_a, perf_b, &fair_true_camera);
      add_to_ipd(pair_aligned_boxes(c.truth_affine, c.a, c.b, pairing_rule(overlap)), perf_a, perf_b,
                 &overlap_true_camera);
      add_to_ipd(register_rocks(c.a, c.b, fair).pairs, perf_a, perf_b, &fair_found);
      add_to_ipd(register_rocks(c.a, c.b, overlap).pairs, perf_a, perf_b, &overlap_found);
    }
    auto row = [&](const char* name, const IpdCheck& x) {
      fmt::print("{:<8} {:<22} {:>8} {:>8.4f} {:>+10.4f}\n", tier.name, name, x.pairs, x.ipd(), x.ipd() - truth.ipd());
    };
    row("true pairs", truth);
    row("overlap, true camera", overlap_true_camera);
    row("floor, true camera", fair_true_camera);
    row("overlap, found", overlap_found);
    row("floor, found", fair_found);
  }
}

}  // namespace ipd
