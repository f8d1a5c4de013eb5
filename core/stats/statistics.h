// Statistics for publishable IPD numbers: scene-level (cluster) bootstrap of a pooled mean, percentile
// intervals, a paired comparison of two renderers (paired bootstrap + sign-flip permutation test), quantiles
// and Spearman's rank correlation. Pure functions over plain structs; no study, no I/O.
//
// Rocks of one scene are correlated, so every resampling works on whole scenes: a scene enters as its
// (sum of |diff|, number of pairs) and a resample's IPD is the pooled Σsum / Σcount. Resampling costs
// O(scenes) per resample, never O(rocks).
//
// Randomness comes from an IndexSource. SeededIndexSource derives its stream from (seed, key) — e.g. the
// cell "model|a|b" — so results don't depend on which thread computes which cell. Tests inject fixed draws
// with FixedIndexSource.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace ipd {

// "No number" (no pairs, no predictions, an empty bin): written n/a or –, and null in JSON.
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// One scene's contribution to a pooled IPD.
struct SceneSum {
  double sum = 0;  // Σ |perf_a - perf_b| over the scene's counted pairs
  long count = 0;  // number of counted pairs
};

// Σsum / Σcount; NaN when there are no pairs.
double pooled_mean(const std::vector<SceneSum>& scenes);

// A point estimate with its bootstrap percentile interval and standard error; NaN fields when undefined
// (no pairs, bootstrap off, or fewer than two usable resamples).
struct Interval {
  double estimate = std::numeric_limits<double>::quiet_NaN();
  double low = std::numeric_limits<double>::quiet_NaN();
  double high = std::numeric_limits<double>::quiet_NaN();
  double se = std::numeric_limits<double>::quiet_NaN();  // standard deviation of the resampled estimates
  int resamples = 0;  // resamples that gave a number (a resample of scenes without pairs gives none)
  bool has_interval() const { return low == low && high == high; }
};

// Uniform integers for resampling. draw() fills all of *out (its size is the caller's) with values in
// [0, bound). One call = one resample (bootstrap: bound = scenes) or one permutation (bound = 2).
class IndexSource {
 public:
  virtual ~IndexSource() = default;
  virtual void draw(std::uint32_t bound, std::vector<std::uint32_t>* out) = 0;
};

// The default source: a splitmix64 stream seeded from `seed` and a key naming what is resampled.
class SeededIndexSource : public IndexSource {
 public:
  SeededIndexSource(std::uint64_t seed, std::string_view key);
  void draw(std::uint32_t bound, std::vector<std::uint32_t>* out) override;
  std::uint64_t next();  // the raw 64-bit stream

 private:
  std::uint64_t state_;
};

// Replays given draws in order (for tests); throws std::logic_error when they run out or a draw has the
// wrong length or a value >= bound.
class FixedIndexSource : public IndexSource {
 public:
  explicit FixedIndexSource(std::vector<std::vector<std::uint32_t>> draws) : draws_(std::move(draws)) {}
  void draw(std::uint32_t bound, std::vector<std::uint32_t>* out) override;

 private:
  std::vector<std::vector<std::uint32_t>> draws_;
  size_t next_ = 0;
};

struct BootstrapOptions {
  int resamples = 2000;  // 0: no bootstrap (intervals stay NaN); 1 is refused (one resample has no spread)
  double level = 0.95;   // central interval, in (0, 1)
  std::uint64_t seed = 0;
  // Empty when usable; otherwise what is wrong, in one sentence.
  std::string validate() const;
};

// The q-quantile (q in [0, 1]) of values, linear interpolation between order statistics (numpy's default);
// NaN for an empty vector.
double quantile(std::vector<double> values, double q);
// K bins of (roughly) equal count: the K - 1 inner edges, quantiles k/K of values.
std::vector<double> quantile_edges(const std::vector<double>& values, int bins);

// Cluster bootstrap of the pooled mean: `resamples` times draw scenes.size() scenes with replacement.
// The interval is the percentile interval of the resampled pooled means at `level`.
Interval bootstrap_pooled_mean(const std::vector<SceneSum>& scenes, const BootstrapOptions& options,
                               IndexSource& draws);
// Same, with SeededIndexSource(options.seed, key).
Interval bootstrap_pooled_mean(const std::vector<SceneSum>& scenes, const BootstrapOptions& options,
                               std::string_view key);

// One scene seen from a reference domain against two others (ref-a, ref-b), for a paired comparison.
struct PairedScene {
  SceneSum a, b;  // the scene's contribution to IPD(ref, a) and IPD(ref, b)
  // restricted to the ref rocks paired in both domains (common_a.count == common_b.count)
  SceneSum common_a, common_b;
};

struct CompareOptions {
  BootstrapOptions bootstrap;
  int permutations = 2000;  // sign-flip permutations for the p-value; 0: no test (p = NaN)
  std::string validate() const;
};

struct Comparison {
  double ipd_a = 0, ipd_b = 0;  // pooled over the scenes given
  Interval delta;               // Δ = IPD(ref, a) - IPD(ref, b), paired bootstrap interval
  double p_value = std::numeric_limits<double>::quiet_NaN();
  double delta_common = std::numeric_limits<double>::quiet_NaN();  // Δ over ref rocks paired in both
  long pairs_a = 0, pairs_b = 0, pairs_common = 0;
  int scenes = 0, permutations = 0;
  bool exact_p = false;  // every one of the 2^scenes swap patterns was counted (p = share reaching |Δ|)
};

// Δ with a paired bootstrap (the same resampled scenes for both IPDs) and a permutation test that swaps
// each scene's (a, b) contributions with probability ½: p = (1 + #{|Δ*| >= |Δ|}) / (N + 1).
Comparison compare_paired(const std::vector<PairedScene>& scenes, const CompareOptions& options,
                          IndexSource& resample_draws, IndexSource& permutation_draws);
// Same, with seeded sources derived from (options.bootstrap.seed, key). When 2^scenes <= permutations the
// permutation test enumerates every swap pattern instead (exact_p; p = #{|Δ*| >= |Δ|} / 2^scenes).
Comparison compare_paired(const std::vector<PairedScene>& scenes, const CompareOptions& options, std::string_view key);

// Spearman's rank correlation (ties get their average rank, then Pearson on ranks); NaN when fewer than
// two points, different lengths, or a constant variable.
double spearman(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace ipd
