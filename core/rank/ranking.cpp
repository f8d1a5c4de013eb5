#include "core/rank/ranking.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/rank/holm.h"
#include "core/util/number_text.h"
#include "core/util/parallel.h"

namespace ipd {

namespace {

// Why a candidate's cell has no IPD to rank; "" when it has one.
std::string unranked_reason(const TableCell& cell, const std::string& ref, const std::string& candidate) {
  if (cell.missing_predictions) return cell.no_value_reason;  // "no predictions of det-real for hapke"
  if (cell.scenes == 0)
    return fmt::format("shares no scenes with {} (no label file stem is in both {}/labels/ and {}/labels/)", ref, ref,
                       candidate);
  if (!cell.no_value_reason.empty()) return cell.no_value_reason;  // "no predictions at or above 0.98 in ..."
  if (cell.pairs == 0)
    return fmt::format("no rock pairs with {} in its {} shared scene{} (no rocks, or none paired)", ref, cell.scenes,
                       cell.scenes == 1 ? "" : "s");
  return "";
}

}  // namespace

DomainPairFilter ranked_pairs(const RankDomains& domains) {
  DomainPairFilter out;
  for (const std::string& c : domains.candidates) out.emplace_back(domains.ref, c);
  return out;
}

RankDomains resolve_rank_domains(const Study& study, const std::string& ref,
                                 const std::vector<std::string>& candidates) {
  RankDomains out;
  out.ref = ref.empty() && !study.domains.empty() ? study.domains.front().name : ref;
  study.require_domain(out.ref, "--ref");
  for (const std::string& c : candidates) {
    study.require_domain(c, "--candidates");
    if (c == out.ref)
      throw StudyError(fmt::format("{}: '{}' is the reference (--ref) and cannot also be a candidate", study.root,
                                   quoted_for_message(c)));
    if (std::count(out.candidates.begin(), out.candidates.end(), c))
      throw StudyError(fmt::format("{}: --candidates names '{}' twice", study.root, quoted_for_message(c)));
    out.candidates.push_back(c);
  }
  if (candidates.empty())
    for (const auto& d : study.domains)
      if (d.name != out.ref) out.candidates.push_back(d.name);
  if (out.candidates.empty())
    throw StudyError(fmt::format("{}: nothing to rank: the study has no domain other than the reference '{}'",
                                 study.root, quoted_for_message(out.ref)));
  return out;
}

std::string RankOptions::validate() const {
  if (!(level > 0 && level < 1))
    return fmt::format("the significance level must be between 0 and 1 (e.g. 0.05), not {}", level);
  if (threads < 0) return fmt::format("threads must be >= 0 (0: every core), got {}", threads);
  return compare.validate();
}

Ranking order_candidates(const Study& study, const CrossTable& table, const RankOptions& options,
                         const std::function<bool(const std::string& candidate)>& without_predictions) {
  if (const auto e = options.validate(); !e.empty()) throw std::invalid_argument("rank options: " + e);
  const auto model = std::find_if(table.models.begin(), table.models.end(),
                                  [&](const ModelInfo& m) { return m.name == options.model; });
  if (model == table.models.end())
    throw StudyError(fmt::format("{}: no model '{}' in the table", study.root, quoted_for_message(options.model)));
  Ranking out;
  out.model = model->name;
  out.trained_on = model->trained_on;
  out.ref = options.domains.ref;
  out.options = options;
  for (const std::string& d : options.domains.candidates) {
    const TableCell* cell = table.cell(out.model, out.ref, d);
    if (!cell)
      throw StudyError(fmt::format("no IPD cell for model '{}' and domains '{}' and '{}'", out.model, out.ref, d));
    if (std::string why = unranked_reason(*cell, out.ref, d); !why.empty()) {
      out.unranked.push_back({d, std::move(why)});
      continue;
    }
    RankedCandidate r;
    r.domain = d;
    if (const auto p = study.config.domain_params.find(d); p != study.config.domain_params.end()) r.params = p->second;
    r.ipd = cell->ipd;
    r.ci_low = cell->ci_low;
    r.ci_high = cell->ci_high;
    r.se = cell->se;
    r.pairs = cell->pairs;
    r.scenes = cell->scenes;
    r.no_predictions_at_threshold = without_predictions(d);
    out.ranked.push_back(std::move(r));
  }
  if (out.ranked.empty()) {
    std::string why;
    for (const auto& u : out.unranked) why += fmt::format("\n  {}: {}", u.domain, u.reason);
    throw StudyError(
        fmt::format("{}: no candidate can be ranked against {} for {}:{}", study.root, out.ref, out.model, why));
  }
  std::stable_sort(out.ranked.begin(), out.ranked.end(),
                   [](const RankedCandidate& x, const RankedCandidate& y) { return x.ipd < y.ipd; });
  for (size_t k = 0; k < out.ranked.size(); ++k) out.ranked[k].rank = static_cast<int>(k) + 1;
  return out;
}

void compare_with_best(Ranking* ranking, const CompareWithBest& compare) {
  Ranking& out = *ranking;
  if (out.ranked.empty()) return;
  const std::string& best = out.ranked.front().domain;
  std::vector<double> raw(out.ranked.size(), std::nan(""));
  // Each comparison draws from its own seeded stream (keyed by its domains): any order gives the same numbers.
  parallel_for(out.ranked.size() - 1, out.options.threads, [&](size_t i) {
    RankedCandidate& r = out.ranked[i + 1];
    r.vs_best = compare(r.domain, best);
    raw[i + 1] = r.vs_best->result.p_value;
  });
  const std::vector<double> adjusted = holm_adjusted(raw);
  out.tests = static_cast<int>(std::count_if(raw.begin(), raw.end(), [](double p) { return !std::isnan(p); }));
  for (size_t k = 0; k < out.ranked.size(); ++k) {
    RankedCandidate& r = out.ranked[k];
    r.p_holm = adjusted[k];
    // Not shown to differ from the best: the best itself, and every candidate compare's verdict rule, on the Holm
    // p-value, cannot tell from it (an untested one included: nothing separates it from the best).
    r.in_best_group = k == 0 || !significant_difference(r.vs_best->result, r.p_holm, out.options.level);
  }
}

Ranking rank_candidates(const StudyLabels& labels, const CrossTable& table, const RankOptions& options) {
  Ranking out = order_candidates(labels.study, table, options, [&](const std::string& d) {
    const TableCell* cell = table.cell(options.model, options.domains.ref, d);
    const size_t column =
        static_cast<size_t>(std::find(table.columns.begin(), table.columns.end(), std::make_pair(cell->a, cell->b)) -
                            table.columns.begin());
    return column < table.pairings.size() && count_predictions(labels, d, options.model, table.pairings[column]) == 0;
  });
  compare_with_best(&out, [&](const std::string& candidate, const std::string& best) {
    return compare_renderers(table, out.model, out.ref, candidate, best, options.compare);
  });
  return out;
}

}  // namespace ipd
