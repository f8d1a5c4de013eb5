// Auditing one scene's rock pairs: how well each pair agrees with the scene's affine, and which pairs look
// wrong. Also the pair numbers people see (GUI and figures share them).
#pragma once

#include <string>
#include <vector>

#include "core/geometry/geometry.h"
#include "core/registration/pairing.h"
#include "core/registration/registration.h"

namespace ipd {

struct AuditOptions {
  // A pair is suspect when its residual exceeds max(residual_factor × the scene's median residual,
  // min_residual_rock_fraction × the median rock size): far off the typical fit, yet never for a
  // sub-rock wobble in a near-perfect scene.
  double residual_factor = 3.0;
  double min_residual_rock_fraction = 0.25;
  double min_size_ratio = 0.5, max_size_ratio = 2.0;  // aligned A box size / B box size (linear)
  // Boxes that do not overlap are suspect only when their centres are farther apart than this (fraction of the
  // image width): closer, a pairing rule with this noise floor pairs them as a near miss of label noise.
  double noise_floor = PairingRule().noise_floor;

  std::string validate() const;  // empty when usable
};

struct PairAudit {
  int a = -1, b = -1;      // rock indices (as in the pairs given)
  double residual_px = 0;  // |affine(centre of a) - centre of b|, in pixels
  double aligned_iou = 0;  // IoU of a's box moved by the affine with b's box
  double size_ratio = 1;   // sqrt(area of the aligned a box / area of b's box)
  bool suspect = false;
  bool checked = false;  // judged correct by hand (review_state.h): then never suspect, `why` still says why
  // "residual", "size", "no overlap" (beyond the noise floor; comma-separated), empty when not suspect
  std::string why;
};

struct SceneAudit {
  // A hand-paired scene whose registration is not computed yet: no affine to audit against, so no pair
  // audits and no residuals (never a number measured against a made-up affine).
  bool waits_for_registration = false;
  std::vector<PairAudit> pairs;    // in the order of the pairs given
  double typical_residual_px = 0;  // median residual
  double suspect_residual_px = 0;  // the threshold that was used
  int suspects = 0;
};

// `b_from_a` maps normalised A coordinates onto B's (RegistrationReport::affine); image_w/h give pixels.
// Throws std::invalid_argument for bad options or pair indices outside the box lists.
SceneAudit audit_pairs(const std::vector<Box>& a, const std::vector<Box>& b, const RockPairs& pairs,
                       const Affine2& b_from_a, int image_w, int image_h, const AuditOptions& options = {});

// The audit of the pair (a, b), or null: looked up through an index by A rock (pairs are one-to-one), since a
// view that scanned the audit once per pair spent 0.1 s a frame on a scene of 20,000 pairs.
class PairAuditIndex {
 public:
  explicit PairAuditIndex(const SceneAudit& audit);
  const PairAudit* find(int a, int b) const;

 private:
  std::vector<const PairAudit*> by_a_;
};

// Per rock of one side, the number its pair is shown with, 0 when unpaired. Stable: a pair's number is
// its left rock's 1-based index, so unpairing pair 3 never renumbers 4, 5, … (`pairs` are (left, right)).
std::vector<int> pair_numbers(const RockPairs& pairs, size_t rocks, bool left_side);

}  // namespace ipd
