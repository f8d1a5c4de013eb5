// A demo of renderer settings with a known answer: a reference domain `real` and N variants rendered with one
// shading parameter (`ambient`, the shading's ambient term) at evenly spaced values in [0, 1]. Labels only: every
// domain shows the same rocks (rows shuffled per domain, so pairing needs registration); the detector `det-real`
// (trained on real) finds each rock in a variant as in the reference, its box further off the more the variant's
// ambient term is from the true one, plus noise of its own. So the expected IPD(real, variant) rises with
// |ambient − true ambient|, is lowest at the true best variant, and the variants next to it are within the noise.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace ipd {

struct VariantStudyOptions {
  int variants = 9;  // N >= 2
  int scenes = 40;
  int min_rocks = 9, max_rocks = 18;  // per scene
  int width = 960, height = 600;
  std::uint64_t seed = 7;
  double true_ambient = 0.375;  // the variant nearest this value is the true best
  // How far a variant's boxes drift per unit of |ambient − true_ambient| (a share of the rock's size), and the
  // noise each variant's boxes have of their own (the same share).
  double drift = 0.15, noise = 0.06;

  std::string validate() const;
  void check() const;
};

// Variant k's ambient term, k = 0 .. variants - 1: k / (variants - 1).
double variant_ambient(const VariantStudyOptions& o, int k);
// The variant's domain name: "ambient-040" for 0.40.
std::string variant_domain(const VariantStudyOptions& o, int k);
// The index of the true best variant (the ambient term nearest true_ambient; the lower one on a tie).
int true_best_variant(const VariantStudyOptions& o);

// study.yaml of the study with the reference and the first `count` variants (domains as a mapping with each
// variant's params, the model, the image size).
std::string variant_study_yaml(const VariantStudyOptions& o, int count);

// Writes the study into `dir`, a new or empty folder (labels, predictions, then study.yaml and README.md:
// demo_files.h). Throws IoError on failure.
void write_variant_study(const std::string& dir, const VariantStudyOptions& options = {});

}  // namespace ipd
