#include "core/stats/study_statistics.h"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <map>

#include "core/picture/picture_codec.h"
#include "core/stats/statistics.h"
#include "core/util/number_text.h"
#include "core/util/parallel.h"

namespace ipd {

namespace {}

std::vector<SceneSum> scene_sums(const TableCell& cell) {
  std::vector<SceneSum> out;
  out.reserve(cell.per_scene.size());
  for (const auto& s : cell.per_scene) out.push_back({s.sum_abs_diff, s.pairs});
  return out;
}

std::string cell_key(const TableCell& cell) { return cell.model + "|" + cell.a + "|" + cell.b; }

void add_confidence_intervals(CrossTable* table, const BootstrapOptions& options, int threads) {
  if (const auto e = options.validate(); !e.empty()) throw std::invalid_argument(e);
  parallel_for(table->cells.size(), threads, [&](size_t k) {
    TableCell& c = table->cells[k];
    if (c.missing_predictions || !c.no_value_reason.empty() || c.pairs == 0) return;
    const Interval ci = bootstrap_pooled_mean(scene_sums(c), options, cell_key(c));
    c.ci_low = ci.low;
    c.ci_high = ci.high;
    c.se = ci.se;
  });
}

SceneDistribution scene_distribution(const TableCell& cell, int worst) {
  SceneDistribution d;
  std::vector<std::pair<std::string, double>> scenes;
  for (const auto& s : cell.per_scene)
    if (s.pairs > 0) scenes.emplace_back(s.stem, s.ipd());
  d.scenes = static_cast<int>(scenes.size());
  std::vector<double> v;
  for (const auto& s : scenes) v.push_back(s.second);
  d.min = quantile(v, 0);
  d.q1 = quantile(v, 0.25);
  d.median = quantile(v, 0.5);
  d.q3 = quantile(v, 0.75);
  d.max = quantile(v, 1);
  std::stable_sort(scenes.begin(), scenes.end(), [](const auto& x, const auto& y) { return x.second > y.second; });
  if (static_cast<int>(scenes.size()) > worst) scenes.resize(std::max(0, worst));
  d.worst = std::move(scenes);
  return d;
}

// ---------------------------------------------------------------------------------------------------------
// Renderer comparison

namespace {

// A cell without a number (TableCell::no_value_reason) has nothing to compare or break down.
[[noreturn]] void throw_no_value(const TableCell& c) {
  throw StudyError(fmt::format("model '{}': IPD({}, {}) is not a number: {}", c.model, c.a, c.b, c.no_value_reason));
}

// Per ref rock of one scene: |diff| of its counted pair in the cell (ref, other).
std::map<int, double> diff_by_ref_rock(const SceneIpd& s, bool ref_is_a) {
  std::map<int, double> out;
  for (size_t k = 0; k < s.counted.size(); ++k)
    out[ref_is_a ? s.counted[k].first : s.counted[k].second] = std::abs(s.perf_a[k] - s.perf_b[k]);
  return out;
}

const TableCell& find_cell(const CrossTable& t, const std::string& model, const std::string& x, const std::string& y) {
  const TableCell* c = t.cell(model, x, y);
  if (!c) throw StudyError(fmt::format("no IPD cell for model '{}' and domains '{}' and '{}'", model, x, y));
  // A missing predictions folder is one of the reasons (it names the domain that lacks one).
  if (!c->no_value_reason.empty()) throw_no_value(*c);
  return *c;
}

}  // namespace

RendererComparison compare_renderers(const CrossTable& table, const std::string& model, const std::string& ref,
                                     const std::string& a, const std::string& b, const CompareOptions& options) {
  if (ref == a || ref == b || a == b)
    throw StudyError(fmt::format("compare needs three different domains, got ref '{}', a '{}', b '{}'", ref, a, b));
  const TableCell& ca = find_cell(table, model, ref, a);
  const TableCell& cb = find_cell(table, model, ref, b);
  std::map<std::string, const SceneIpd*> b_scenes;
  for (const auto& s : cb.per_scene) b_scenes[s.stem] = &s;
  RendererComparison out{model, ref, a, b, {}, {}};
  std::vector<PairedScene> scenes;
  for (const auto& sa : ca.per_scene) {
    const auto it = b_scenes.find(sa.stem);
    if (it == b_scenes.end()) continue;
    const SceneIpd& sb = *it->second;
    PairedScene p;
    p.a = {sa.sum_abs_diff, sa.pairs};
    p.b = {sb.sum_abs_diff, sb.pairs};
    const auto da = diff_by_ref_rock(sa, ca.a == ref), db = diff_by_ref_rock(sb, cb.a == ref);
    for (const auto& [rock, diff] : da) {
      const auto other = db.find(rock);
      if (other == db.end()) continue;
      p.common_a.sum += diff;
      p.common_b.sum += other->second;
      ++p.common_a.count;
      ++p.common_b.count;
    }
    scenes.push_back(p);
    out.scenes.push_back(sa.stem);
  }
  out.result = compare_paired(scenes, options, model + "|" + ref + "|" + a + "|" + b);
  return out;
}

std::string minus_number(double v, int digits) {
  if (std::isnan(v)) return "n/a";
  const std::string s = fmt::format("{:.{}f}", std::abs(v), digits);
  return (v < 0 && s.find_first_not_of("0.") != std::string::npos ? "−" : "") + s;
}

bool significant_difference(const Comparison& c, double p, double alpha) {
  if (std::isnan(p) || std::isnan(c.delta.estimate)) return false;
  const bool interval_excludes_zero = !c.delta.has_interval() || c.delta.low > 0 || c.delta.high < 0;
  return p < alpha && interval_excludes_zero;
}

double level_of_interval(double interval_level) { return std::round((1 - interval_level) * 1e9) / 1e9; }

std::string comparison_sentence(const RendererComparison& c, double alpha) {
  const Comparison& r = c.result;
  const auto num = minus_number;
  if (std::isnan(r.delta.estimate))
    return fmt::format("no comparison of {} and {} against {} for {}: one of them has no rock pairs ({} {})", c.a, c.b,
                       c.ref, c.model, r.scenes, r.scenes == 1 ? "scene" : "scenes");
  if (r.scenes < 2)
    return fmt::format("cannot tell whether {} or {} is closer to {} for {}: ΔIPD = {}, {} scene: no interval, no test",
                       c.a, c.b, c.ref, c.model, num(r.delta.estimate, 4), r.scenes);
  std::string numbers = "ΔIPD = " + num(r.delta.estimate, 4);
  if (r.delta.has_interval()) numbers += fmt::format(" [{}, {}]", num(r.delta.low, 3), num(r.delta.high, 3));
  // Never scientific notation (the studio shows this sentence): {:.2g} writes p >= 0.0001 in full.
  if (!std::isnan(r.p_value))
    numbers += (r.p_value < 1e-4 ? std::string(", p < 0.0001") : fmt::format(", p = {:.2g}", r.p_value)) +
               (r.exact_p ? " (exact)" : "");
  numbers += fmt::format(", {} {}", grouped_thousands(r.scenes), r.scenes == 1 ? "scene" : "scenes");
  // Without a test (no permutations asked for) there is no verdict either way: "no significant difference" would
  // read as a tested null result, even when the interval excludes 0.
  if (std::isnan(r.p_value))
    return fmt::format("not tested whether {} or {} is closer to {} for {}: {} (no permutation test was run)", c.a, c.b,
                       c.ref, c.model, numbers);
  if (!significant_difference(r, r.p_value, alpha)) {
    // The verdict needs both the test and the interval: when only one of them tells the two apart, say which, so
    // "no significant difference" beside an interval that excludes 0 does not read as a contradiction.
    const bool excludes_zero = r.delta.has_interval() && (r.delta.low > 0 || r.delta.high < 0);
    // An exact test's smallest p is 2 / 2^scenes (no swap, and every scene swapped): too few scenes never reach alpha.
    const double smallest_p = r.exact_p ? std::ldexp(2.0, -r.scenes) : 0;
    std::string why;
    if (excludes_zero && smallest_p >= alpha)
      why = fmt::format(
          "; the interval excludes 0, but with {} scenes the exact test's p can't go below {:.2g}: more "
          "scenes are needed",
          r.scenes, smallest_p);
    else if (excludes_zero)
      why = fmt::format("; the interval excludes 0, but p is not below {:g}", alpha);
    else if (r.p_value < alpha && r.delta.has_interval())
      why = fmt::format("; p is below {:g}, but the interval holds 0", alpha);
    return fmt::format("no significant difference between {} and {} in closeness to {} for {}: {}{}", c.a, c.b, c.ref,
                       c.model, numbers, why);
  }
  const bool a_closer = r.delta.estimate < 0;
  return fmt::format("{} is closer to {} than {} for {}: {}", a_closer ? c.a : c.b, c.ref, a_closer ? c.b : c.a,
                     c.model, numbers);
}

// ---------------------------------------------------------------------------------------------------------
// Breakdowns

bool parse_breakdown_by(const std::string& name, BreakdownBy* out) {
  if (name == "size")
    *out = BreakdownBy::kSize;
  else if (name == "region")
    *out = BreakdownBy::kRegion;
  else if (name == "confidence")
    *out = BreakdownBy::kConfidence;
  else
    return false;
  return true;
}

const char* to_string(BreakdownBy by) {
  switch (by) {
    case BreakdownBy::kSize:
      return "size";
    case BreakdownBy::kRegion:
      return "region";
    case BreakdownBy::kConfidence:
      return "confidence";
  }
  return "?";
}

std::string BreakdownOptions::validate() const {
  if (bins < 1 || bins > kMaxBreakdownBins)
    return fmt::format("--bins must be between 1 and {}, not {}", kMaxBreakdownBins, bins);
  return bootstrap.validate();
}

std::pair<int, int> domain_image_size(const Study& study, const std::string& domain) {
  if (study.config.image_width > 0 && study.config.image_height > 0)
    return {study.config.image_width, study.config.image_height};
  const Domain* d = study.domain(domain);
  if (d)
    for (const auto& [stem, path] : d->images) {
      // As the picture is shown and measured: turned upright by its EXIF orientation, as YOLOv5 labels it
      // (IMREAD_UNCHANGED keeps a phone photo's sensor orientation, whose width is the upright height).
      const cv::Mat m = read_study_picture(study.root, path, cv::IMREAD_COLOR).image;
      if (!m.empty()) return {m.cols, m.rows};
    }
  return {0, 0};
}

namespace {

// One counted pair of a cell: its scene, the ref rock's property, |diff|. NaN property: "no detection".
struct PairValue {
  int scene;
  double value, diff;
};

// The property a breakdown bins by, of ref rock i of a scene (gt: the scene's GT in domain a, pred its
// predictions, perf their performance values when binning by confidence). Size is the mask's area in the
// segment task (what its performance value measures), the box's in detect.
double rock_property(BreakdownBy by, const std::vector<Box>& gt, const std::vector<Box>& pred,
                     const PerformanceValues& perf, int i, double pixel_area, Task task) {
  const Box& box = gt[i];
  double v = 0;
  switch (by) {
    case BreakdownBy::kSize:
      v = (task == Task::kSegment && box.outline ? box.outline->area : box.area()) * pixel_area;
      break;
    case BreakdownBy::kRegion:
      v = std::clamp(static_cast<int>(std::floor(box.cy * 3)), 0, 2) * 3 +
          std::clamp(static_cast<int>(std::floor(box.cx * 3)), 0, 2);
      break;
    case BreakdownBy::kConfidence:
      v = perf.best_prediction[i] >= 0 ? pred[perf.best_prediction[i]].conf : kNaN;
      break;
  }
  return v;
}

// Every counted pair of the cell with its ref rock's property.
std::vector<PairValue> pair_values(const StudyLabels& labels, const TableCell& cell, BreakdownBy by) {
  std::vector<PairValue> pairs;
  const auto [width, height] = domain_image_size(labels.study, cell.a);
  const double pixel_area = width > 0 ? static_cast<double>(width) * height : 1e6;
  for (size_t s = 0; s < cell.per_scene.size(); ++s) {
    const SceneIpd& sc = cell.per_scene[s];
    const auto& gt = labels.gt_of(cell.a, sc.stem).boxes;
    const auto& pred = labels.predictions_of(cell.a, cell.model, sc.stem).boxes;
    PerformanceValues perf;
    if (by == BreakdownBy::kConfidence) perf = performance_values(gt, pred, labels.study.config.task);
    for (size_t k = 0; k < sc.counted.size(); ++k) {
      const double v = rock_property(by, gt, pred, perf, sc.counted[k].first, pixel_area, labels.study.config.task);
      pairs.push_back({static_cast<int>(s), v, std::abs(sc.perf_a[k] - sc.perf_b[k])});
    }
  }
  return pairs;
}

// The bins of a breakdown, empty of pairs: the nine regions, or quantile bins of the properties present (plus
// "no detection" by confidence). Returns the quantile bins' inner edges (none for regions).
std::vector<double> make_bins(const std::vector<PairValue>& pairs, const BreakdownOptions& options,
                              std::vector<BreakdownBin>* bins) {
  std::vector<double> edges;  // inner edges for quantile bins
  std::vector<double> present;
  for (const auto& p : pairs)
    if (!std::isnan(p.value)) present.push_back(p.value);
  if (pairs.empty()) return edges;  // no rock pairs: no bins (quantiles of nothing read "nan–nan")
  if (options.by == BreakdownBy::kRegion) {
    static const char* kRegions[] = {"top-left", "top",         "top-right", "left",        "centre",
                                     "right",    "bottom-left", "bottom",    "bottom-right"};
    for (int k = 0; k < 9; ++k) bins->push_back({kRegions[k], double(k), double(k), {}, 0, 0});
    return edges;
  }
  // Every pair without a detection (by confidence): only the "no detection" bin.
  const int nbins = present.empty() ? 0 : options.bins;
  edges = quantile_edges(present, nbins);
  const double lo = quantile(present, 0), hi = quantile(present, 1);
  for (int k = 0; k < nbins; ++k) {
    BreakdownBin b;
    b.low = k == 0 ? lo : edges[k - 1];
    b.high = k == nbins - 1 ? hi : edges[k];
    // A range takes an en dash (print typography; a hyphen reads as a minus next to numbers).
    b.label = options.by == BreakdownBy::kSize ? fmt::format("{:.0f}\u2013{:.0f} px²", b.low, b.high)
                                               : fmt::format("{:.2f}\u2013{:.2f}", b.low, b.high);
    bins->push_back(b);
  }
  if (options.by == BreakdownBy::kConfidence) bins->push_back({"no detection", kNaN, kNaN, {}, 0, 0});
  return edges;
}

}  // namespace

CellBreakdown breakdown_cell(const StudyLabels& labels, const TableCell& cell, const BreakdownOptions& options) {
  if (const auto e = options.validate(); !e.empty()) throw std::invalid_argument(e);
  if (!cell.no_value_reason.empty()) throw_no_value(cell);  // its bins would all read 0
  CellBreakdown out{cell.model, cell.trained_on, cell.a, cell.b, options.by, {}};
  const std::vector<PairValue> pairs = pair_values(labels, cell, options.by);
  const std::vector<double> edges = make_bins(pairs, options, &out.bins);
  const int nbins = static_cast<int>(out.bins.size()) - (options.by == BreakdownBy::kConfidence ? 1 : 0);
  auto bin_of = [&](double v) {
    if (std::isnan(v)) return nbins;  // the "no detection" bin
    if (options.by == BreakdownBy::kRegion) return static_cast<int>(v);
    // Upper edges belong to the lower bin, so a bin [e_{k-1}, e_k] holds its quantile's values.
    return static_cast<int>(std::lower_bound(edges.begin(), edges.end(), v) - edges.begin());
  };
  std::vector<std::vector<SceneSum>> per_bin(out.bins.size(), std::vector<SceneSum>(cell.per_scene.size()));
  for (const auto& p : pairs) {
    SceneSum& s = per_bin[bin_of(p.value)][p.scene];
    s.sum += p.diff;
    ++s.count;
  }
  for (size_t k = 0; k < out.bins.size(); ++k) {
    BreakdownBin& b = out.bins[k];
    b.ipd = bootstrap_pooled_mean(per_bin[k], options.bootstrap,
                                  fmt::format("{}|{}|{}", cell_key(cell), to_string(options.by), k));
    for (const auto& s : per_bin[k]) {
      b.pairs += s.count;
      b.scenes += s.count > 0;
    }
  }
  return out;
}

}  // namespace ipd
