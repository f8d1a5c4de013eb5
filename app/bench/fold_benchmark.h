// `ipd bench registration --folds`: the default method scored on terrains its constants were not chosen on.
//
// The method's constants were chosen by ablation on the benchmark's own cases, so a score on those cases says
// how well they were fitted, not how well they carry over. Each fold holds some POLAR-Sim terrains out
// (validation) and scores tuning and validation terrains apart, each against its ceiling: the true camera with
// the method's own pairing rule. A second truth, one-to-one by IoU > 0.3 of the untouched files, is defined
// independently of that rule, so a looser rule cannot raise its own score.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "app/bench/registration_benchmark.h"

namespace ipd {

struct Fold {
  std::string name;
  std::vector<int> validation;  // terrain numbers held out; the others are the tuning terrains
};
// Every terrain is held out once: {05, 07, 08}, {01, 02}, {03, 04}.
std::vector<Fold> benchmark_folds();

// One tier on one side of a fold: the default method's F1 and its ceiling's, against both truths.
struct FoldScore {
  int cases = 0;
  double f1 = 0, ceiling = 0, strict_f1 = 0, strict_ceiling = 0, ms_median = 0;
  BandCounts bands, ceiling_bands;  // against `truth`, by side A's rock size
};
// `o`: the default method's options with the image's aspect (and, to score another pairing rule, its floor).
FoldScore score_fold(const std::vector<RegistrationCase>& cases, const RegistrationOptions& o, double image_w,
                     double image_h);

// The label pairs whose terrain is (validation = true) or is not in `fold.validation`.
std::vector<LabelPair> fold_pairs(const std::vector<LabelPair>& pairs, const Fold& fold, bool validation);

// Prints the fold table (per fold, tier and side: F1, ceiling, gap, both truths) and the size-band table
// (validation sides of every fold together), with the goals' verdicts. `pair_noise_floor`: the pairing rule's
// (RegistrationOptions), for the method and its ceiling alike. `bands_on_tuning`: the size-band table counts the
// tuning sides instead, where a pairing rule is chosen (the goals' verdicts stay the validation sides').
void print_fold_report(const std::vector<LabelPair>& pairs, const std::vector<MisalignmentRange>& tiers, int cases,
                       std::uint64_t seed, double image_w, double image_h, double pair_noise_floor = 0,
                       bool bands_on_tuning = false);

}  // namespace ipd
