// `ipd bench registration --ipd-check`: what the pairing rule does to the IPD itself, on layouts whose true
// pairs are known.
//
// Each benchmark case (POLAR-Sim label pairs, a known misalignment, app/bench/registration_benchmark.h) gets a
// simulated detector on both sides: every rock is predicted with its box moved and resized by a few pixels of
// localisation error, the same in pixels whatever the rock's size, so small rocks score lower and differ more
// between the sides, as they do in real detectors. The IPD over the true pairs is the reference; the IPD over
// the pairs found with overlap alone (noise floor 0, the default) and with a noise floor, under the true camera
// and after the default method's registration, says which rule moves the number towards it.
#pragma once

#include <cstdint>
#include <vector>

#include "app/bench/registration_benchmark.h"

namespace ipd {

// Per-rock performance values of one side under the simulated detector: the best IoU of the rock's box with its
// predicted box (centre off by `sigma_px` pixels per axis, each side scaled by 1 +- `extent_sigma`, normal draws).
// Deterministic for the seed.
std::vector<double> simulated_performance(const std::vector<Box>& gt, double image_w, double image_h,
                                          std::uint64_t seed, double sigma_px = 3.0, double extent_sigma = 0.1);

struct IpdCheck {
  double sum = 0;  // sum of |perf_A - perf_B| over the counted pairs of every case
  long pairs = 0;
  double ipd() const { return pairs ? sum / static_cast<double>(pairs) : 0.0; }
};

// Adds one case's pairs to `into` (the product's counting rule, scene_contribution).
void add_to_ipd(const RockPairs& pairs, const std::vector<double>& perf_a, const std::vector<double>& perf_b,
                IpdCheck* into);

// Prints, per tier, the IPD on the true pairs and on the pairs of overlap alone and of the rule with
// `noise_floor` (fraction of the width), under the true camera and after the default method's registration,
// with their distance to the true-pair IPD.
void print_ipd_check(const std::vector<LabelPair>& pairs, const std::vector<MisalignmentRange>& tiers, int cases,
                     std::uint64_t seed, double image_w, double image_h, double noise_floor);

}  // namespace ipd
