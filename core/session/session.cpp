#include "core/session/session.h"

#include <unistd.h>

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <set>

#include "core/geometry/confidence_threshold.h"
#include "core/ipd/study_layout.h"
#include "core/ipd/study_pipeline.h"
#include "core/registration/registration_cache.h"
#include "core/util/atomic_file.h"
#include "core/util/contained_file.h"
#include "core/util/parallel.h"

namespace fs = std::filesystem;

namespace ipd {

Session Session::open(const std::string& root, const RegistrationOptions* registration) {
  SessionOptions o;
  o.registration = registration;
  return open(root, o);
}

namespace {
// Keeps the scenes whose stem is among the first `n` of the study (all domains together), so that every
// domain pair's common scenes are a prefix of the whole study's.
void keep_first_scenes(Study* study, size_t n) {
  std::set<std::string> all;
  for (const auto& d : study->domains) all.insert(d.stems.begin(), d.stems.end());
  if (all.size() <= n) return;
  const std::string last = *std::next(all.begin(), static_cast<long>(n) - 1);
  for (auto& d : study->domains) d.stems.erase(std::upper_bound(d.stems.begin(), d.stems.end(), last), d.stems.end());
}
// Temp files of saves that died mid-way (their writer is gone) would otherwise pile up beside the pairs and
// the review marks: pairs/<A>__<B>/ and review/. Only real folders are tidied (a link in the study is never
// followed out of it: each folder is opened beneath the study, listed and tidied through its descriptor), and
// only regular files of our temp names (remove_stale_temp_files_beneath).
void remove_stale_saves(const std::string& root) {
  remove_stale_temp_files_beneath(root, "review");
  std::vector<std::string> pair_folders;
  try {
    pair_folders = folders_beneath(root, "pairs");
  } catch (const IoError&) {
    return;  // pairs/ is a link or unreadable: the study's scan says so; tidying is no place to stop
  }
  for (const std::string& f : pair_folders) remove_stale_temp_files_beneath(root, "pairs/" + f);
}

}  // namespace

Session Session::open(const std::string& root, const SessionOptions& options) {
  Study study = open_study(root);
  if (options.first_scenes > 0) keep_first_scenes(&study, options.first_scenes);
  remove_stale_saves(study.root);
  if (!options.class_word.empty()) study.config.rock_class = study.classes.resolve(options.class_word);
  // A window shows one class: with none chosen, the first the study names (rocks, as a rule) rather than a refusal.
  std::string class_note;
  const std::vector<std::string>& names = study.classes.names;
  const long named = std::count_if(names.begin(), names.end(), [](const std::string& n) { return !n.empty(); });
  if (study.config.rock_class == kNoClassChosen && named > 1)
    for (size_t k = 0; k < names.size() && study.config.rock_class == kNoClassChosen; ++k)
      if (!names[k].empty()) study.config.rock_class = static_cast<int>(k);
  if (options.progress && !options.study_cache_path.empty()) options.progress("reading the study cache", 0, 0);
  auto parsed = std::make_unique<StudyCache>(options.study_cache_path, study.root);
  auto load = [&]() {
    return parsed->load_labels(study, [&](int done, int total) {
      if (options.progress) options.progress("label files", done, total);
    });
  };
  StudyLabels labels = load();
  const bool unnamed_classes = !labels.class_choice_needed.empty();
  if (unnamed_classes) {  // classes without names: the lowest number present
    study.config.rock_class = labels.gt_boxes_by_class.begin()->first;
    parsed = std::make_unique<StudyCache>(options.study_cache_path, study.root);
    labels = load();
  }
  if (named > 1 || unnamed_classes || labels.requested_class == kAllClasses) {
    std::string all;
    for (size_t k = 0; k < names.size(); ++k)
      if (!names[k].empty()) all += (all.empty() ? "" : ", ") + names[k];
    class_note = fmt::format("showing {}{}; the class menu picks another", class_statement(labels),
                             all.empty() ? "" : " of " + all);
  }
  // The rule every command keeps (LabelError::unusable_file): a label file that can't be read stops the study.
  for (const LabelError& e : labels.errors)
    if (e.unusable_file()) throw StudyError(e.to_string() + " (every rock of the file would count as missing)");
  // As every command: under task segment a box without an outline would mix box and mask IoU in one number.
  if (!labels.task_needs_outlines.empty()) throw StudyError(labels.task_needs_outlines);
  if (labels.study.config.task == Task::kSegment)
    class_note = "mask IoU (task segment)" + (class_note.empty() ? "" : "; " + class_note);
  else if (!labels.task_note.empty())  // outlines drawn, boxes scored: said where the numbers are
    class_note = "box IoU: outlines read as their boxes (task: segment in study.yaml for mask IoU)" +
                 (class_note.empty() ? "" : "; " + class_note);
  RegistrationCache registration(options.cache_dir);
  parsed->hand_registrations_to(registration);
  SessionOptions with_cache = options;
  with_cache.registration_cache = &registration;
  Session session(std::move(labels), with_cache);
  parsed->save(session.labels(), registration);
  session.study_cache_stats_ = parsed->stats();
  session.class_note_ = class_note;
  return session;
}

Session::Session(StudyLabels labels, const RegistrationOptions* registration)
    : Session(std::move(labels), SessionOptions{registration, {}, {}, 0, nullptr, {}, {}}) {}

Session::Session(StudyLabels labels, const SessionOptions& options)
    : labels_(std::make_shared<const StudyLabels>(std::move(labels))) {
  const StudyLabels& labels_ref = *labels_;
  const Study& st = labels_ref.study;
  pairs_ = ipd::domain_pairs(st, {});
  PipelineOptions po;
  po.registration = options.registration ? *options.registration : st.config.registration;
  // Hand-paired scenes are registered when first needed (register_scene): opening reads their pairs only.
  po.register_fixed_scenes = false;
  registration_ = po.registration;
  cache_dir_ = options.registration_cache ? options.registration_cache->dir() : options.cache_dir;
  const RegistrationCache own_cache(options.registration_cache ? std::string() : options.cache_dir);
  po.cache = options.registration_cache ? options.registration_cache : &own_cache;
  if (options.progress)
    po.progress = [&](int done, int total) {
      if (done % 64 == 0 || done == total) options.progress("registration", done, total);
    };
  PairedStudy paired = pair_study(labels_ref, pairs_, po);
  for (DomainPairScenes& d : paired.pairs) {
    std::vector<SceneState> list(d.scenes.size());
    for (size_t k = 0; k < list.size(); ++k) {
      SceneState& s = list[k];
      s.automatic = std::move(d.scenes[k].automatic);
      s.stem = s.automatic.stem;
      s.current.pairs = s.automatic.pairs;
      s.disk_ab = d.scenes[k].version_ab;
      s.disk_ba = d.scenes[k].version_ba;
      s.pairs_unusable = d.scenes[k].pairs_unusable;
      s.pairs_other_class = d.scenes[k].pairs_other_class;
      s.pairs_other_class_file = d.scenes[k].pairs_other_class_file;
      s.pairs_problems = s.automatic.pairs_problems;
      if (d.scenes[k].fixed) {
        s.current = std::move(*d.scenes[k].fixed);
        s.edited = s.fixed_on_disk = true;
        s.registered = false;
      }
    }
    scenes_.emplace_back(std::move(list));
  }
  const std::vector<Problem> review_problems = load_reviews();  // before the audits: a checked pair is not suspect
  for (size_t p = 0; p < scenes_.size(); ++p) {
    const int pair = static_cast<int>(p);
    std::vector<SceneAudit> audits(scenes_[p].size());
    parallel_for(audits.size(), 0, [&](size_t k) { audits[k] = audit_of(pair, static_cast<int>(k)); });
    audits_.emplace_back(std::move(audits));
  }
  // Every problem the engine found, in the order the CLI reports them: label files, then scene matching and
  // pairs files, then review marks that no longer apply, then prediction sets that are missing.
  std::vector<Problem> problems = label_problems(labels_ref);
  problems.insert(problems.end(), paired.problems.begin(), paired.problems.end());
  problems.insert(problems.end(), review_problems.begin(), review_problems.end());
  for (const auto& m : st.models)
    for (const auto& d : st.domains)
      if (!labels_ref.has_predictions(d.name, m.name))
        problems.push_back(missing_predictions_problem(st, m.name, d.name));
      else if (auto p = missing_prediction_files_problem(labels_ref, m.name, d.name))
        problems.push_back(std::move(*p));
  // What the layout leaves out (two domains without a shared scene, labels in sub-folders, a prediction set
  // nested too deep, no GT of the class): the same words `ipd table` stops with.
  for (const LayoutProblem& p : layout_problems(labels_ref, domain_pairs(), st.models))
    problems.push_back({{}, 0, {}, {}, {}, p.message});
  problems_ = std::make_shared<const std::vector<Problem>>(std::move(problems));
  cached_ = paired.cached_registrations;
  if (!st.models.empty()) model_ = st.models.front().name;
  // Default view: the first model trained on the first domain, if any.
  for (const auto& m : st.models)
    if (!st.domains.empty() && m.trained_on == st.domains.front().name) {
      model_ = m.name;
      break;
    }
  const fs::path pairs_dir = fs::path(st.root) / "pairs";
  // (the study's root and pairs/ must be writable for edits to be saved)
  std::error_code ec;
  if (::access(st.root.c_str(), W_OK) != 0)
    set_read_only("the study folder is not writable");
  else if (fs::exists(pairs_dir, ec) && ::access(pairs_dir.c_str(), W_OK) != 0)
    set_read_only("the study's pairs/ folder is not writable");
  recompute_performance();
}

void Session::set_read_only(const std::string& reason) {
  read_only_ = true;
  read_only_reason_ = reason;
}

std::vector<PairsProblem> Session::pairs_problems() const {
  std::vector<PairsProblem> out;
  for (const auto& list : scenes_)
    for (const auto& sc : list) out.insert(out.end(), sc.pairs_problems.begin(), sc.pairs_problems.end());
  return out;
}

void Session::select(int pair_index, const std::string& model) {
  if (pair_index >= 0 && pair_index < static_cast<int>(pairs_.size())) pair_ = pair_index;
  model_ = model;
}

bool Session::select_domains(const std::string& a, const std::string& b) {
  for (size_t k = 0; k < pairs_.size(); ++k) {
    if (pairs_[k].first == a && pairs_[k].second == b) {
      pair_ = static_cast<int>(k);
      swapped_ = false;
      return true;
    }
    if (pairs_[k].first == b && pairs_[k].second == a) {
      pair_ = static_cast<int>(k);
      swapped_ = true;
      return true;
    }
  }
  return false;
}

const std::string& Session::left_domain() const { return swapped_ ? pairs_[pair_].second : pairs_[pair_].first; }
const std::string& Session::right_domain() const { return swapped_ ? pairs_[pair_].first : pairs_[pair_].second; }

Side Session::pair_side(Side v) const { return swapped_ ? (v == Side::kA ? Side::kB : Side::kA) : v; }

int Session::scene_index(const std::string& stem) const {
  const auto& list = scenes_[pair_];
  for (size_t k = 0; k < list.size(); ++k)
    if (list[k].stem == stem) return static_cast<int>(k);
  return -1;
}

const std::vector<Box>& Session::gt(Side side, int scene) const {
  return labels_->gt_of(domain_of(side), scenes_[pair_][scene].stem).boxes;
}

const std::string& Session::domain_of(Side side) const {
  return pair_side(side) == Side::kA ? pairs_[pair_].first : pairs_[pair_].second;
}

const std::vector<Box>& Session::predictions(Side side, int scene) const {
  static const std::vector<Box> none;
  return lookup(*shown_predictions_, domain_of(side), model_, scenes_[pair_][scene].stem, none);
}

const PerformanceValues& Session::performance(Side side, int scene) const {
  static const PerformanceValues none;
  return lookup(*perf_, domain_of(side), model_, scenes_[pair_][scene].stem, none);
}

bool Session::excluded(Side side, int scene, int rock) const {
  const auto& fp = scenes_[pair_][scene].current;
  const auto& list = pair_side(side) == Side::kA ? fp.excluded_a : fp.excluded_b;
  return std::find(list.begin(), list.end(), rock) != list.end();
}

RockPairs Session::view_pairs(int scene) const {
  RockPairs out = scenes_[pair_][scene].current.pairs;
  if (swapped_) {
    for (auto& p : out) std::swap(p.first, p.second);
    std::sort(out.begin(), out.end());
  }
  return out;
}

SceneAudit Session::audit_of(int pair, int scene) const {
  const SceneState& s = scenes_[pair][scene];
  if (!s.registered) {
    SceneAudit waiting;
    waiting.waits_for_registration = true;
    return waiting;
  }
  const auto& [a, b] = pairs_[pair];
  const Study& st = labels_->study;
  // Residuals in pixels; a study without image_size counts 1000 px across.
  const int w = st.config.image_width > 0 ? st.config.image_width : 1000;
  const int h = st.config.image_height > 0 ? st.config.image_height : static_cast<int>(std::lround(w / st.aspect()));
  SceneAudit audit = audit_pairs(labels_->gt_of(a, s.stem).boxes, labels_->gt_of(b, s.stem).boxes, s.current.pairs,
                                 s.automatic.registration.affine, w, h);
  // A pair judged correct by hand is no longer suspect: N skips it and it is drawn as an ordinary pair.
  for (PairAudit& p : audit.pairs)
    if (reviews_[pair]->is_checked(scene, p.a, p.b)) {
      p.checked = true;
      if (p.suspect) --audit.suspects;
      p.suspect = false;
    }
  return audit;
}

void Session::reaudit(int pair, int scene) { audits_[pair].set(scene, audit_of(pair, scene)); }

bool Session::register_scene(int pair, int scene) {
  if (pair < 0 || pair >= static_cast<int>(scenes_.size()) || scene < 0 ||
      scene >= static_cast<int>(scenes_[pair].size()) || scenes_[pair][scene].registered)
    return false;
  const auto& [a, b] = pairs_[pair];
  const RegistrationCache cache(cache_dir_);
  SceneState& s = scenes_[pair].edit(scene);
  s.automatic.registration =
      ipd::register_scene(*labels_, a, b, s.stem, registration_, &cache, &s.automatic.from_cache);
  s.automatic.pairs = s.automatic.registration.pairs;
  s.registered = true;
  reaudit(pair, scene);
  return true;
}

std::vector<char> Session::suspect_rocks(Side side, int scene) const {
  const bool side_a = pair_side(side) == Side::kA;
  std::vector<char> out(gt(side, scene).size(), 0);
  for (const auto& p : audits_[pair_][scene].pairs) {
    const int idx = side_a ? p.a : p.b;
    if (p.suspect && idx >= 0 && idx < static_cast<int>(out.size())) out[idx] = 1;
  }
  return out;
}

std::vector<SceneSummary> Session::summaries() const {
  std::vector<SceneSummary> out;
  out.reserve(scenes_[pair_].size());
  for (size_t k = 0; k < scenes_[pair_].size(); ++k) out.push_back(summary(static_cast<int>(k)));
  return out;
}

SceneSummary Session::summary(int scene) const {
  SceneSummary s;
  const auto it = contributions_.find({model_, pair_});
  s.stem = scenes_[pair_][scene].stem;
  s.edited = scenes_[pair_][scene].edited;
  s.suspects = audits_[pair_][scene].suspects;
  s.reviewed = reviewed(scene);
  s.ambiguous = scenes_[pair_][scene].automatic.registration.ambiguous;
  s.ambiguity = scenes_[pair_][scene].automatic.registration.ambiguity;
  if (it == contributions_.end()) {
    s.ipd = std::nan("");
    return s;
  }
  const SceneIpd& c = it->second[scene];
  s.ipd = c.ipd();
  const auto& [a, b] = pairs_[pair_];
  static const std::vector<Box> kNone;
  const size_t na = lookup(*shown_predictions_, a, model_, s.stem, kNone).size();
  const size_t nb = lookup(*shown_predictions_, b, model_, s.stem, kNone).size();
  s.no_value_reason = no_predictions_reason(static_cast<long>(na), static_cast<long>(nb), a, b, effective_threshold());
  if (!s.no_value_reason.empty()) s.ipd = std::nan("");
  s.pairs = c.pairs;
  s.unpaired_a = swapped_ ? c.unpaired_b : c.unpaired_a;
  s.unpaired_b = swapped_ ? c.unpaired_a : c.unpaired_b;
  return s;
}

TableCell Session::cell_for(const std::string& model, int pair_index) const {
  const auto it = totals_.find({model, pair_index});
  if (it != totals_.end()) return it->second;
  TableCell none;  // no such model or domain pair
  none.model = model;
  return none;
}

const CowVector<SceneIpd>& Session::contributions_for(const std::string& model, int pair_index) const {
  static const CowVector<SceneIpd> kNone;
  const auto it = contributions_.find({model, pair_index});
  return it == contributions_.end() ? kNone : it->second;
}

SceneIpd Session::contribution(const std::string& model, int pair, int scene) const {
  const auto& [a, b] = pairs_[pair];
  const SceneState& s = scenes_[pair][scene];
  return scene_contribution(s.stem, s.current.pairs, s.current.excluded_a, s.current.excluded_b,
                            perf_->at(a).at(model).at(s.stem).value, perf_->at(b).at(model).at(s.stem).value);
}

void Session::recompute_performance() {
  auto perf = std::make_shared<ByDomainModelStem<PerformanceValues>>();
  auto shown_predictions = std::make_shared<ByDomainModelStem<std::vector<Box>>>();
  for (const auto& d : labels_->study.domains) {
    for (const auto& m : labels_->study.models) {
      if (!labels_->has_predictions(d.name, m.name)) continue;
      // Fill the maps first (serially), then compute every scene on every core.
      auto& perf_of = (*perf)[d.name][m.name];
      auto& shown_of = (*shown_predictions)[d.name][m.name];
      std::vector<std::pair<PerformanceValues*, std::vector<Box>*>> slots;
      for (const auto& stem : d.stems) slots.emplace_back(&perf_of[stem], &shown_of[stem]);
      parallel_for(d.stems.size(), 0, [&](size_t k) {
        std::vector<Box>& shown = *slots[k].second;
        shown = predictions_kept(labels_->predictions_of(d.name, m.name, d.stems[k]).boxes, conf_threshold_);
        *slots[k].first =
            performance_values(labels_->gt_of(d.name, d.stems[k]).boxes, shown, labels_->study.config.task);
      });
    }
  }
  perf_ = std::move(perf);
  shown_predictions_ = std::move(shown_predictions);
  rebuild_totals();
}

std::vector<Problem> Session::problems() const {
  std::vector<Problem> out;
  // The pairs files' problems as the scenes hold them now, where opening listed them: "reset to automatic"
  // discards a stale file, and a reload (after a save conflict) can find the file on disk stale.
  bool pairs_files_listed = false;
  auto list_pairs_files = [&] {
    pairs_files_listed = true;
    for (size_t k = 0; k < pairs_.size(); ++k)
      for (const SceneState& s : scenes_[k])
        for (const PairsProblem& w : s.pairs_problems)
          out.push_back(pairs_file_problem(w, pairs_[k].first, pairs_[k].second, s.stem));
  };
  for (const Problem& p : *problems_)
    if (!p.pairs_file)
      out.push_back(p);
    else if (!pairs_files_listed)
      list_pairs_files();
  if (!pairs_files_listed) list_pairs_files();
  out.insert(out.end(), threshold_problems_.begin(), threshold_problems_.end());
  return out;
}

double Session::effective_threshold() const { return std::max(conf_threshold_, labels_->study.config.conf_threshold); }

long Session::shown_predictions(const std::string& domain, const std::string& model, int pair) const {
  long n = 0;
  static const std::vector<Box> kNone;
  for (const SceneState& s : scenes_[pair])
    n += static_cast<long>(lookup(*shown_predictions_, domain, model, s.stem, kNone).size());
  return n;
}

void Session::rebuild_totals() {
  totals_.clear();
  contributions_.clear();
  threshold_problems_.clear();
  for (const auto& m : labels_->study.models) {
    for (size_t p = 0; p < pairs_.size(); ++p) {
      const auto& [a, b] = pairs_[p];
      TableCell& t = totals_[{m.name, static_cast<int>(p)}];
      t = make_table_cell(m, a, b);
      if (!mark_missing_predictions(t, *labels_).empty()) continue;  // "n/a", as the table's
      std::vector<SceneIpd> list;
      for (size_t s = 0; s < scenes_[p].size(); ++s) {
        list.push_back(contribution(m.name, static_cast<int>(p), static_cast<int>(s)));
        count_scene_in_cell(t, list.back());
      }
      contributions_[{m.name, static_cast<int>(p)}] = CowVector<SceneIpd>(std::move(list));
      // The table's rule (compute_cross_table): no predictions on either side is no number; on one, a warning.
      const long na = shown_predictions(a, m.name, static_cast<int>(p)),
                 nb = shown_predictions(b, m.name, static_cast<int>(p));
      t.no_value_reason = no_predictions_reason(na, nb, a, b, effective_threshold());
      settle_table_cell(t);
      // Listed too, for the cells the table shows (those of the training domain; `ipd table` footnotes them): the
      // Problems window says why a cell has no number.
      if (!t.no_value_reason.empty() && t.involves_training_domain) {
        Problem q;
        q.domain = a;
        q.other_domain = b;
        q.message = fmt::format("model '{}': IPD({}, {}) is not a number: {}", m.name, a, b, t.no_value_reason);
        threshold_problems_.push_back(std::move(q));
      } else if (t.no_value_reason.empty() && (na == 0 || nb == 0)) {
        Problem q;
        q.domain = na == 0 ? a : b;
        q.other_domain = na == 0 ? b : a;
        q.message = one_side_without_predictions(m.name, q.domain, q.other_domain, effective_threshold());
        threshold_problems_.push_back(std::move(q));
      }
    }
  }
}

void Session::set_conf_threshold(double threshold) {
  conf_threshold_ = std::clamp(threshold, 0.0, 1.0);
  recompute_performance();
}

}  // namespace ipd
