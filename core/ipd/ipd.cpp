#include "core/ipd/ipd.h"

#include "core/ipd/study_pipeline.h"
#include "core/registration/registration_cache.h"
#include "core/util/nested_lookup.h"
#include "core/util/number_text.h"
#include "core/util/parallel.h"

#include <fmt/format.h>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>
#include <string_view>
#include <unordered_map>

namespace fs = std::filesystem;

namespace ipd {

namespace {
const LabelFile kEmpty{};
}

const LabelFile& StudyLabels::gt_of(const std::string& d, const std::string& stem) const {
  const auto di = gt.find(d);
  if (di == gt.end()) return kEmpty;
  const auto si = di->second.find(stem);
  return si == di->second.end() ? kEmpty : si->second;
}

const LabelFile& StudyLabels::predictions_of(const std::string& d, const std::string& m, const std::string& s) const {
  return lookup(predictions, d, m, s, kEmpty);
}

bool StudyLabels::has_predictions(const std::string& d, const std::string& m) const {
  const auto di = predictions.find(d);
  return di != predictions.end() && di->second.count(m) > 0;
}

StudyLabels load_labels(const Study& study, const std::function<void(int done, int total)>& progress,
                        const LabelReuse& reuse, const std::vector<std::string>& only_domains) {
  StudyLabels out;
  out.study = study;
  const int cls = study.config.rock_class;
  // Every file is read and parsed on every core into its own slot (the maps are filled first, serially);
  // errors are then gathered in file order, so the result does not depend on the thread count.
  struct Job {
    LabelFile* slot;
    std::string path, relative;  // relative: below the study's root, read without following links
    const std::string *domain, *model, *stem;
  };
  static const std::string kGroundTruth;  // the model of a GT file
  std::vector<Job> jobs;
  size_t files = 0;
  const auto read = [&](const Domain& d) {
    return only_domains.empty() || std::find(only_domains.begin(), only_domains.end(), d.name) != only_domains.end();
  };
  for (const auto& d : study.domains) files += read(d) ? d.stems.size() * (1 + d.models.size()) : 0;
  jobs.reserve(files);
  // Stems are listed in order: each slot goes in at its map's end, each path is its folder's plus the stem.
  for (const auto& d : study.domains) {
    if (!read(d)) continue;
    auto add = [&](std::map<std::string, LabelFile>& slots, const std::string& folder, const std::string& relative,
                   const std::string* model) {
      for (const auto& stem : d.stems)
        jobs.push_back({&slots.emplace_hint(slots.end(), stem, LabelFile{})->second, Study::label_file(folder, stem),
                        Study::label_file(relative, stem), &d.name, model, &stem});
    };
    add(out.gt[d.name], study.label_folder(d.name), d.name + "/labels", &kGroundTruth);
    for (const auto& m : d.models)
      add(out.predictions[d.name][m], study.prediction_folder(d.name, m), d.name + "/predictions/" + m, &m);
  }
  std::atomic<int> done{0};
  const int total = static_cast<int>(jobs.size());
  parallel_for(jobs.size(), 0, [&](size_t k) {
    const Job& j = jobs[k];
    const bool prediction = !j.model->empty();
    if (!reuse || !reuse(*j.domain, *j.model, *j.stem, j.path, j.slot)) {
      LabelFile f =
          read_labels_beneath(study.root, j.relative, {prediction ? LabelKind::kPrediction : LabelKind::kGroundTruth});
      const std::string set = prediction ? *j.domain + "/predictions/" + *j.model : *j.domain + "/labels";
      map_label_classes(&f, study.classes, study.classes.id_map(*j.domain, *j.model), set + "/classes.txt");
      if (cls >= 0) keep_class(&f, cls);
      if (prediction) keep_confident(&f, study.config.conf_threshold);
      *j.slot = std::move(f);
    }
    const int d = ++done;
    if (progress && (d % 256 == 0 || d == total)) progress(d, total);
  });
  for (const Job& j : jobs) out.errors.insert(out.errors.end(), j.slot->errors.begin(), j.slot->errors.end());
  settle_class(&out);
  settle_task(&out);
  return out;
}

double SceneIpd::ipd() const { return pairs > 0 ? sum_abs_diff / pairs : std::nan(""); }

SceneIpd scene_contribution(const std::string& stem, const RockPairs& pairs, const std::vector<int>& excluded_a,
                            const std::vector<int>& excluded_b, const std::vector<double>& pa,
                            const std::vector<double>& pb) {
  SceneIpd s;
  s.stem = stem;
  // One flag byte a rock, A's then B's: a table of 10,000 scenes makes this call 90,000 times.
  enum : char { kUsed = 1, kExcluded = 2 };
  std::vector<char> flags(pa.size() + pb.size(), 0);
  char* fa = flags.data();
  char* fb = flags.data() + pa.size();
  for (int i : excluded_a) fa[i] |= kExcluded;
  for (int j : excluded_b) fb[j] |= kExcluded;
  s.perf_a.reserve(pairs.size());
  s.perf_b.reserve(pairs.size());
  s.counted.reserve(pairs.size());
  for (const auto& [i, j] : pairs) {
    if ((fa[i] & kUsed) || (fb[j] & kUsed)) continue;
    fa[i] |= kUsed;
    fb[j] |= kUsed;
    if ((fa[i] & kExcluded) || (fb[j] & kExcluded)) continue;  // an excluded rock takes its pair out of the IPD
    s.perf_a.push_back(pa[i]);
    s.perf_b.push_back(pb[j]);
    s.counted.emplace_back(i, j);
    s.sum_abs_diff += std::abs(pa[i] - pb[j]);
    ++s.pairs;
  }
  for (size_t i = 0; i < pa.size(); ++i) s.unpaired_a += fa[i] == 0;
  for (size_t j = 0; j < pb.size(); ++j) s.unpaired_b += fb[j] == 0;
  return s;
}

SceneIpd scene_ipd(const ScenePairing& pairing, const std::vector<Box>& gt_a, const std::vector<Box>& pred_a,
                   const std::vector<Box>& gt_b, const std::vector<Box>& pred_b, Task task) {
  return scene_contribution(pairing.stem, pairing.pairs, pairing.excluded_a, pairing.excluded_b,
                            performance_values(gt_a, pred_a, task).value, performance_values(gt_b, pred_b, task).value);
}

namespace {
// A prediction at exactly the threshold is kept (conf >= T), so "above T" would be a shade wrong.
std::string above(double threshold) {
  return threshold > 0 ? fmt::format(" at or above {:g}", threshold) : std::string();
}
}  // namespace

std::string no_predictions_reason(long na, long nb, const std::string& a, const std::string& b, double threshold) {
  if (na > 0 || nb > 0) return {};
  return fmt::format("no predictions{} in {} and {}", above(threshold), a, b);
}

std::string one_side_without_predictions(const std::string& model, const std::string& domain, const std::string& other,
                                         double threshold) {
  return fmt::format(
      "model '{}' has no predictions{} in '{}' (its scenes compared with '{}'): every rock there "
      "counts as missed, as a detector that found nothing",
      model, above(threshold), domain, other);
}

long count_predictions(const StudyLabels& labels, const std::string& domain, const std::string& model,
                       const std::vector<ScenePairing>& pairings) {
  const auto d = labels.predictions.find(domain);
  if (d == labels.predictions.end()) return 0;
  const auto m = d->second.find(model);
  if (m == d->second.end()) return 0;
  long n = 0;  // the model's files of the domain looked up once, then each scene's
  for (const ScenePairing& p : pairings)
    if (const auto f = m->second.find(p.stem); f != m->second.end()) n += static_cast<long>(f->second.boxes.size());
  return n;
}

TableCell make_table_cell(const ModelInfo& model, const std::string& a, const std::string& b) {
  TableCell cell;
  cell.model = model.name;
  cell.trained_on = model.trained_on;
  cell.a = a;
  cell.b = b;
  cell.involves_training_domain = model.trained_on.empty() || model.trained_on == a || model.trained_on == b;
  return cell;
}

void count_scene_in_cell(TableCell& cell, const SceneIpd& s, int sign) {
  cell.sum_abs_diff += sign * s.sum_abs_diff;
  cell.pairs += sign * s.pairs;
  cell.unpaired_a += sign * s.unpaired_a;
  cell.unpaired_b += sign * s.unpaired_b;
  cell.scenes += sign;
  settle_table_cell(cell);
}

void settle_table_cell(TableCell& cell) {
  cell.ipd = cell.pairs > 0 && cell.no_value_reason.empty() ? cell.sum_abs_diff / static_cast<double>(cell.pairs)
                                                            : std::nan("");
}

void total_table_cell(TableCell& cell) {
  cell.sum_abs_diff = 0;
  cell.pairs = cell.unpaired_a = cell.unpaired_b = 0;
  cell.scenes = 0;
  for (const SceneIpd& s : cell.per_scene) count_scene_in_cell(cell, s);
  settle_table_cell(cell);
}

std::vector<std::string> mark_missing_predictions(TableCell& cell, const StudyLabels& labels) {
  std::vector<std::string> missing;
  for (const auto& d : {cell.a, cell.b}) {
    if (labels.has_predictions(d, cell.model)) continue;
    cell.missing_predictions = true;
    // The table's footnote for its "n/a" (the warning on stderr says where the folder was looked for).
    cell.no_value_reason += (cell.no_value_reason.empty() ? "no predictions of " + cell.model + " for " : " and ") + d;
    missing.push_back(d);
  }
  settle_table_cell(cell);
  return missing;
}

const TableCell* CrossTable::cell(const std::string& model, const std::string& a, const std::string& b) const {
  for (const auto& c : cells)
    if (c.model == model && ((c.a == a && c.b == b) || (c.a == b && c.b == a))) return &c;
  return nullptr;
}

std::vector<std::pair<std::string, std::string>> domain_pairs(const Study& study,
                                                              const std::vector<std::string>& domains) {
  std::vector<std::string> chosen;
  for (const auto& d : study.domains)
    if (domains.empty() || std::find(domains.begin(), domains.end(), d.name) != domains.end()) chosen.push_back(d.name);
  std::vector<std::pair<std::string, std::string>> out;
  for (size_t i = 0; i < chosen.size(); ++i)
    for (size_t j = i + 1; j < chosen.size(); ++j) out.emplace_back(chosen[i], chosen[j]);
  return out;
}

namespace {

// The study's models that `wanted` names (all of them when it is empty); an unknown name is an error.
std::vector<ModelInfo> chosen_models(const Study& study, const std::vector<std::string>& wanted) {
  std::vector<ModelInfo> models;
  for (const auto& m : study.models)
    if (wanted.empty() || std::count(wanted.begin(), wanted.end(), m.name)) models.push_back(m);
  for (const auto& want : wanted) {
    if (std::none_of(models.begin(), models.end(), [&](const auto& m) { return m.name == want; })) {
      std::string names;
      for (const auto& m : study.models) names += (names.empty() ? "" : ", ") + quoted_for_message(m.name);
      throw StudyError(fmt::format(
          "{}: no model '{}' (no <domain>/predictions/{}/ directory and not in study.yaml; the study's models: {})",
          study.root, quoted_for_message(want), quoted_for_message(want), names.empty() ? "none" : names));
    }
  }
  if (models.empty()) throw StudyError(study.root + ": no models (expected <domain>/predictions/<model>/ directories)");
  return models;
}

// The performance values of every (model, domain, scene) the shown cells read, each computed once and on every
// core: a domain's values for a model are the same in each domain pair it is in (two of three pairs in a
// three-domain table, every candidate's pair for a ranking's reference).
class PerformanceValueTable {
 public:
  // The scenes of one model in one domain: stem -> index of its values.
  using Scenes = std::unordered_map<std::string_view, size_t>;
  Scenes& scenes(size_t model, const std::string& domain) { return index_[{model, domain}]; }
  // The index of (model, domain, stem)'s values once computed.
  size_t need(Scenes& scenes, size_t model, const std::string& domain, const std::string& stem) {
    const auto [at, added] = scenes.emplace(stem, jobs_.size());
    if (added) jobs_.push_back({model, &domain, &stem});
    return at->second;
  }
  void compute(const StudyLabels& labels, const std::vector<ModelInfo>& models, int threads) {
    values_.resize(jobs_.size());
    parallel_for(jobs_.size(), threads, [&](size_t k) {
      const Job& j = jobs_[k];
      values_[k] = performance_values(labels.gt_of(*j.domain, *j.stem).boxes,
                                      labels.predictions_of(*j.domain, models[j.model].name, *j.stem).boxes,
                                      labels.study.config.task)
                       .value;
    });
  }
  const std::vector<double>& values(size_t k) const { return values_[k]; }

 private:
  struct Job {
    size_t model;
    const std::string* domain;  // the table's column names and pairing stems: they outlive the table
    const std::string* stem;
  };
  std::map<std::pair<size_t, std::string>, Scenes> index_;  // a std::map: its values stay where they are
  std::vector<Job> jobs_;
  std::vector<std::vector<double>> values_;
};

// One cell per (model, column) from the columns' rock pairs; a column not shown was never paired and has no value.
void add_cells(const StudyLabels& labels, const std::vector<bool>& shown, int threads, CrossTable* t) {
  const Study& study = labels.study;
  std::set<std::string> warned;
  // First each cell and whether it has predictions, then the performance values its scenes read, then the
  // scenes' IPD.
  PerformanceValueTable perf;
  std::vector<std::vector<std::string>> warnings;                 // each cell's, in the order the cells are made
  std::vector<std::vector<std::pair<size_t, size_t>>> values_of;  // each cell's scenes' values, A's and B's
  for (size_t m = 0; m < t->models.size(); ++m) {
    const ModelInfo& model = t->models[m];
    for (size_t c = 0; c < t->columns.size(); ++c) {
      const auto& [a, b] = t->columns[c];
      TableCell cell = make_table_cell(model, a, b);
      warnings.emplace_back();
      values_of.emplace_back();
      if (!shown[c]) {  // never registered: no scenes, no value
        total_table_cell(cell);
        t->cells.push_back(std::move(cell));
        continue;
      }
      const std::vector<std::string> missing = mark_missing_predictions(cell, labels);
      for (const auto& d : {a, b}) {
        if (!warned.insert(model.name + "\n" + d).second) continue;
        if (std::find(missing.begin(), missing.end(), d) != missing.end())
          warnings.back().push_back(missing_predictions_problem(study, model.name, d).to_string());
        else if (auto p = missing_prediction_files_problem(labels, model.name, d))
          warnings.back().push_back(p->to_string());
      }
      if (!cell.missing_predictions) {
        auto& in_a = perf.scenes(m, a);
        auto& in_b = perf.scenes(m, b);
        for (const ScenePairing& p : t->pairings[c])
          values_of.back().emplace_back(perf.need(in_a, m, a, p.stem), perf.need(in_b, m, b, p.stem));
      }
      t->cells.push_back(std::move(cell));
    }
  }
  perf.compute(labels, t->models, threads);
  for (size_t m = 0, k = 0; m < t->models.size(); ++m)
    for (size_t c = 0; c < t->columns.size(); ++c, ++k) {
      TableCell& cell = t->cells[k];
      for (std::string& w : warnings[k]) t->warnings.push_back(std::move(w));
      if (!shown[c]) continue;
      const auto& [a, b] = t->columns[c];
      if (!cell.missing_predictions) {
        const std::vector<ScenePairing>& scenes = t->pairings[c];
        const auto& values = values_of[k];
        cell.per_scene.resize(scenes.size());
        parallel_for(scenes.size(), threads, [&](size_t s) {
          const ScenePairing& p = scenes[s];
          cell.per_scene[s] = scene_contribution(p.stem, p.pairs, p.excluded_a, p.excluded_b,
                                                 perf.values(values[s].first), perf.values(values[s].second));
        });
      }
      total_table_cell(cell);
      if (!cell.missing_predictions) {
        const double threshold = study.config.conf_threshold;
        const long na = count_predictions(labels, a, cell.model, t->pairings[c]);
        const long nb = count_predictions(labels, b, cell.model, t->pairings[c]);
        cell.no_value_reason = no_predictions_reason(na, nb, a, b, threshold);
        settle_table_cell(cell);
        if (cell.no_value_reason.empty() && (na == 0 || nb == 0))
          t->warnings.push_back(one_side_without_predictions(cell.model, na == 0 ? a : b, na == 0 ? b : a, threshold));
      }
    }
}

}  // namespace

bool includes_pair(const DomainPairFilter& only, const std::string& a, const std::string& b) {
  if (only.empty()) return true;
  return std::any_of(only.begin(), only.end(),
                     [&](const auto& p) { return (p.first == a && p.second == b) || (p.first == b && p.second == a); });
}

std::string TableOptions::validate() const {
  if (threads < 0) return fmt::format("threads must be >= 0 (0: hardware concurrency), got {}", threads);
  return {};
}

void TableOptions::check() const {
  if (const std::string problem = validate(); !problem.empty())
    throw std::invalid_argument("table options: " + problem);
}

CrossTable compute_cross_table(const StudyLabels& labels, const TableOptions& options) {
  options.check();
  const Study& study = labels.study;
  for (const auto& d : options.domains) study.require_domain(d);
  for (const auto& [a, b] : options.only_pairs) study.require_domain(a), study.require_domain(b);
  CrossTable t;
  t.models = chosen_models(study, options.models);
  t.columns = domain_pairs(study, options.domains);
  if (t.columns.empty()) throw StudyError(study.root + ": at least two domains are needed to compare");

  // Pair rocks once per (domain pair, scene): pairing depends only on GT, never on the model.
  PipelineOptions po;
  po.registration = options.registration;
  po.threads = options.threads;
  po.progress = options.progress;
  const RegistrationCache own_cache(options.registration_cache ? std::string() : options.cache_dir);
  po.cache = options.registration_cache ? options.registration_cache : &own_cache;
  // A column is shown when some chosen model's training domain is in it (or the model names none).
  std::vector<bool> shown(t.columns.size(), true);
  std::vector<std::pair<std::string, std::string>> to_pair;
  for (size_t c = 0; c < t.columns.size(); ++c) {
    if (options.shown_cells_only) {
      const std::pair<std::string, std::string>& column = t.columns[c];
      shown[c] = std::any_of(t.models.begin(), t.models.end(), [&](const ModelInfo& m) {
        return make_table_cell(m, column.first, column.second).involves_training_domain;
      });
    }
    shown[c] = shown[c] && includes_pair(options.only_pairs, t.columns[c].first, t.columns[c].second);
    if (shown[c]) to_pair.push_back(t.columns[c]);
  }
  PairedStudy paired = pair_study(labels, to_pair, po);
  t.registrations = paired.registrations;
  t.fixed_scenes = paired.fixed_scenes;
  t.cached_registrations = paired.cached_registrations;
  t.registration_ms = paired.registration_ms;
  // Unusable hand pairs are errors for the CLI (CrossTable::pairs_problems), not warnings.
  for (const Problem& p : paired.problems)
    if (!p.unusable_pairs) t.warnings.push_back(p.to_string());
  t.pairs_problems = std::move(paired.pairs_problems);
  t.pairings.resize(t.columns.size());
  for (size_t c = 0, k = 0; c < t.columns.size(); ++c)
    if (shown[c])
      for (const PipelineScene& s : paired.pairs[k++].scenes) t.pairings[c].push_back(s.counted());

  add_cells(labels, shown, options.threads, &t);
  return t;
}

}  // namespace ipd
