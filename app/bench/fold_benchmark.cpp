#include "app/bench/fold_benchmark.h"

#include <fmt/format.h>
#include <algorithm>
#include <chrono>

namespace ipd {

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

std::string terrain_list(const std::vector<int>& terrains) {
  std::string s;
  for (int t : terrains) s += fmt::format("{}{:02}", s.empty() ? "" : ",", t);
  return s;
}

double ratio(double num, double den) { return den > 0 ? num / den : 1.0; }

void add_bands(const BandCounts& x, BandCounts* into) {
  for (int b = 0; b < kSizeBands; ++b)
    into->found[b] += x.found[b], into->truth[b] += x.truth[b], into->common[b] += x.common[b];
}

}  // namespace

std::vector<Fold> benchmark_folds() { return {{"A", {5, 7, 8}}, {"B", {1, 2}}, {"C", {3, 4}}}; }

std::vector<LabelPair> fold_pairs(const std::vector<LabelPair>& pairs, const Fold& fold, bool validation) {
  std::vector<LabelPair> out;
  for (const auto& p : pairs) {
    const int t = terrain_of(p.file_a);
    const bool held_out = std::find(fold.validation.begin(), fold.validation.end(), t) != fold.validation.end();
    if (held_out == validation) out.push_back(p);
  }
  return out;
}

FoldScore score_fold(const std::vector<RegistrationCase>& cases, const RegistrationOptions& o, double W, double H) {
  FoldScore s;
  s.cases = static_cast<int>(cases.size());
  if (cases.empty()) return s;
  std::vector<double> ms;
  for (const auto& c : cases) {
    const auto start = std::chrono::steady_clock::now();
    const auto r = register_rocks(c.a, c.b, o);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    const RockPairs best = pairs_under_true_affine(c, o);
    s.f1 += score_pairs(r.pairs, c.truth).f1;
    s.ceiling += score_pairs(best, c.truth).f1;
    s.strict_f1 += score_pairs(r.pairs, c.strict_truth).f1;
    s.strict_ceiling += score_pairs(best, c.strict_truth).f1;
    count_by_size_band(r.pairs, c.truth, c.a, W, H, &s.bands);
    count_by_size_band(best, c.truth, c.a, W, H, &s.ceiling_bands);
  }
  const double n = static_cast<double>(cases.size());
  s.f1 /= n, s.ceiling /= n, s.strict_f1 /= n, s.strict_ceiling /= n;
  s.ms_median = median(ms);
  return s;
}

void print_fold_report(const std::vector<LabelPair>& pairs, const std::vector<MisalignmentRange>& tiers, int cases,
                       std::uint64_t seed, double W, double H, double pair_noise_floor, bool bands_on_tuning) {
  RegistrationOptions o;
  o.aspect = W / H;
  o.pair_noise_floor = pair_noise_floor;
  fmt::print("pairing rule: aligned IoU > {}{}\n", o.min_pair_iou,
             pair_noise_floor > 0 ? fmt::format(", or centres within {} of the width ({:.1f} px) with sides within {}x",
                                                pair_noise_floor, pair_noise_floor * W, o.pair_max_size_ratio)
                                  : std::string(" (overlap alone)"));
  fmt::print(
      "Folds: the default method on its tuning terrains and on held-out (validation) terrains, {} cases per tier and "
      "side.\nceiling = the true camera with the method's pairing rule; gap = ceiling - F1. strict = against truth "
      "one-to-one by IoU > {} of the untouched files (independent of the pairing rule).\n\n",
      cases, kStrictTruthIou);
  fmt::print("{:<5} {:<11} {:<15} {:<8} {:>6} {:>7} {:>8} {:>7} {:>8} {:>9} {:>8} {:>7}\n", "fold", "side", "terrains",
             "tier", "cases", "F1", "ceiling", "gap", "strict", "s.ceiling", "s.gap", "ms med");
  std::vector<BandCounts> bands(tiers.size()), ceiling_bands(tiers.size());
  std::vector<double> worst_gap(tiers.size(), 0.0), worst_ms(tiers.size(), 0.0), sum_gap(tiers.size(), 0.0);
  int validation_sides = 0;
  for (const auto& fold : benchmark_folds())
    for (bool validation : {false, true}) {
      const auto subset = fold_pairs(pairs, fold, validation);
      std::vector<int> terrains;
      for (const auto& p : subset) terrains.push_back(terrain_of(p.file_a));
      std::sort(terrains.begin(), terrains.end());
      terrains.erase(std::unique(terrains.begin(), terrains.end()), terrains.end());
      for (size_t t = 0; t < tiers.size(); ++t) {
        const auto s = score_fold(make_cases(subset, tiers[t], cases, seed, W, H), o, W, H);
        fmt::print("{:<5} {:<11} {:<15} {:<8} {:>6} {:>7.4f} {:>8.4f} {:>7.4f} {:>8.4f} {:>9.4f} {:>8.4f} {:>7.3f}\n",
                   fold.name, validation ? "validation" : "tuning", terrain_list(terrains), tiers[t].name, s.cases,
                   s.f1, s.ceiling, s.ceiling - s.f1, s.strict_f1, s.strict_ceiling, s.strict_ceiling - s.strict_f1,
                   s.ms_median);
        if (validation != bands_on_tuning) {
          add_bands(s.bands, &bands[t]);
          add_bands(s.ceiling_bands, &ceiling_bands[t]);
        }
        if (!validation) continue;
        worst_gap[t] = std::max(worst_gap[t], s.ceiling - s.f1);
        sum_gap[t] += s.ceiling - s.f1;
        validation_sides += t == 0;
        worst_ms[t] = std::max(worst_ms[t], s.ms_median);
      }
    }
  fmt::print(
      "\nBy size band of side A's rock (geometric mean of the box's sides, px), {} sides of every fold:\n"
      "recall = true pairs found / true pairs, precision = true pairs found / pairs found.\n\n",
      bands_on_tuning ? "tuning" : "validation");
  fmt::print("{:<8} {:<9} {:>7} {:>8} {:>8} {:>10} {:>10}\n", "tier", "band", "true", "recall", "prec", "ceil.recall",
             "ceil.prec");
  for (size_t t = 0; t < tiers.size(); ++t)
    for (int b = 0; b < kSizeBands; ++b) {
      const auto& m = bands[t];
      const auto& c = ceiling_bands[t];
      fmt::print("{:<8} {:<9} {:>7.0f} {:>8.4f} {:>8.4f} {:>10.4f} {:>10.4f}\n", tiers[t].name, size_band_name(b),
                 m.truth[b], ratio(m.common[b], m.truth[b]), ratio(m.common[b], m.found[b]),
                 ratio(c.common[b], c.truth[b]), ratio(c.common[b], c.found[b]));
    }
  // The goals on the validation terrains: gap <= 0.01 (small misalignments) or 0.02 (others), recall of the
  // rocks under 30 px >= 0.97, median <= 0.5 ms per pair.
  fmt::print("\n");
  for (size_t t = 0; t < tiers.size(); ++t) {
    const double gap_goal = tiers[t].name == "small" ? 0.01 : 0.02;
    const double small_recall = ratio(bands[t].common[0], bands[t].truth[0]);
    auto verdict = [](bool met) { return met ? "met" : "NOT met"; };
    // The recall goal is judged on the validation sides only: with the tuning sides' bands it is just shown.
    const std::string recall = bands_on_tuning ? fmt::format("recall < 30 px on the tuning sides {:.4f}", small_recall)
                                               : fmt::format("recall < 30 px {:.4f} (goal 0.97: {})", small_recall,
                                                             verdict(small_recall >= 0.97));
    // Judged on the worst fold; the folds' mean (every case of every validation side) is shown beside it, as a
    // 300-case side's gap moves by several thousandths with the seed.
    fmt::print(
        "  {}: worst validation gap {:.4f} (goal {}: {}; mean of the folds {:.4f}), {}, worst median {:.3f} ms/pair "
        "(goal 0.5: {})\n",
        tiers[t].name, worst_gap[t], gap_goal, verdict(worst_gap[t] <= gap_goal),
        validation_sides > 0 ? sum_gap[t] / validation_sides : 0.0, recall, worst_ms[t], verdict(worst_ms[t] <= 0.5));
  }
}

}  // namespace ipd
