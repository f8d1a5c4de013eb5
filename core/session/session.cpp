#include "core/session/session.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <optional>
#include <set>
#include <unordered_set>

#include "core/util/atomic_file.h"
#include "core/util/parallel.h"
#include "core/registration/registration_cache.h"

namespace fs = std::filesystem;

namespace ipd {

namespace {
void remove_durably(const std::string& path) {
  std::error_code ec;
  if (!fs::remove(path, ec) && ec) throw IoError(path + ": cannot remove: " + ec.message());
  // Make the removal durable before the next step depends on it.
  const std::string dir = fs::path(path).has_parent_path() ? fs::path(path).parent_path().string() : ".";
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
}
}  // namespace

void run_save_job(const SaveJob& job, const WriteStepHook& hook) {
  // `path` is the name order read_fixed_pairs tries first: while it exists, the other one doesn't count.
  if (job.contents) {
    write_file_atomically(job.path, *job.contents, hook);
    for (const auto& p : job.also_remove) {
      remove_durably(p);
      if (hook) hook("other removed");
    }
  } else {
    for (const auto& p : job.also_remove) {
      remove_durably(p);
      if (hook) hook("other removed");
    }
    remove_durably(job.path);
    if (hook) hook("removed");
  }
}

double CellTotals::ipd() const { return pairs > 0 ? sum_abs_diff / static_cast<double>(pairs) : std::nan(""); }

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
  for (auto& d : study->domains)
    d.stems.erase(std::upper_bound(d.stems.begin(), d.stems.end(), last), d.stems.end());
}
}  // namespace

Session Session::open(const std::string& root, const SessionOptions& options) {
  Study study = open_study(root);
  if (options.first_scenes > 0) keep_first_scenes(&study, options.first_scenes);
  // Temp files of saves that died mid-way (their writer is gone) would otherwise pile up beside the pairs.
  std::error_code ec;
  for (fs::directory_iterator it(fs::path(study.root) / "pairs", ec); !ec && it != fs::directory_iterator();
       it.increment(ec))
    if (it->is_directory(ec)) remove_stale_temp_files(it->path().string());
  if (options.progress && !options.study_cache_path.empty()) options.progress("reading the study cache", 0, 0);
  StudyCache parsed(options.study_cache_path, study.root);
  StudyLabels labels = parsed.load_labels(study, [&](int done, int total) {
    if (options.progress) options.progress("label files", done, total);
  });
  RegistrationCache registration(options.cache_dir);
  registration.preload(parsed.take_registrations());
  SessionOptions with_cache = options;
  with_cache.registration_cache = &registration;
  Session session(std::move(labels), with_cache);
  parsed.save(session.labels(), registration);
  session.study_cache_stats_ = parsed.stats();
  return session;
}

namespace {
// Stems with a pairs file in pairs/<a>__<b>/ or pairs/<b>__<a>/, from two directory listings instead of two
// lookups per scene; nullopt when a directory can't be listed (then every scene is looked up).
std::optional<std::unordered_set<std::string>> stems_with_pairs_files(const Study& st, const std::string& a,
                                                                      const std::string& b) {
  std::unordered_set<std::string> out;
  for (const std::string& dir : {st.pairs_dir(a, b), st.pairs_dir(b, a)}) {
    std::error_code ec;
    if (!fs::exists(dir, ec)) {
      if (ec) return std::nullopt;
      continue;
    }
    for (fs::directory_iterator it(dir, ec); !ec && it != fs::directory_iterator(); it.increment(ec))
      if (it->path().extension() == ".json") out.insert(it->path().stem().string());
    if (ec) return std::nullopt;
  }
  return out;
}
}  // namespace

Session::Session(StudyLabels labels, const RegistrationOptions* registration)
    : Session(std::move(labels), SessionOptions{registration, {}, {}, 0, nullptr, {}}) {}

Session::Session(StudyLabels labels, const SessionOptions& options)
    : labels_(std::make_shared<const StudyLabels>(std::move(labels))) {
  const StudyLabels& labels_ref = *labels_;
  const Study& st = labels_ref.study;
  pairs_ = ipd::domain_pairs(st, {});
  RegistrationOptions reg = options.registration ? *options.registration : st.config.registration;
  if (reg.aspect == 1.0) reg.aspect = st.aspect();
  const RegistrationCache own_cache(options.registration_cache ? std::string() : options.cache_dir);
  const RegistrationCache& cache = options.registration_cache ? *options.registration_cache : own_cache;
  int total = 0;
  for (const auto& [a, b] : pairs_) total += static_cast<int>(match_scenes(*st.domain(a), *st.domain(b)).common.size());
  std::atomic<int> done{0}, cached{0};
  for (const auto& domain_pair : pairs_) {
    const std::string &a = domain_pair.first, &b = domain_pair.second;  // C++17 lambdas can't capture bindings
    const std::vector<std::string> stems = match_scenes(*st.domain(a), *st.domain(b)).common;
    std::vector<SceneState> list(stems.size());
    std::vector<std::string> errors(stems.size());
    const auto with_pairs_files = stems_with_pairs_files(st, a, b);
    // Registration is the heavy part of opening a study: every core takes scenes.
    parallel_for(stems.size(), 0, [&](size_t k) {
      SceneState& s = list[k];
      s.stem = stems[k];
      const auto& ga = labels_ref.gt_of(a, s.stem).boxes;
      const auto& gb = labels_ref.gt_of(b, s.stem).boxes;
      s.automatic.stem = s.stem;
      s.automatic.count_a = static_cast<int>(ga.size());
      s.automatic.count_b = static_cast<int>(gb.size());
      bool hit = false;
      s.automatic.registration = register_rocks_cached(&cache, ga, gb, reg, &hit);
      s.automatic.from_cache = hit;
      cached += hit;
      s.automatic.pairs = s.automatic.registration.pairs;
      s.current.pairs = s.automatic.pairs;
      try {
        const bool may_have_file = !with_pairs_files || with_pairs_files->count(s.stem);
        if (auto fixed = may_have_file ? read_fixed_pairs(st, a, b, s.stem, s.automatic.count_a, s.automatic.count_b)
                                       : std::nullopt) {
          s.current = std::move(*fixed);
          s.edited = s.fixed_on_disk = true;
        }
      } catch (const std::exception& e) {
        errors[k] = e.what();
      }
      const int d = ++done;
      if (options.progress && (d % 64 == 0 || d == total)) options.progress("registration", d, total);
    });
    for (const auto& e : errors)
      if (!e.empty()) throw StudyError(e);
    scenes_.push_back(std::move(list));
    audits_.emplace_back(scenes_.back().size());
    for (size_t k = 0; k < scenes_.back().size(); ++k) reaudit(static_cast<int>(scenes_.size()) - 1, static_cast<int>(k));
  }
  cached_ = cached;
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
  read_only_ = ::access(st.root.c_str(), W_OK) != 0 ||
               (fs::exists(pairs_dir, ec) && ::access(pairs_dir.c_str(), W_OK) != 0);
  recompute_performance();
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

void Session::reaudit(int pair, int scene) {
  const auto& [a, b] = pairs_[pair];
  const SceneState& s = scenes_[pair][scene];
  const Study& st = labels_->study;
  // Residuals in pixels; a study without image_size counts 1000 px across.
  const int w = st.config.image_width > 0 ? st.config.image_width : 1000;
  const int h = st.config.image_height > 0 ? st.config.image_height : static_cast<int>(std::lround(w / st.aspect()));
  audits_[pair][scene] = audit_pairs(labels_->gt_of(a, s.stem).boxes, labels_->gt_of(b, s.stem).boxes, s.current.pairs,
                                     s.automatic.registration.affine, w, h);
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
  s.ambiguous = scenes_[pair_][scene].automatic.registration.ambiguous;
  s.ambiguity = scenes_[pair_][scene].automatic.registration.ambiguity;
  if (it == contributions_.end()) {
    s.ipd = std::nan("");
    return s;
  }
  const SceneIpd& c = it->second[scene];
  s.ipd = c.ipd();
  s.pairs = c.pairs;
  s.unpaired_a = swapped_ ? c.unpaired_b : c.unpaired_a;
  s.unpaired_b = swapped_ ? c.unpaired_a : c.unpaired_b;
  return s;
}

CellTotals Session::totals_for(const std::string& model, int pair_index) const {
  const auto it = totals_.find({model, pair_index});
  if (it == totals_.end()) {
    CellTotals none;
    none.sum_abs_diff = std::nan("");
    return none;
  }
  return it->second;
}

const std::vector<SceneIpd>& Session::contributions_for(const std::string& model, int pair_index) const {
  static const std::vector<SceneIpd> kNone;
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
        for (const auto& p : labels_->predictions_of(d.name, m.name, d.stems[k]).boxes)
          if (p.conf >= conf_threshold_) shown.push_back(p);
        *slots[k].first = performance_values(labels_->gt_of(d.name, d.stems[k]).boxes, shown);
      });
    }
  }
  perf_ = std::move(perf);
  shown_predictions_ = std::move(shown_predictions);
  rebuild_totals();
}

void Session::rebuild_totals() {
  totals_.clear();
  contributions_.clear();
  for (const auto& m : labels_->study.models) {
    for (size_t p = 0; p < pairs_.size(); ++p) {
      if (!labels_->has_predictions(pairs_[p].first, m.name) || !labels_->has_predictions(pairs_[p].second, m.name))
        continue;
      auto& list = contributions_[{m.name, static_cast<int>(p)}];
      CellTotals& t = totals_[{m.name, static_cast<int>(p)}];
      for (size_t s = 0; s < scenes_[p].size(); ++s) {
        list.push_back(contribution(m.name, static_cast<int>(p), static_cast<int>(s)));
        t.sum_abs_diff += list.back().sum_abs_diff;
        t.pairs += list.back().pairs;
        t.unpaired_a += list.back().unpaired_a;
        t.unpaired_b += list.back().unpaired_b;
        ++t.scenes;
      }
    }
  }
}

void Session::set_conf_threshold(double threshold) {
  conf_threshold_ = std::clamp(threshold, 0.0, 1.0);
  recompute_performance();
}

SaveJob Session::job_for(int pair, int scene, const std::string& root) const {
  const auto& [a, b] = pairs_[pair];
  const SceneState& s = scenes_[pair][scene];
  SaveJob job;
  job.path = (fs::path(root) / "pairs" / (a + "__" + b) / (s.stem + ".json")).string();
  job.also_remove.push_back((fs::path(root) / "pairs" / (b + "__" + a) / (s.stem + ".json")).string());
  if (s.edited) job.contents = fixed_pairs_json(s.current);
  return job;
}

SaveJob Session::set_scene(int pair, int scene, const FixedPairs& fp, bool edited) {
  SceneState& s = scenes_[pair][scene];
  s.current = fp;
  std::sort(s.current.pairs.begin(), s.current.pairs.end());
  s.edited = edited;
  // Only this scene's contribution changes: swap it in every model's totals.
  for (auto& [key, list] : contributions_) {
    if (key.second != pair) continue;
    CellTotals& t = totals_[key];
    const SceneIpd& old = list[scene];
    t.sum_abs_diff -= old.sum_abs_diff;
    t.pairs -= old.pairs;
    t.unpaired_a -= old.unpaired_a;
    t.unpaired_b -= old.unpaired_b;
    list[scene] = contribution(key.first, pair, scene);
    t.sum_abs_diff += list[scene].sum_abs_diff;
    t.pairs += list[scene].pairs;
    t.unpaired_a += list[scene].unpaired_a;
    t.unpaired_b += list[scene].unpaired_b;
  }
  reaudit(pair, scene);
  last_scene_ = scene;
  return job_for(pair, scene, labels_->study.root);
}

SaveJob Session::apply(int scene, Edit e) {
  const SceneState& s = scenes_[pair_][scene];
  FixedPairs next = s.current;
  bool edited = true;
  // Sides of the view to sides of the domain pair.
  int ia = e.a, ib = e.b;
  if (swapped_ && e.kind == Edit::Kind::kPair) std::swap(ia, ib);
  const Side side = pair_side(e.side);
  auto erase_if = [](RockPairs& v, auto pred) { v.erase(std::remove_if(v.begin(), v.end(), pred), v.end()); };
  auto drop = [](std::vector<int>& v, int x) { v.erase(std::remove(v.begin(), v.end(), x), v.end()); };
  switch (e.kind) {
    case Edit::Kind::kPair:
      erase_if(next.pairs, [&](const auto& p) { return p.first == ia || p.second == ib; });
      next.pairs.emplace_back(ia, ib);
      drop(next.excluded_a, ia);
      drop(next.excluded_b, ib);
      break;
    case Edit::Kind::kUnpair:
      erase_if(next.pairs, [&](const auto& p) { return side == Side::kA ? p.first == e.a : p.second == e.a; });
      break;
    case Edit::Kind::kToggleExclude: {
      auto& list = side == Side::kA ? next.excluded_a : next.excluded_b;
      if (std::find(list.begin(), list.end(), e.a) != list.end()) drop(list, e.a);
      else list.push_back(e.a);
      std::sort(list.begin(), list.end());
      break;
    }
    case Edit::Kind::kReplacePairs:
      next.pairs = e.pairs;
      if (swapped_)
        for (auto& p : next.pairs) std::swap(p.first, p.second);
      break;
    case Edit::Kind::kResetToAutomatic:
      next = FixedPairs{};
      next.pairs = s.automatic.pairs;
      edited = false;
      break;
  }
  std::sort(next.pairs.begin(), next.pairs.end());
  history_.resize(undo_pos_);
  history_.push_back({pair_, scene, s.current, next, s.edited, edited});
  ++undo_pos_;
  return set_scene(pair_, scene, next, edited);
}

std::optional<SaveJob> Session::undo() {
  if (!can_undo()) return std::nullopt;
  const HistoryEntry& h = history_[--undo_pos_];
  pair_ = h.pair;
  return set_scene(h.pair, h.scene, h.before, h.edited_before);
}

std::optional<SaveJob> Session::redo() {
  if (!can_redo()) return std::nullopt;
  const HistoryEntry& h = history_[undo_pos_++];
  pair_ = h.pair;
  return set_scene(h.pair, h.scene, h.after, h.edited_after);
}

std::vector<SaveJob> Session::save_all_to(const std::string& other_root) const {
  std::vector<SaveJob> jobs;
  for (size_t p = 0; p < scenes_.size(); ++p)
    for (size_t s = 0; s < scenes_[p].size(); ++s)
      if (scenes_[p][s].edited) jobs.push_back(job_for(static_cast<int>(p), static_cast<int>(s), other_root));
  return jobs;
}

}  // namespace ipd
