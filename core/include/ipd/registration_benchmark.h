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

#include "ipd/geometry.h"
#include "ipd/registration.h"

namespace ipd {

struct LabelPair {
  std::string file_a, file_b;
  std::vector<Box> a, b;  // rock class only
  RockPairs truth;        // IoU assignment of the untouched files
};

// Pairs of files of one view (terrain, camera, light, left/right) at different sun azimuths, one exposure
// each; only pairs with at least `min_true_pairs` true pairs. Sorted by file names.
std::vector<LabelPair> polar_sim_label_pairs(const std::string& labels_root, int min_true_pairs = 5);

struct MisalignmentRange {
  std::string name;
  double max_rotation_deg, min_scale, max_scale, max_shear, max_shift, hidden, noise;  // shift/noise: of width
};
MisalignmentRange small_misalignment();
MisalignmentRange large_misalignment();

struct RegistrationCase {
  std::vector<Box> a, b;
  Affine2 truth_affine;  // normalised A -> normalised B
  RockPairs truth;
  std::string source;
};

// Deterministic for (pair, range, seed). Pixel geometry of 1936 x 1216 (POLAR) for angles and shifts.
RegistrationCase make_case(const LabelPair& pair, const MisalignmentRange& range, std::uint64_t seed,
                           double image_w = 1936, double image_h = 1216);

struct PairScore {
  double precision = 0, recall = 0, f1 = 0;
};
PairScore score_pairs(const RockPairs& found, const RockPairs& truth);

// Median over A's rocks of the distance between where the found and the true affine put them, as a
// fraction of the image width (pixels / width).
double transform_error(const Affine2& found, const Affine2& truth, const std::vector<Box>& a, double aspect);

}  // namespace ipd
