// Registration cases with a known answer, built from real label pairs, and the measures of a result.
//
// Two POLAR-Sim annotations of one camera view under different sun azimuths label the same rocks separately
// (different rocks hidden by shadows, different box extents). Their true pairing is the IoU assignment of the
// untouched files (the camera did not move). A case hides some rocks on each side, applies a known affine and
// centre noise to side B, and shuffles B's rows.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/geometry/geometry.h"
#include "core/registration/pairing.h"
#include "core/registration/registration.h"

namespace ipd {

struct LabelPair {
  std::string file_a, file_b;
  std::vector<Box> a, b;  // rock class only
  RockPairs truth;        // IoU > kTruthIou assignment of the untouched files
  // Truth that no method's pairing rule defines: one-to-one by IoU > kStrictTruthIou of the untouched files,
  // so a looser rule cannot raise its own score by pairing what merely touches.
  RockPairs strict_truth;
};
inline constexpr double kStrictTruthIou = 0.3;
// The true pairs are the untouched files' one-to-one IoU > 0.1 assignment, by overlap alone: the camera did not
// move, so no noise floor is needed, and a pairing rule with one is scored against a truth it does not define.
inline constexpr double kTruthIou = 0.1;
// The overlap-only rule the truths are made with (no near misses).
PairingRule overlap_only(double min_iou);

// The terrain number of a POLAR-Sim label file ("05_A_off_30_L_1024.txt" -> 5); -1 when the name has none.
int terrain_of(const std::string& file);

// Pairs of files of one view (terrain, camera, light, left/right) at different sun azimuths, one exposure
// each; only pairs with at least `min_true_pairs` true pairs. Sorted by file names.
std::vector<LabelPair> polar_sim_label_pairs(const std::string& labels_root, int min_true_pairs = 5);

struct MisalignmentRange {
  std::string name;
  double max_rotation_deg, min_scale, max_scale, max_shear, max_shift, hidden, noise;  // shift/noise: of width
  // Rocks leave the picture: the moved side's boxes are clipped to [0, 1] and rocks less than half visible
  // are dropped, as a real label file would have them.
  bool clip_to_image = true;
  // Unequal counts: side A (the "real" labels) loses its smallest rocks, a fraction drawn in [min, max].
  double drop_smallest_min = 0, drop_smallest_max = 0;
};
MisalignmentRange small_misalignment();
MisalignmentRange large_misalignment();
// Small misalignment, but A misses its smallest 30-50% of rocks (hand-labelled real GT vs synthetic GT).
MisalignmentRange unequal_counts();
// small, large, unequal.
std::vector<MisalignmentRange> benchmark_tiers();

struct RegistrationCase {
  std::vector<Box> a, b;
  Affine2 truth_affine;  // normalised A -> normalised B
  RockPairs truth;
  RockPairs strict_truth;  // LabelPair::strict_truth of the kept rocks
  std::string source;
};

// Deterministic for (pair, range, seed). Pixel geometry of 1936 x 1216 (POLAR) for angles and shifts.
RegistrationCase make_case(const LabelPair& pair, const MisalignmentRange& range, std::uint64_t seed,
                           double image_w = 1936, double image_h = 1216);

// `count` cases of `range` with at least three true pairs (fewer leave nothing to register), drawn in turn
// from `pairs` with successive seeds (at most 20 * count tries).
std::vector<RegistrationCase> make_cases(const std::vector<LabelPair>& pairs, const MisalignmentRange& range, int count,
                                         std::uint64_t seed, double image_w, double image_h);

// The floor of transform error: the least-squares affine on the true pairs' centres (image coordinates);
// false when there are fewer than three true pairs or they are degenerate.
bool least_squares_on_truth(const RegistrationCase& c, Affine2* out);
// The ceiling of pairing: the true affine, then the methods' own pairing rule (pairing_rule(o), o.aspect the
// image's).
RockPairs pairs_under_true_affine(const RegistrationCase& c, const RegistrationOptions& o);

// A synthetic label pair of n rocks spread over the picture (sizes shrinking as 1/sqrt(n)), side B a
// re-labelling (centre and size noise); for timing registration against the rock count.
LabelPair synthetic_label_pair(int n, std::uint64_t seed);

struct PairScore {
  double precision = 0, recall = 0, f1 = 0;
};
PairScore score_pairs(const RockPairs& found, const RockPairs& truth);

// Size bands of a rock, by the geometric mean of its box's sides in pixels: < 30, 30-70, > 70. A few pixels of
// label noise cost a small box much more IoU than a large one, so pairing is scored per band.
inline constexpr int kSizeBands = 3;
int size_band(const Box& b, double image_w, double image_h);
const char* size_band_name(int band);
// Per band of side A's rock: pairs found, true pairs and pairs both found and true (added to).
struct BandCounts {
  double found[kSizeBands] = {}, truth[kSizeBands] = {}, common[kSizeBands] = {};
};
void count_by_size_band(const RockPairs& found, const RockPairs& truth, const std::vector<Box>& a, double image_w,
                        double image_h, BandCounts* out);

// Median over A's rocks of the distance between where the found and the true affine put them, as a
// fraction of the image width (pixels / width).
double transform_error(const Affine2& found, const Affine2& truth, const std::vector<Box>& a, double aspect);

}  // namespace ipd
