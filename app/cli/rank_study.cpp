#include "app/cli/rank_study.h"

#include <fmt/format.h>

#include <algorithm>

#include "app/cli/rank_reuse.h"
#include "core/util/number_text.h"

namespace ipd::cli {

namespace {

// The one model a ranking is for: --model, else the study's model trained on the reference when there is one.
std::string ranked_model(const Study& study, const std::vector<std::string>& models, const std::string& ref) {
  if (models.size() > 1)
    throw CLI::ValidationError(fmt::format(
        "--model: a ranking is for one model (the detector that scores every setting), got {}", models.size()));
  if (models.size() == 1) return models.front();
  std::vector<std::string> on_ref, all;
  for (const auto& m : study.models) {
    all.push_back(m.name);
    if (m.trained_on == ref) on_ref.push_back(m.name);
  }
  if (on_ref.size() == 1) return on_ref.front();
  if (all.size() == 1) return all.front();
  std::string list;
  for (const auto& m : all) list += (list.empty() ? "" : ", ") + quoted_for_message(m);
  throw StudyError(fmt::format("{}: give --model: {} model{} trained on '{}' (the study's models: {})", study.root,
                               on_ref.empty() ? "no" : "more than one", on_ref.empty() ? " is" : "s are",
                               quoted_for_message(ref), list.empty() ? "none" : list));
}

// "24 candidates as the last ranking left them (their label and prediction files unchanged); 1 read and computed:
// ambient-100", or "all 25 candidates as ...".
std::string reuse_note(const std::vector<std::string>& reused, const std::vector<std::string>& candidates) {
  std::vector<std::string> computed;
  for (const std::string& c : candidates)
    if (std::find(reused.begin(), reused.end(), c) == reused.end()) computed.push_back(quoted_for_message(c));
  const bool one = reused.size() == 1;
  const std::string kept =
      fmt::format("{} {} as the last ranking left {} ({} label and prediction files unchanged)", reused.size(),
                  one ? "candidate" : "candidates", one ? "it" : "them", one ? "its" : "their");
  if (computed.empty()) return one ? kept : "all " + kept;
  const size_t shown = std::min<size_t>(computed.size(), 3);
  std::string names;
  for (size_t k = 0; k < shown; ++k) names += (k ? ", " : "") + computed[k];
  if (computed.size() > shown) names += fmt::format(" and {} more", computed.size() - shown);
  return fmt::format("{}; {} read and computed: {}", kept, computed.size(), names);
}

}  // namespace

void add_rank_options(CLI::App* cmd, RankArgs* args) {
  add_study_options(cmd, &args->study, true);
  cmd->add_option("--ref", args->ref, "Reference domain, e.g. real (default: the study's first)");
  cmd->add_option("--candidates", args->candidates,
                  "Candidate domains to rank (comma-separated; default: every other domain)")
      ->delimiter(',');
  cmd->add_option("--level", args->level,
                  "Significance level of the Holm-corrected comparisons with the best (default 0.05, as ipd compare)")
      ->check(CLI::Range(0.0001, 0.5));
  cmd->add_option("--permutations", args->permutations, "Permutations for each p-value (0: none)")
      ->check(CLI::NonNegativeNumber)
      ->default_val(2000);
}

std::optional<RankedStudy> rank_study(const RankArgs& args, const std::function<void(const Study&)>& check) {
  StudyOptions so = args.study;
  if (!so.domains.empty())
    throw CLI::ValidationError(
        "--domains: a ranking's domains are --ref and --candidates (default: every other domain)");
  const Study study = open_study_with_conf(so);
  if (check) check(study);
  RankOptions ro;
  ro.domains = resolve_rank_domains(study, args.ref, args.candidates);
  ro.model = ranked_model(study, so.models, ro.domains.ref);
  ro.level = args.level;
  ro.threads = so.threads;
  so.models = {ro.model};
  so.domains = ro.domains.candidates;
  so.domains.insert(so.domains.begin(), ro.domains.ref);
  const RegistrationOptions registration = registration_options(study, so);
  ro.compare.bootstrap = run_bootstrap(so, registration);
  ro.compare.permutations = args.permutations;
  if (const auto e = ro.validate(); !e.empty()) throw CLI::ValidationError(e);

  // What the last ranking of these settings kept: the candidates whose files are unchanged are not read again.
  const RankCache cache(so.no_cache ? std::string() : study.root,
                        rank_cache_settings(study, ro.model, ro.domains.ref, registration, ro.compare.bootstrap));
  std::optional<RankReusePlan> plan;
  if (cache.enabled()) plan = plan_rank_reuse(study, so, ro, registration, cache.settings());
  if (plan) {
    std::vector<std::string> reused;
    if (auto out = rank_from_kept(*plan, cache, &reused)) {
      fmt::print(stderr, "note: {}\n", reuse_note(reused, ro.domains.candidates));
      return out;
    }
  }

  // Registration is done for the (ref, candidate) pairs the ranking reads, never candidate against candidate.
  const ShownPairs shown{false, ranked_pairs(ro.domains), true};
  auto loaded = load_study_table(study, so, true, shown);
  if (!loaded) return std::nullopt;
  RankedStudy out{std::move(*loaded), {}, {}};
  out.ranking = rank_candidates(out.loaded.labels, out.loaded.table, ro);
  // Which label files and hand edits the numbers come from: over the (ref, candidate) pairs the ranking read.
  out.provenance = table_provenance(out.loaded.table, out.loaded.labels, shown.only);
  if (plan) keep_whole_ranking(*plan, cache, out);
  return out;
}

}  // namespace ipd::cli
