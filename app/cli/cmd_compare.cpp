// `ipd compare STUDY --ref real --a principled --b hapke`: which renderer is closer to the reference, with a
// paired scene-bootstrap interval on ΔIPD and a permutation test.
#include <fmt/format.h>
#include <algorithm>

#include <iostream>
#include <nlohmann/json.hpp>

#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "app/cli/study_options.h"
#include "core/report/provenance.h"
#include "core/stats/study_statistics.h"
#include "core/util/json_output.h"
#include "core/util/number_text.h"

namespace ipd::cli {

namespace {
nlohmann::ordered_json comparison_json(const RendererComparison& c, double alpha, const Provenance& provenance) {
  const Comparison& r = c.result;
  return {{"model", c.model},
          {"ref", c.ref},
          {"a", c.a},
          {"b", c.b},
          {"ipd_a", json_number(r.ipd_a)},
          {"ipd_b", json_number(r.ipd_b)},
          {"delta", json_number(r.delta.estimate)},
          {"ci_low", json_number(r.delta.low)},
          {"ci_high", json_number(r.delta.high)},
          {"se", json_number(r.delta.se)},
          {"p_value", json_number(r.p_value)},
          {"scenes", r.scenes},
          {"pairs_a", r.pairs_a},
          {"pairs_b", r.pairs_b},
          {"delta_common", json_number(r.delta_common)},
          {"pairs_common", r.pairs_common},
          {"sentence", comparison_sentence(c, alpha)},
          {"provenance", provenance_json(provenance)}};
}

// What `ipd compare` was asked for.
struct CompareArgs {
  StudyOptions study;
  std::string ref, a, b;
  int permutations = 2000;
  bool json = false;
};

void declare_compare_options(CLI::App* cmd, CompareArgs* args) {
  add_study_options(cmd, &args->study, true);
  cmd->add_option("--ref", args->ref, "Reference domain (default: the study's first)");
  cmd->add_option("--a", args->a, "First renderer (default: the study's second domain)");
  cmd->add_option("--b", args->b, "Second renderer (default: the study's third domain)");
  cmd->add_option("--permutations", args->permutations, "Permutations for the p-value (0: none)")
      ->check(CLI::NonNegativeNumber)
      ->default_val(2000);
  cmd->add_flag("--json", args->json, "One JSON object (an array of them when several models are compared)");
}

// The domain given by its flag, else the study's k-th.
std::string domain_or_default(const Study& study, const std::string& name, size_t k, const char* flag) {
  if (!name.empty()) return name;
  if (study.domains.size() <= k)
    throw StudyError(fmt::format("{}: compare needs three domains; give {}", study.root, flag));
  return study.domains[k].name;
}

// One comparison per model with predictions for all three domains. A model without them is skipped with a
// warning, or is an error when it was asked for by name; so is one whose IPD is not a number.
std::vector<RendererComparison> compare_each_model(const LoadedStudy& loaded, const StudyOptions& so,
                                                   const std::string& root, const std::string& ref,
                                                   const std::string& a, const std::string& b,
                                                   const CompareOptions& co) {
  std::vector<RendererComparison> results;
  std::string no_value;  // the first cell that is not a number, and why
  for (const auto& m : loaded.table.models) {
    const TableCell* x = loaded.table.cell(m.name, ref, a);
    const TableCell* y = loaded.table.cell(m.name, ref, b);
    if (!x || !y || x->missing_predictions || y->missing_predictions) {
      std::string lacking;  // the domains without a predictions folder for this model, by name
      for (const std::string& d : {ref, a, b})
        if (!loaded.labels.has_predictions(d, m.name)) lacking += (lacking.empty() ? "" : ", ") + d;
      if (!so.models.empty()) throw StudyError(fmt::format("model '{}' has no predictions for {}", m.name, lacking));
      fmt::print(stderr, "warning: model '{}' skipped: it has no predictions for {}\n", m.name, lacking);
      continue;
    }
    // Two empty prediction sets would compare as "no significant difference": refuse, and say why.
    const TableCell* empty = !x->no_value_reason.empty() ? x : !y->no_value_reason.empty() ? y : nullptr;
    if (empty) {
      const std::string why = fmt::format("model '{}': IPD({}, {}) is not a number: {}", m.name, empty->a, empty->b,
                                          empty->no_value_reason);
      if (!so.models.empty()) throw StudyError(why);
      fmt::print(stderr, "warning: {}; model skipped\n", why);
      if (no_value.empty()) no_value = why;
      continue;
    }
    results.push_back(compare_renderers(loaded.table, m.name, ref, a, b, co));
  }
  if (results.empty() && !no_value.empty()) throw StudyError(fmt::format("{}: nothing to compare: {}", root, no_value));
  if (results.empty()) throw StudyError(fmt::format("{}: no model has predictions for {}, {} and {}", root, ref, a, b));
  return results;
}

// `alpha`: the verdict's significance level (level_of_interval of the intervals').
void print_comparisons_json(const std::vector<RendererComparison>& results, double alpha,
                            const Provenance& provenance) {
  if (results.size() == 1) {
    std::cout << dump_json_output(comparison_json(results[0], alpha, provenance), 2) << "\n";
  } else {
    nlohmann::ordered_json all = nlohmann::ordered_json::array();
    for (const auto& r : results) all.push_back(comparison_json(r, alpha, provenance));
    std::cout << dump_json_output(all, 2) << "\n";
  }
}

// One sentence per model, then how the intervals and tests were made and where the numbers come from.
void print_comparisons_text(const std::vector<RendererComparison>& results, const CompareOptions& co,
                            const Provenance& provenance) {
  for (const auto& r : results) {
    std::cout << comparison_sentence(r, level_of_interval(co.bootstrap.level)) << "\n";
    if (!std::isnan(r.result.delta_common))
      std::cout << fmt::format("  over the {} ref rocks paired in both: ΔIPD = {}\n",
                               grouped_thousands(r.result.pairs_common),
                               minus_number(r.result.delta_common, 4));  // the sentence's minus sign
  }
  // A row of fewer than 2 scenes has neither interval nor test (its sentence says so).
  const auto tested = [](const RendererComparison& r) { return r.result.scenes >= 2; };
  const bool all_exact =
      std::all_of(results.begin(), results.end(), [&](const auto& r) { return r.result.exact_p || !tested(r); });
  const std::string test =
      co.permutations == 0 ? std::string("not run (--permutations 0)")
      : all_exact          ? std::string("exact: every swap pattern of the scenes")
                  : fmt::format("{} permutations, exact where 2^scenes ≤ that", grouped_thousands(co.permutations));
  if (std::none_of(results.begin(), results.end(), tested))
    std::cout << "(intervals and tests need at least 2 scenes)\n";
  else
    std::cout << fmt::format(
        "({:g}% paired scene-bootstrap interval, {} resamples; sign-flip permutation test, "
        "{}; seed {})\n",
        100 * co.bootstrap.level, grouped_thousands(co.bootstrap.resamples), test, co.bootstrap.seed);
  std::cout << provenance_note(provenance) << "\n";
}

int run_compare(const CompareArgs& args) {
  StudyOptions so = args.study;
  const Study study = open_study_with_conf(so);
  if (args.json) require_utf8_names(study);  // before the work, naming the file
  const std::string ref = domain_or_default(study, args.ref, 0, "--ref");
  const std::string a = domain_or_default(study, args.a, 1, "--a");
  const std::string b = domain_or_default(study, args.b, 2, "--b");
  if (ref == a || ref == b || a == b)
    throw StudyError(fmt::format("compare needs three different domains, got --ref {} --a {} --b {}", ref, a, b));
  so.domains = {ref, a, b};
  // The comparison reads IPD(ref, a) and IPD(ref, b): the pair (a, b) is never registered.
  auto loaded = load_study_table(study, so, false, {false, {{ref, a}, {ref, b}}, false});
  if (!loaded) return kBadInput;
  CompareOptions co;
  co.bootstrap = loaded->bootstrap;
  co.permutations = args.permutations;
  if (const auto e = co.validate(); !e.empty()) throw CLI::ValidationError(e);
  const std::vector<RendererComparison> results = compare_each_model(*loaded, so, study.root, ref, a, b, co);
  // Which label files and hand edits the comparison's numbers come from.
  const Provenance provenance = table_provenance(loaded->table, loaded->labels);
  if (args.json)
    print_comparisons_json(results, level_of_interval(co.bootstrap.level), provenance);
  else
    print_comparisons_text(results, co, provenance);
  return kOk;
}

}  // namespace

Runner add_compare_command(CLI::App& app) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd =
      app.add_subcommand("compare", "Which renderer is closer to the reference: ΔIPD = IPD(ref, a) - IPD(ref, b)");
  declare_compare_options(cmd, args.get());
  return [args]() -> int { return run_compare(*args); };
}

}  // namespace ipd::cli
