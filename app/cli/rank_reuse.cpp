#include "app/cli/rank_reuse.h"

#include <fmt/format.h>

#include <algorithm>

#include "app/cli/cli_common.h"
#include "core/ipd/study_layout.h"
#include "core/ipd/study_pipeline.h"
#include "core/registration/registration_cache.h"
#include "core/report/provenance.h"
#include "core/study/unused_hand_files.h"
#include "core/util/errors.h"

namespace ipd::cli {

namespace {

// (x, y) the way round a table holds it (domain_pairs: in the study's domain order).
std::pair<std::string, std::string> table_pair(const Study& study, const std::string& x, const std::string& y) {
  const auto pairs = domain_pairs(study, {x, y});
  return pairs.empty() ? std::make_pair(x, y) : pairs.front();
}

size_t column_of(const CrossTable& t, const std::pair<std::string, std::string>& pair) {
  return static_cast<size_t>(std::find(t.columns.begin(), t.columns.end(), pair) - t.columns.begin());
}

PairProvenance pair_provenance(const CrossTable& table, size_t column, const StudyLabels& labels) {
  Provenance p;
  if (column < table.pairings.size()) add_column_provenance(table, column, labels, &p);
  PairProvenance out{p.scenes_with_hand_pairs,
                     p.pairs_set_by_hand,
                     p.rocks_excluded,
                     p.scenes_reviewed,
                     p.pairs_checked,
                     p.scenes_with_stale_hand_pairs,
                     {}};
  for (const EditedScene& e : p.edited_scenes) out.edited_stems.push_back(e.stem);
  return out;
}

void add_pair_provenance(const PairProvenance& part, const std::pair<std::string, std::string>& pair, Provenance* p) {
  p->scenes_with_hand_pairs += part.scenes_with_hand_pairs;
  p->pairs_set_by_hand += part.pairs_set_by_hand;
  p->rocks_excluded += part.rocks_excluded;
  p->scenes_reviewed += part.scenes_reviewed;
  p->pairs_checked += part.pairs_checked;
  p->scenes_with_stale_hand_pairs += part.scenes_with_stale_hand_pairs;
  for (const std::string& stem : part.edited_stems) p->edited_scenes.push_back({pair.first, pair.second, stem});
}

// The labels said nothing but numbers: no error, no class or task note or warning, no choice left to make.
bool labels_quiet(const StudyLabels& l) {
  return l.errors.empty() && l.class_warnings.empty() && l.class_choice_needed.empty() &&
         l.task_needs_outlines.empty() && l.task_note.empty();
}

// The digest `domain`'s cell is kept under; "" when the plan has none for it.
const std::string& inputs_of(const RankReusePlan& plan, const std::string& domain) {
  static const std::string kNever;
  const auto it = plan.inputs.find(domain);
  return it == plan.inputs.end() ? kNever : it->second;
}

std::optional<KeptComparison> kept_comparison(const Ranking& ranking, const std::string& candidate,
                                              const RankReusePlan& plan) {
  const RankedCandidate* best = ranking.best();
  for (const RankedCandidate& r : ranking.ranked)
    if (r.domain == candidate && r.vs_best)
      return KeptComparison{best->domain, inputs_of(plan, best->domain), plan.rank.compare.permutations, *r.vs_best};
  return std::nullopt;
}

bool no_predictions_at_threshold(const Ranking& ranking, const std::string& candidate) {
  for (const RankedCandidate& r : ranking.ranked)
    if (r.domain == candidate) return r.no_predictions_at_threshold;
  return false;
}

// The cells of candidates this run did not rank, kept as they were while their domain is in the study.
void keep_other_cells(const RankRecord& old, const RankReusePlan& plan, RankRecord* record) {
  const auto& candidates = plan.rank.domains.candidates;
  for (const KeptCell& k : old.cells)
    if (std::find(candidates.begin(), candidates.end(), k.candidate) == candidates.end() &&
        plan.study->domain(k.candidate))
      record->cells.push_back(k);
}

// The domains a run on kept cells reads: the reference, the candidates it computes and any domain whose files are
// not as they were kept (what it says, a label error or a class note, is said by a whole run too).
std::vector<std::string> domains_to_read(const RankReusePlan& plan, const RankRecord& kept,
                                         const std::vector<std::string>& fresh) {
  std::vector<std::string> read{plan.rank.domains.ref};
  for (const Domain& d : plan.study->domains) {
    const auto k = kept.domains.find(d.name);
    const bool as_kept = k != kept.domains.end() && k->second.stamps == plan.now.at(d.name).stamps;
    const bool computed = std::find(fresh.begin(), fresh.end(), d.name) != fresh.end();
    if (d.name != plan.rank.domains.ref && (computed || !as_kept)) read.push_back(d.name);
  }
  return read;
}

// The (reference, candidate) cells of `fresh` computed on `labels` as the whole run computes them, intervals
// included; nullopt when anything besides numbers comes of it.
std::optional<CrossTable> compute_fresh_cells(const RankReusePlan& plan, const StudyLabels& labels,
                                              const std::vector<std::string>& fresh) {
  TableOptions opt;
  opt.models = {plan.rank.model};
  opt.domains = plan.rank.domains.candidates;
  opt.domains.insert(opt.domains.begin(), plan.rank.domains.ref);
  opt.threads = plan.options->threads;
  opt.registration = plan.registration;
  // Registered in memory: the new variants' registrations live on in their kept cells.
  const RegistrationCache memory{std::string()};
  opt.registration_cache = &memory;
  for (const std::string& c : fresh) opt.only_pairs.emplace_back(plan.rank.domains.ref, c);
  Progress progress("registering");
  opt.progress = [&](int d, int t) { progress.update(d, t); };
  CrossTable t = compute_cross_table(labels, opt);
  if (!t.warnings.empty() || !t.pairs_problems.empty()) return std::nullopt;
  std::vector<std::pair<std::string, std::string>> computed;
  for (const auto& [a, b] : t.columns)
    if (includes_pair(opt.only_pairs, a, b)) computed.emplace_back(a, b);
  if (!layout_problems(labels, computed, t.models).empty()) return std::nullopt;
  if (plan.options->bootstrap > 0) add_confidence_intervals(&t, plan.rank.compare.bootstrap, plan.options->threads);
  return t;
}

}  // namespace

std::optional<RankReusePlan> plan_rank_reuse(const Study& study, const StudyOptions& options, const RankOptions& rank,
                                             const RegistrationOptions& registration, const std::string& settings) {
  RankReusePlan plan;
  plan.study = &study;
  plan.options = &options;
  plan.rank = rank;
  plan.registration = registration;
  try {
    plan.now = stamp_domains(study, options.threads);
    const DomainStamps& ref = plan.now.at(rank.domains.ref);
    for (const std::string& c : rank.domains.candidates) {
      const auto [a, b] = table_pair(study, rank.domains.ref, c);
      plan.inputs[c] = rank_cell_inputs(settings, a == c ? plan.now.at(c) : ref, a == c ? ref : plan.now.at(c), a, b,
                                        pair_file_stamps(study, a, b));
    }
  } catch (const std::exception&) {
    return std::nullopt;  // a link or an unreadable folder: the whole run reads the study and says what it is
  }
  return plan;
}

namespace {

// A ranking run on kept cells, as it goes.
struct KeptRun {
  const RankReusePlan& plan;
  const RankCache& cache;
  std::map<std::string, const KeptCell*> reused;  // the candidates taken as kept
  std::vector<std::string> fresh;                 // the others, read and computed
  StudyLabels labels;                             // the domains read
  std::optional<CrossTable> computed;             // the fresh candidates' cells
  CrossTable table;                               // the ranking's: one column a candidate, computed or kept

  const std::string& ref() const { return plan.rank.domains.ref; }
  std::pair<std::string, std::string> pair(const std::string& c) const { return table_pair(*plan.study, ref(), c); }
  const KeptCell* kept(const std::string& c) const {
    const auto k = reused.find(c);
    return k == reused.end() ? nullptr : k->second;
  }
};

// The ranking's table: each candidate's cell computed now or as kept (its scenes read when a comparison needs them).
void make_ranking_table(KeptRun& run) {
  const RankOptions& ro = run.plan.rank;
  for (const ModelInfo& m : run.plan.study->models)
    if (m.name == ro.model) run.table.models.push_back(m);
  for (const std::string& c : ro.domains.candidates) {
    run.table.columns.push_back(run.pair(c));
    const KeptCell* k = run.kept(c);
    run.table.cells.push_back(k ? k->cell : *run.computed->cell(ro.model, run.ref(), c));
  }
}

// Each candidate compared with the best: as kept while that comparison was with this best as it is now (the best's
// inputs name it) and as many permutations, else computed on the cells' scenes. False when a kept cell's scenes
// can't be read.
bool compare_with_kept(KeptRun& run, Ranking* ranking) {
  const RankOptions& ro = run.plan.rank;
  const std::string best = ranking->ranked.front().domain;
  std::map<std::string, const KeptComparison*> kept_vs_best;
  for (const auto& [c, k] : run.reused)
    if (k->vs_best && k->vs_best->best_inputs == inputs_of(run.plan, best) &&
        k->vs_best->permutations == ro.compare.permutations)
      kept_vs_best[c] = &*k->vs_best;
  auto with_scenes = [&](const std::string& d) {
    const auto& all = ro.domains.candidates;
    TableCell& cell = run.table.cells[static_cast<size_t>(std::find(all.begin(), all.end(), d) - all.begin())];
    if (!cell.per_scene.empty() || cell.scenes == 0) return true;
    auto scenes = run.cache.scenes(*run.kept(d));
    if (scenes) cell.per_scene = std::move(*scenes);
    return scenes.has_value();
  };
  bool compare_now = false;
  for (size_t k = 1; k < ranking->ranked.size(); ++k)
    if (!kept_vs_best.count(ranking->ranked[k].domain)) {
      if (!with_scenes(ranking->ranked[k].domain)) return false;
      compare_now = true;
    }
  if (compare_now && !with_scenes(best)) return false;
  compare_with_best(ranking, [&](const std::string& c, const std::string& b) {
    if (const auto k = kept_vs_best.find(c); k != kept_vs_best.end()) return k->second->comparison;
    return compare_renderers(run.table, ro.model, run.ref(), c, b, ro.compare);
  });
  return true;
}

// Keeps the run for the next one (the new cells with their scenes) and returns its provenance: the labels' part,
// then each candidate's pair in the order a table's columns have them.
Provenance keep_run(const KeptRun& run, const Ranking& ranking, const ResumedFingerprint& fingerprint) {
  const RankReusePlan& plan = run.plan;
  RankRecord record;
  std::map<std::string, PairProvenance> parts;
  for (const std::string& c : plan.rank.domains.candidates) {
    const KeptCell* k = run.kept(c);
    parts[c] = k ? k->provenance : pair_provenance(*run.computed, column_of(*run.computed, run.pair(c)), run.labels);
    KeptCell cell = k ? *k
                      : KeptCell{c,
                                 inputs_of(plan, c),
                                 *run.computed->cell(plan.rank.model, run.ref(), c),
                                 no_predictions_at_threshold(ranking, c),
                                 parts[c],
                                 {}};
    if (k) cell.cell.per_scene.clear();  // its scenes file is there already
    cell.vs_best = kept_comparison(ranking, c, plan);
    if (!cell.inputs.empty()) record.cells.push_back(std::move(cell));
  }
  record.fingerprint = fingerprint.fingerprint;
  record.checkpoints = fingerprint.checkpoints;
  record.domains = plan.now;
  keep_other_cells(run.cache.record(), plan, &record);
  run.cache.save(record);
  Provenance provenance = labels_provenance(run.labels);
  for (const Domain& d : plan.study->domains)
    if (parts.count(d.name)) add_pair_provenance(parts[d.name], run.pair(d.name), &provenance);
  return provenance;
}

}  // namespace

std::optional<RankedStudy> rank_from_kept(const RankReusePlan& plan, const RankCache& cache,
                                          std::vector<std::string>* reused_names) {
  const Study& study = *plan.study;
  const RankOptions& ro = plan.rank;
  const RankRecord& kept = cache.record();
  KeptRun run{plan, cache, {}, {}, {}, {}, {}};
  for (const std::string& c : ro.domains.candidates) {
    const auto inputs = plan.inputs.find(c);
    if (const KeptCell* k = inputs == plan.inputs.end() ? nullptr : cache.cell(c, inputs->second))
      run.reused[c] = k;
    else
      run.fresh.push_back(c);
  }
  if (run.reused.empty()) return std::nullopt;
  // What pairing says of the whole study, whichever pairs it pairs (pair_study): a run that pairs nothing new would
  // not say it, so a study with any of it is read whole.
  if (!unused_hand_files(study).empty() || !square_pictures_problem(study, plan.registration).message.empty())
    return std::nullopt;
  try {
    run.labels = load_labels(study, {}, {}, domains_to_read(plan, kept, run.fresh));
    if (!labels_quiet(run.labels)) return std::nullopt;
    if (!run.fresh.empty() && !(run.computed = compute_fresh_cells(plan, run.labels, run.fresh))) return std::nullopt;
    make_ranking_table(run);
    const ResumedFingerprint fingerprint = label_set_fingerprint(study, kept.checkpoints, [&](const std::string& d) {
      const auto k = kept.domains.find(d);
      return k != kept.domains.end() && k->second.gt_stamps == plan.now.at(d).gt_stamps;
    });
    run.labels.label_fingerprint = fingerprint.fingerprint;
    Ranking ranking = order_candidates(study, run.table, ro, [&](const std::string& c) {
      if (const KeptCell* k = run.kept(c)) return k->no_predictions_at_threshold;
      const size_t column = column_of(*run.computed, run.pair(c));
      return count_predictions(run.labels, c, ro.model, run.computed->pairings.at(column)) == 0;
    });
    if (!compare_with_kept(run, &ranking)) return std::nullopt;
    Provenance provenance = keep_run(run, ranking, fingerprint);
    report_class_notes(run.labels);
    for (const auto& [c, k] : run.reused) reused_names->push_back(c);

    RankedStudy out;
    out.loaded.labels = std::move(run.labels);
    out.loaded.table = std::move(run.table);
    out.loaded.conf_threshold = study.config.conf_threshold;
    out.loaded.registration_budget_ms = plan.registration.time_budget_ms.value_or(0);
    out.loaded.bootstrap = ro.compare.bootstrap;
    out.ranking = std::move(ranking);
    out.provenance = std::move(provenance);
    return out;
  } catch (const StudyError&) {
    return std::nullopt;  // the whole run meets it again and says it
  } catch (const IoError&) {
    return std::nullopt;
  }
}

void keep_whole_ranking(const RankReusePlan& plan, const RankCache& cache, const RankedStudy& ranked) {
  const LoadedStudy& l = ranked.loaded;
  if (!labels_quiet(l.labels) || !l.table.warnings.empty() || !l.table.pairs_problems.empty() ||
      l.labels.label_fingerprint.empty())
    return;
  const std::string& ref = plan.rank.domains.ref;
  RankRecord record;
  record.fingerprint = l.labels.label_fingerprint;
  record.checkpoints = l.fingerprint_checkpoints;
  record.domains = plan.now;
  for (const std::string& c : plan.rank.domains.candidates) {
    const TableCell* cell = l.table.cell(plan.rank.model, ref, c);
    if (!cell) return;
    const size_t column = column_of(l.table, table_pair(*plan.study, ref, c));
    if (inputs_of(plan, c).empty()) continue;
    record.cells.push_back({c, inputs_of(plan, c), *cell, no_predictions_at_threshold(ranked.ranking, c),
                            pair_provenance(l.table, column, l.labels), kept_comparison(ranked.ranking, c, plan)});
  }
  keep_other_cells(cache.record(), plan, &record);
  cache.save(record);
}

}  // namespace ipd::cli
