#include "core/report/rank_format.h"

#include <fmt/format.h>

#include <cmath>

#include "core/report/csv.h"
#include "core/report/markdown.h"
#include "core/report/table_cells.h"
#include "core/util/json_output.h"
#include "core/util/number_text.h"

namespace ipd {

namespace {

nlohmann::ordered_json number(double v) {
  return std::isnan(v) ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(v);
}

std::string num(double v, int digits) { return std::isnan(v) ? std::string("–") : fmt::format("{:.{}f}", v, digits); }

// "0.0312 [0.027, 0.036]"
std::string ipd_text(const RankedCandidate& r) {
  std::string s = num(r.ipd, 4);
  if (!std::isnan(r.ci_low)) s += fmt::format(" [{:.3f}, {:.3f}]", r.ci_low, r.ci_high);
  return s;
}

// "+0.0018 [−0.001, 0.004]", "best" for the best
std::string delta_text(const RankedCandidate& r) {
  if (!r.vs_best) return "best";
  const Interval& d = r.vs_best->result.delta;
  std::string s = (d.estimate > 0 ? "+" : "") + minus_number(d.estimate, 4);
  if (d.has_interval()) s += fmt::format(" [{}, {}]", minus_number(d.low, 3), minus_number(d.high, 3));
  return s;
}

std::string p_text(double p) {
  if (std::isnan(p)) return "–";
  return p < 1e-4 ? std::string("<0.0001") : fmt::format("{:.4f}", p);
}

std::string group_text(const RankedCandidate& r) {
  if (!r.vs_best) return "best";
  return r.in_best_group ? "≈ best" : "worse";
}

std::string params_text(const RankedCandidate& r) {
  std::string s;
  for (const auto& [name, value] : r.params) s += fmt::format("{}{}={:g}", s.empty() ? "" : " ", name, value);
  return s;
}

bool any_params(const Ranking& k) {
  for (const auto& r : k.ranked)
    if (!r.params.empty()) return true;
  return false;
}

// The parameter names of every ranked candidate, in order of first appearance (CSV columns).
std::vector<std::string> param_names(const Ranking& k) {
  std::vector<std::string> names;
  for (const auto& r : k.ranked)
    for (const auto& p : r.params)
      if (std::find(names.begin(), names.end(), p.first) == names.end()) names.push_back(p.first);
  return names;
}

std::string title(const Ranking& k) {
  return fmt::format("{}{} against {}: {} candidate{} ranked (IPD, lower is better)", k.model,
                     k.trained_on.empty() ? "" : " (" + k.trained_on + ")", k.ref, k.ranked.size(),
                     k.ranked.size() == 1 ? "" : "s");
}

std::string text_ranking(const Ranking& k, const TableFormatOptions& o) {
  const bool params = any_params(k);
  size_t name_w = 6, param_w = 6;
  for (const auto& r : k.ranked) {
    name_w = std::max(name_w, r.domain.size());
    param_w = std::max(param_w, params_text(r).size());
  }
  std::string out = title(k) + "\n";
  auto row = [&](const std::string& rank, const std::string& domain, const std::string& par, const std::string& ipd,
                 const std::string& pairs, const std::string& delta, const std::string& p, const std::string& ph,
                 const std::string& group) {
    std::string line = fmt::format("{:<5} {:<{}}  ", rank, domain, name_w);
    if (params) line += fmt::format("{:<{}}  ", par, param_w);
    line += fmt::format("{:<24} {:>7}  {:<26} {:>8} {:>8}  {}", ipd, pairs, delta, p, ph, group);
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out += line + "\n";
  };
  row("rank", "domain", "params", fmt::format("IPD [{:g}% CI]", 100 * o.level), "pairs", "ΔIPD vs best [CI]", "p",
      "p Holm", "group");
  for (const auto& r : k.ranked)
    row(std::to_string(r.rank), r.domain, params_text(r), ipd_text(r), grouped_thousands(r.pairs), delta_text(r),
        r.vs_best ? p_text(r.vs_best->result.p_value) : "–", r.vs_best ? p_text(r.p_holm) : "–", group_text(r));
  for (const std::string& n : ranking_notes(k, o)) out += n + "\n";
  return out;
}

std::string markdown_ranking(const Ranking& k, const TableFormatOptions& o) {
  const bool params = any_params(k);
  std::string out = "**" + markdown_cell(title(k)) + "**\n\n";
  out += std::string("| rank | domain |") + (params ? " params |" : "") +
         fmt::format(" IPD [{:g}% CI] | pairs | ΔIPD vs best [CI] | p | p (Holm) | group |\n", 100 * o.level);
  out += std::string("|---:|---|") + (params ? "---|" : "") + "---:|---:|---:|---:|---:|---|\n";
  for (const auto& r : k.ranked) {
    out += fmt::format("| {} | {} |", r.rank, markdown_cell(r.domain));
    if (params) out += " " + markdown_cell(params_text(r)) + " |";
    const std::string ipd = r.rank == 1 ? "**" + ipd_text(r) + "**" : ipd_text(r);
    out += fmt::format(" {} | {} | {} | {} | {} | {} |\n", ipd, grouped_thousands(r.pairs), delta_text(r),
                       r.vs_best ? p_text(r.vs_best->result.p_value) : "–", r.vs_best ? p_text(r.p_holm) : "–",
                       group_text(r));
  }
  out += "\n";
  for (const std::string& n : ranking_notes(k, o)) out += markdown_cell(n) + "\n\n";
  return out;
}

std::string csv_ranking(const Ranking& k, const TableFormatOptions& o) {
  const std::vector<std::string> names = param_names(k);
  const auto prov = o.provenance ? provenance_csv_fields(*o.provenance) : decltype(provenance_csv_fields({})){};
  std::vector<std::string> header = {"model", "trained_on", "ref", "rank", "domain"};
  for (const auto& n : names) header.push_back("param_" + n);
  for (const char* h : {"ipd", "ci_low", "ci_high", "se", "pairs", "scenes", "delta", "delta_ci_low", "delta_ci_high",
                        "p_value", "exact_p", "p_holm", "correction", "level", "in_best_group", "reason"})
    header.push_back(h);
  for (const auto& [name, value] : prov) header.push_back(name);
  std::string out = csv_row(header);
  auto g = [](double v) { return std::isnan(v) ? std::string() : fmt::format("{:.17g}", v); };
  for (const auto& r : k.ranked) {
    std::vector<std::string> f = {k.model, k.trained_on, k.ref, std::to_string(r.rank), r.domain};
    for (const auto& n : names) {
      std::string v;
      for (const auto& p : r.params)
        if (p.first == n) v = g(p.second);
      f.push_back(v);
    }
    const Comparison* c = r.vs_best ? &r.vs_best->result : nullptr;
    for (const std::string& v : std::vector<std::string>{
             g(r.ipd), g(r.ci_low), g(r.ci_high), g(r.se), std::to_string(r.pairs), std::to_string(r.scenes),
             c ? g(c->delta.estimate) : "", c ? g(c->delta.low) : "", c ? g(c->delta.high) : "", c ? g(c->p_value) : "",
             c ? (c->exact_p ? "true" : "false") : "", c ? g(r.p_holm) : "", "Holm",
             fmt::format("{:g}", k.options.level), r.in_best_group ? "true" : "false", ""})
      f.push_back(v);
    for (const auto& [name, value] : prov) f.push_back(value);
    out += csv_row(f);
  }
  for (const auto& u : k.unranked) {
    std::vector<std::string> f = {k.model, k.trained_on, k.ref, "", u.domain};
    f.resize(f.size() + names.size() + 15);
    f.push_back(u.reason);
    for (const auto& [name, value] : prov) f.push_back(value);
    out += csv_row(f);
  }
  return out;
}

std::string json_ranking(const Ranking& k, const TableFormatOptions& o) {
  nlohmann::ordered_json j;
  j["model"] = k.model;
  j["trained_on"] = k.trained_on.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(k.trained_on);
  j["ref"] = k.ref;
  j["best"] = k.best() ? nlohmann::ordered_json(k.best()->domain) : nlohmann::ordered_json(nullptr);
  nlohmann::ordered_json group = nlohmann::ordered_json::array();
  for (const auto& r : k.ranked)
    if (r.in_best_group) group.push_back(r.domain);
  j["best_group"] = group;
  j["level"] = k.options.level;
  j["correction"] = "Holm";
  j["tests"] = k.tests;
  j["interval_level"] = o.level;
  j["resamples"] = o.resamples;
  j["permutations"] = k.options.compare.permutations;
  j["seed"] = o.seed;
  j["conf_threshold"] = o.conf_threshold;
  nlohmann::ordered_json ranked = nlohmann::ordered_json::array();
  for (const auto& r : k.ranked) {
    nlohmann::ordered_json e;
    e["rank"] = r.rank;
    e["domain"] = r.domain;
    nlohmann::ordered_json params = nlohmann::ordered_json::object();
    for (const auto& [name, value] : r.params) params[name] = value;
    e["params"] = params;
    e["ipd"] = number(r.ipd);
    e["ci_low"] = number(r.ci_low);
    e["ci_high"] = number(r.ci_high);
    e["se"] = number(r.se);
    e["pairs"] = r.pairs;
    e["scenes"] = r.scenes;
    const Comparison* c = r.vs_best ? &r.vs_best->result : nullptr;
    e["delta"] = c ? number(c->delta.estimate) : nlohmann::ordered_json(nullptr);
    e["delta_ci_low"] = c ? number(c->delta.low) : nlohmann::ordered_json(nullptr);
    e["delta_ci_high"] = c ? number(c->delta.high) : nlohmann::ordered_json(nullptr);
    e["common_scenes"] = c ? nlohmann::ordered_json(c->scenes) : nlohmann::ordered_json(nullptr);
    e["p_value"] = c ? number(c->p_value) : nlohmann::ordered_json(nullptr);
    e["exact_p"] = c ? nlohmann::ordered_json(c->exact_p) : nlohmann::ordered_json(nullptr);
    e["p_holm"] = number(r.p_holm);
    e["in_best_group"] = r.in_best_group;
    e["no_predictions_at_threshold"] = r.no_predictions_at_threshold;
    ranked.push_back(e);
  }
  j["ranked"] = ranked;
  nlohmann::ordered_json unranked = nlohmann::ordered_json::array();
  for (const auto& u : k.unranked) unranked.push_back({{"domain", u.domain}, {"reason", u.reason}});
  j["unranked"] = unranked;
  if (o.provenance) j["provenance"] = provenance_json(*o.provenance);
  return dump_json_output(j, 2) + "\n";
}

// Print's signs as LaTeX math, so the notes typeset with any engine.
std::string latex_signs(std::string s) {
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"−", "$-$"},
                                 {"Δ", "$\\Delta$"},
                                 {"≈", "$\\approx$"},
                                 {"≤", "$\\le$"},
                                 {"≥", "$\\ge$"}})
    for (size_t at; (at = s.find(from)) != std::string::npos;) s.replace(at, from.size(), to);
  return s;
}

// The gap between the p-value and the mark of the group not distinguishable from the best, in points.
constexpr double kRankMarkGapPt = 2;

// The parameter names every ranked candidate has, in the first one's order: the compact layout's columns
// instead of the settings' names. Empty when a candidate has none or other ones.
std::vector<std::string> shared_params(const Ranking& k) {
  std::vector<std::string> names;
  if (k.ranked.empty()) return names;
  for (const auto& [name, value] : k.ranked.front().params) names.push_back(name);
  for (const auto& r : k.ranked) {
    if (r.params.size() != names.size()) return {};
    for (size_t i = 0; i < names.size(); ++i)
      if (r.params[i].first != names[i]) return {};
  }
  return names;
}

// The compact LaTeX ranking, for one IEEE column (252 pt at 10 pt type): a setting named by its parameter values
// when every setting has the same parameters (else by its name), intervals on a second line under the IPD and
// the ΔIPD, the group not distinguishable from the best marked $\approx$ in a narrow last column.
std::string latex_compact_ranking(const Ranking& k, const TableFormatOptions& o) {
  using table_cells::latex_text;
  const std::vector<std::string> params = shared_params(k);
  const size_t id_cols = params.empty() ? 1 : params.size();
  const bool bt = o.booktabs;
  std::string out = "% IPD ranking, generated by `ipd rank --format latex` (one column; --latex-wide: table*)\n";
  if (bt) out += "% needs \\usepackage{booktabs}\n";
  // Rows in rank order (no rank column); the group mark sits 2 pt after the p-value, not a full column gap away.
  out += "\\begin{tabular}{" + std::string(bt ? "@{}" : "") + std::string(id_cols, params.empty() ? 'l' : 'r') +
         "rrr@{\\hspace{" + fmt::format("{:g}", kRankMarkGapPt) + "pt}}c" + (bt ? "@{}" : "") + "}\n";
  out += bt ? "\\toprule\n" : "\\hline\n";
  if (params.empty()) out += "setting";
  for (size_t i = 0; i < params.size(); ++i) out += (i ? " & " : "") + latex_text(params[i]);
  out += " & IPD & $\\Delta$IPD & $p$ Holm & \\\\\n";
  out += bt ? "\\midrule\n" : "\\hline\n";
  const auto interval = [](double lo, double hi) {
    const auto n = [](double v) { return v < 0 ? fmt::format("$-${:.3f}", -v) : fmt::format("{:.3f}", v); };
    return "{[}" + n(lo) + ", " + n(hi) + "{]}";  // braced: "[" after \\ is an argument
  };
  for (const auto& r : k.ranked) {
    if (params.empty()) out += latex_text(r.domain);
    for (size_t i = 0; i < r.params.size() && !params.empty(); ++i)
      out += fmt::format("{}{:g}", i ? " & " : "", r.params[i].second);
    std::string ipd = num(r.ipd, 4);
    if (r.rank == 1) ipd = "\\textbf{" + ipd + "}";
    const Interval* d = r.vs_best ? &r.vs_best->result.delta : nullptr;
    std::string delta = "best";
    if (d)
      delta = (d->estimate > 0 ? "+" : d->estimate < 0 ? "$-$" : "") + fmt::format("{:.4f}", std::abs(d->estimate));
    out += " & " + ipd + " & " + delta + " & " + (r.vs_best ? latex_text(p_text(r.p_holm)) : "--") + " & " +
           (r.in_best_group && r.vs_best ? "$\\approx$" : "") + " \\\\\n";
    if (o.latex_ci) {
      out += std::string(id_cols - 1, '&');  // the setting's cells, empty
      out += " & " + (std::isnan(r.ci_low) ? std::string() : interval(r.ci_low, r.ci_high));
      out += " & " + (d && d->has_interval() ? interval(d->low, d->high) : std::string()) + " & & \\\\\n";
    }
  }
  out += bt ? "\\bottomrule\n" : "\\hline\n";
  out += "\\end{tabular}\n";
  std::string legend = "Best first";
  if (!params.empty()) {
    legend += "; settings by their parameters (";
    for (const auto& r : k.ranked) legend += (r.rank == 1 ? "" : ", ") + latex_text(r.domain);
    legend += ")";
  }
  out += "\\par\\smallskip{\\footnotesize " + legend + ".}\n";
  for (const std::string& n : ranking_notes(k, o))
    out += "\\par{\\footnotesize " + latex_signs(table_cells::latex_text(n)) + "}\n";
  return out;
}

// The width of the compact ranking's tabular at 10 pt Computer Modern (within a few points).
double compact_ranking_width_pt(const Ranking& k, const TableFormatOptions& o) {
  using table_cells::latex_text_width_pt;
  const std::vector<std::string> params = shared_params(k);
  const size_t id_cols = params.empty() ? 1 : params.size();
  std::vector<double> w(id_cols + 4, 0);  // the setting's columns, IPD, ΔIPD, p, the group mark
  w[id_cols] = latex_text_width_pt("IPD", false);
  w[id_cols + 1] = latex_text_width_pt("IPD", false) + 8.33;  // $\Delta$
  w[id_cols + 2] = latex_text_width_pt("p Holm", false);
  for (size_t i = 0; i < params.size(); ++i) w[i] = latex_text_width_pt(params[i], false);
  if (params.empty()) w[0] = latex_text_width_pt("setting", false);
  const auto interval = [](double lo, double hi) { return fmt::format("[{:.3f}, {:.3f}]", lo, hi); };
  for (const auto& r : k.ranked) {
    if (params.empty()) w[0] = std::max(w[0], latex_text_width_pt(r.domain, false));
    for (size_t i = 0; i < params.size() && i < r.params.size(); ++i)
      w[i] = std::max(w[i], latex_text_width_pt(fmt::format("{:g}", r.params[i].second), false));
    double ipd = latex_text_width_pt(num(r.ipd, 4), r.rank == 1);
    if (o.latex_ci && !std::isnan(r.ci_low))
      ipd = std::max(ipd, latex_text_width_pt(interval(r.ci_low, r.ci_high), false));
    w[id_cols] = std::max(w[id_cols], ipd);
    if (const Interval* d = r.vs_best ? &r.vs_best->result.delta : nullptr) {
      double dw = latex_text_width_pt(fmt::format("+{:.4f}", std::abs(d->estimate)), false);
      if (o.latex_ci && d->has_interval())
        dw = std::max(dw, latex_text_width_pt(interval(std::abs(d->low), std::abs(d->high)), false) +
                              (d->low < 0 ? 7.78 : 0) + (d->high < 0 ? 7.78 : 0));
      w[id_cols + 1] = std::max(w[id_cols + 1], dw);
      w[id_cols + 2] = std::max(w[id_cols + 2], latex_text_width_pt(p_text(r.p_holm), false));
    }
    if (r.in_best_group && r.vs_best) w[id_cols + 3] = 7.78;
  }
  const double sep = 12;  // 2 \tabcolsep
  double total = o.booktabs ? -sep : 0;
  for (double v : w) total += v + sep;
  return total - (sep - kRankMarkGapPt);  // the mark's narrow gap
}

std::string latex_ranking(const Ranking& k, const TableFormatOptions& o) {
  using table_cells::latex_text;
  const bool params = any_params(k);
  if (!o.latex_wide) return latex_compact_ranking(k, o);
  std::string out =
      "% IPD ranking, generated by `ipd rank --format latex --latex-wide` (a table* across both columns)\n";
  out += std::string("\\begin{tabular}{rl") + (params ? "l" : "") + "rrrl}\n";
  out += o.booktabs ? "\\toprule\n" : "\\hline\n";
  out += std::string("& setting") + (params ? " & params" : "") + " & IPD & $\\Delta$IPD vs best & $p$ (Holm) & \\\\\n";
  out += o.booktabs ? "\\midrule\n" : "\\hline\n";
  for (const auto& r : k.ranked) {
    std::string ipd = num(r.ipd, 4);
    if (r.rank == 1) ipd = "\\textbf{" + ipd + "}";
    if (o.latex_ci && !std::isnan(r.ci_low)) ipd += fmt::format(" [{:.3f}, {:.3f}]", r.ci_low, r.ci_high);
    out += fmt::format("{} & {}", r.rank, latex_text(r.domain));
    if (params) out += " & " + latex_text(params_text(r));
    out += fmt::format(" & {} & {} & {} & {} \\\\\n", ipd, latex_signs(delta_text(r)),
                       r.vs_best ? latex_text(p_text(r.p_holm)) : "--",
                       r.in_best_group ? (r.vs_best ? "$\\approx$ best" : "best") : "");
  }
  out += o.booktabs ? "\\bottomrule\n" : "\\hline\n";
  out += "\\end{tabular}\n";
  for (const std::string& n : ranking_notes(k, o)) out += "\\par{\\footnotesize " + latex_signs(latex_text(n)) + "}\n";
  return out;
}

}  // namespace

std::vector<std::string> ranking_notes(const Ranking& k, const TableFormatOptions& o) {
  std::vector<std::string> notes;
  std::string group;
  for (const auto& r : k.ranked)
    if (r.in_best_group) group += (group.empty() ? "" : ", ") + r.domain;
  notes.push_back(fmt::format(
      "Best: {}; not distinguishable from it at level {:g} (Holm-corrected over {} comparison{} with the best): {}.",
      k.best()->domain, k.options.level, k.tests, k.tests == 1 ? "" : "s", group));
  if (o.resamples > 0) notes.push_back(table_cells::ci_caption(o) + ".");
  const int perms = k.options.compare.permutations;
  notes.push_back(fmt::format(
      "ΔIPD = IPD({0}, candidate) − IPD({0}, best) over the scenes {0}, the candidate and the best share, with its "
      "{1:g}% paired scene-bootstrap interval; p: sign-flip permutation test ({2}), as ipd compare; p Holm: "
      "Holm-corrected over the candidates compared with the best; ≈ best: not distinguishable from the best "
      "(p Holm ≥ {3:g}, or the interval holds 0).",
      k.ref, 100 * o.level,
      perms == 0 ? std::string("not run: --permutations 0")
                 : fmt::format("{} permutations, exact where 2^scenes ≤ that", grouped_thousands(perms)),
      k.options.level));
  for (const auto& r : k.ranked)
    if (r.no_predictions_at_threshold)
      notes.push_back(fmt::format("{}: no predictions of {}{}: every rock there counts as missed.", r.domain, k.model,
                                  o.conf_threshold > 0 ? fmt::format(" at or above {:g}", o.conf_threshold) : ""));
  for (const auto& u : k.unranked) notes.push_back(fmt::format("Not ranked: {}: {}.", u.domain, u.reason));
  if (o.provenance) notes.push_back(provenance_note(*o.provenance));
  return notes;
}

std::string latex_ranking_fit_advice(const Ranking& ranking, const TableFormatOptions& options) {
  if (options.latex_wide) return "";
  const double w = compact_ranking_width_pt(ranking, options);
  if (w <= kIeeeColumnPt) return "";
  return fmt::format("the LaTeX ranking is about {:.0f} pt wide, more than one IEEE column ({:g} pt at 10 pt type): {}",
                     w, kIeeeColumnPt,
                     w <= kIeeeTextWidthPt ? "it fits a table* across both columns (--latex-wide spells the names out)"
                                           : "choose fewer parameters or candidates (--candidates)");
}

std::string format_ranking(const Ranking& ranking, TableFormat format, const TableFormatOptions& options) {
  switch (format) {
    case TableFormat::kText:
      return text_ranking(ranking, options);
    case TableFormat::kMarkdown:
      return markdown_ranking(ranking, options);
    case TableFormat::kCsv:
      return csv_ranking(ranking, options);
    case TableFormat::kJson:
      return json_ranking(ranking, options);
    case TableFormat::kLatex:
      return latex_ranking(ranking, options);
  }
  return {};
}

}  // namespace ipd
