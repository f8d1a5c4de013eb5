// The statistics of ipd/statistics.h applied to a study's cross table: intervals on every cell, the
// per-scene distribution, a paired renderer comparison, breakdowns by rock size / region / confidence.
// Everything is computed from CrossTable::cells[*].per_scene (and the labels for rock properties), so it
// agrees with the table by construction.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/ipd/ipd.h"
#include "core/stats/statistics.h"

namespace ipd {

// The cell's scenes as (Σ|diff|, pairs), in per_scene order.
std::vector<SceneSum> scene_sums(const TableCell& cell);
// "model|a|b": the key of a cell's random stream.
std::string cell_key(const TableCell& cell);

// Fills ci_low / ci_high / se of every cell that has pairs (cells are computed in parallel; each cell's
// stream comes from (options.seed, cell_key), so the output is the same for any thread count).
void add_confidence_intervals(CrossTable* table, const BootstrapOptions& options, int threads = 0);

// Per-scene IPD of one cell (scenes without pairs left out): quartiles and the worst scenes.
struct SceneDistribution {
  int scenes = 0;
  double min = 0, q1 = 0, median = 0, q3 = 0, max = 0;  // NaN when scenes == 0
  std::vector<std::pair<std::string, double>> worst;    // (stem, IPD), highest first
};
SceneDistribution scene_distribution(const TableCell& cell, int worst = 5);

// Which renderer is closer to a reference domain, for one model.
struct RendererComparison {
  std::string model, ref, a, b;
  Comparison result;
  std::vector<std::string> scenes;  // stems present in all three domains
};
// Uses the table's (ref, a) and (ref, b) cells (in either order); throws StudyError when a cell is missing
// or the model has no predictions for one of the domains.
RendererComparison compare_renderers(const CrossTable& table, const std::string& model, const std::string& ref,
                                     const std::string& a, const std::string& b, const CompareOptions& options);
// The significance level of a comparison's verdict when none is given (ipd compare's sentence, ipd rank's --level).
constexpr double kSignificanceLevel = 0.05;
// The verdict rule of a comparison at significance level `alpha`, given its p-value `p` (the comparison's own, or
// one corrected for multiple tests): a difference is significant when p < alpha and the paired interval excludes
// 0 (or there is no interval). No p-value (no test run) is never significant.
bool significant_difference(const Comparison& c, double p, double alpha);
// The significance level that goes with an interval of `interval_level` (0.05 for 95%): a verdict that asks the test
// and the interval to agree asks both at one level.
double level_of_interval(double interval_level);
// One plain sentence, e.g. "principled is closer to real than hapke for det-real: ΔIPD = -0.0896
// [-0.112, -0.069], p = 0.0005, 40 scenes"; "no significant difference ..." when p >= alpha or the
// interval contains 0.
std::string comparison_sentence(const RendererComparison& c, double alpha = kSignificanceLevel);
// `v` with `digits` decimals and a typographic minus (U+2212), as in print and in comparison_sentence;
// never a minus on a number that rounds to zero ("0.0000", not "−0.0000"); "n/a" for NaN.
std::string minus_number(double v, int digits);

// IPD of one cell broken down by a property of the reference (the cell's first domain, `a`) rock.
enum class BreakdownBy { kSize, kRegion, kConfidence };
bool parse_breakdown_by(const std::string& name, BreakdownBy* out);
const char* to_string(BreakdownBy by);

// The most quantile bins a breakdown takes, printed (ipd breakdown) or drawn (ipd figure breakdown) alike: a
// figure draws a row per bin, and 20 rows still fit a column at 8 pt; past that a bin of a study the size of
// the demo (about 80 pairs a cell) holds too few pairs from too few scenes for an interval.
constexpr int kMaxBreakdownBins = 20;

struct BreakdownOptions {
  BreakdownBy by = BreakdownBy::kSize;
  int bins = 4;  // size and confidence: quantile bins (1 to kMaxBreakdownBins); region is always a 3x3 grid
  BootstrapOptions bootstrap;
  std::string validate() const;
};

struct BreakdownBin {
  std::string label;         // e.g. "120-450 px²", "top-left", "0.31-0.58", "no detection"
  double low = 0, high = 0;  // the bin's range of the property (region: the row-major cell number twice)
  Interval ipd;
  long pairs = 0;
  int scenes = 0;  // scenes with at least one pair in this bin
};

struct CellBreakdown {
  std::string model, trained_on, a, b;
  BreakdownBy by = BreakdownBy::kSize;
  std::vector<BreakdownBin> bins;
};

// What a breakdown of a cell without rock pairs (no rocks, or none paired) says instead of its bins.
constexpr const char* kNoRockPairsToBin = "No rock pairs in this cell (no rocks, or none paired): nothing to bin.";

// Needs the cell's per_scene[*].counted and the labels it came from. A cell without counted pairs has no bins;
// by confidence, pairs none of whose rocks was detected have only the "no detection" bin. Size is the ref box's area in
// pixels (image size from study.yaml or the domain's pictures, else normalised area × 10⁶); confidence is that of the
// ref rock's best-IoU prediction ("no detection" bin when nothing overlaps).
CellBreakdown breakdown_cell(const StudyLabels& labels, const TableCell& cell, const BreakdownOptions& options);

// A domain's picture size: study.yaml's image_size, else the first picture's (upright, after its EXIF
// orientation), else {0, 0}.
std::pair<int, int> domain_image_size(const Study& study, const std::string& domain);

}  // namespace ipd
