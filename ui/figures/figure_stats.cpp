#include "ui/figures/figure_stats.h"

#include <fmt/format.h>

#include <cmath>

#include "core/util/number_text.h"

namespace ipd::ui {

namespace {
std::string model_label(const std::string& name, const std::string& trained_on) {
  return trained_on.empty() ? name : name + " (" + trained_on + ")";
}
std::string p_text(double p) {
  if (!std::isfinite(p)) return "p n/a";
  return p < 0.001 ? "p < 0.001" : fmt::format("p = {:.3f}", p);
}
// "−0.267" with a real minus sign, "+0.012".
std::string signed_text(double v) {
  if (!std::isfinite(v)) return "n/a";
  return (v < 0 ? "\u2212" : "+") + fmt::format("{:.3f}", std::abs(v));
}
}  // namespace

DotWhiskerChart compare_chart(const CrossTable& table, const std::vector<std::string>& models, const std::string& ref,
                              const std::string& a, const std::string& b, const CompareOptions& options) {
  DotWhiskerChart ch;
  const int pct = int(std::lround(options.bootstrap.level * 100));
  ch.title = fmt::format(
      "\u0394IPD = IPD({0}, {1}) \u2212 IPD({0}, {2}) per model, {3}% scene-bootstrap interval; "
      "below 0: {1} is closer to {0}",
      ref, a, b, pct);
  ch.axis_label = fmt::format("\u0394IPD ({} vs {})", a, b);
  ch.zero_line = true;
  std::vector<std::string> skipped;
  int exact_rows = 0, random_rows = 0, min_scenes = 0, max_scenes = 0;
  for (const ModelInfo& m : table.models) {
    if (!models.empty() && std::find(models.begin(), models.end(), m.name) == models.end()) continue;
    try {
      const RendererComparison c = compare_renderers(table, m.name, ref, a, b, options);
      ch.rows.push_back(
          {model_label(m.name, m.trained_on), c.result.delta.estimate, c.result.delta.low, c.result.delta.high,
           c.result.scenes < 2
               ? fmt::format("{}, {} scene: no test", signed_text(c.result.delta.estimate), c.result.scenes)
               : fmt::format("{}, {}", signed_text(c.result.delta.estimate), p_text(c.result.p_value))});
      (c.result.exact_p ? exact_rows : random_rows) += 1;
      min_scenes = min_scenes == 0 ? c.result.scenes : std::min(min_scenes, c.result.scenes);
      max_scenes = std::max(max_scenes, c.result.scenes);
    } catch (const std::exception&) {
      skipped.push_back(m.name);
    }
  }
  // Say what the p-values are: with few scenes every swap pattern is counted (exact, and p cannot go below
  // 2 / 2^scenes); otherwise `permutations` random ones.
  const std::string n =
      min_scenes == max_scenes ? fmt::format("{}", max_scenes) : fmt::format("{}\u2013{}", min_scenes, max_scenes);
  if (max_scenes < 2)  // no row has an interval: the title promises none
    ch.title = fmt::format("\u0394IPD = IPD({0}, {1}) \u2212 IPD({0}, {2}) per model; below 0: {1} is closer to {0}",
                           ref, a, b);
  if (max_scenes < 2)
    ch.footnote =
        fmt::format("{} scene present in all three domains: no interval, no test (they need at least 2).", max_scenes);
  else if (options.permutations == 0)  // no p-values, so no verdict: the rows' sentences say "not tested"
    ch.footnote =
        fmt::format("No permutation test was run (0 permutations); {} scenes present in all three domains.", n);
  else if (random_rows == 0 && exact_rows > 0)
    ch.footnote = fmt::format(
        "Sign-flip permutation test, exact (every swap pattern) over the {} scenes present in "
        "all three domains.",
        n);
  else if (exact_rows == 0)
    ch.footnote = fmt::format(
        "Sign-flip permutation test ({} permutations) over the {} scenes present in all three "
        "domains.",
        grouped_thousands(options.permutations), n);
  else
    ch.footnote = fmt::format(
        "Sign-flip permutation test over the {} scenes present in all three domains: exact "
        "where 2^scenes \u2264 {}, else {} random permutations.",
        n, grouped_thousands(options.permutations), grouped_thousands(options.permutations));
  if (!skipped.empty()) {
    std::string names;
    for (const auto& s : skipped) names += (names.empty() ? "" : ", ") + s;
    ch.footnote += " Not compared (missing predictions or pairs): " + names + ".";
  }
  return ch;
}

DistributionChart distribution_chart(const CrossTable& table, const std::string& model, int worst) {
  DistributionChart ch;
  const ModelInfo* info = nullptr;
  for (const auto& m : table.models)
    if (m.name == model) info = &m;
  ch.title =
      fmt::format("Per-scene IPD of {} for each domain pair (box: quartiles, whiskers: range; worst scenes named)",
                  info ? model_label(info->name, info->trained_on) : model);
  ch.axis_label = "scene IPD";
  for (const TableCell& cell : table.cells) {
    // As in the table: a domain pair without the model's training domain is not that model's result.
    if (cell.model != model || !cell.involves_training_domain) continue;
    BoxRow row;
    row.label = "|" + cell.a + " \u2212 " + cell.b + "|";
    for (const SceneIpd& s : cell.per_scene)
      if (s.pairs > 0) row.values.push_back(s.ipd());
    const SceneDistribution d = scene_distribution(cell, worst);
    row.min = d.min, row.q1 = d.q1, row.median = d.median, row.q3 = d.q3, row.max = d.max;
    row.worst = d.worst;
    ch.rows.push_back(row);
  }
  ch.footnote = "Each dot is one scene (its pooled |perf difference| over its pairs).";
  return ch;
}

DotWhiskerChart breakdown_chart(const CellBreakdown& b, double level) {
  DotWhiskerChart ch;
  const int pct = int(std::lround(level * 100));
  const char* by = b.by == BreakdownBy::kSize     ? "size"
                   : b.by == BreakdownBy::kRegion ? "image region"
                                                  : "detection confidence";
  ch.title = fmt::format("IPD({}, {}) of {} by {} of the {} rock, {}% scene-bootstrap interval", b.a, b.b,
                         model_label(b.model, b.trained_on), by, b.a, pct);
  ch.axis_label = "IPD";
  ch.non_negative = true;
  for (const BreakdownBin& bin : b.bins)
    ch.rows.push_back({bin.label, bin.ipd.estimate, bin.ipd.low, bin.ipd.high, fmt::format("{} pairs", bin.pairs)});
  if (b.bins.empty()) ch.footnote = kNoRockPairsToBin;
  return ch;
}

}  // namespace ipd::ui
