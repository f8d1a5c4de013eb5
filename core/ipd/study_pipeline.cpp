#include "core/ipd/study_pipeline.h"

#include "core/study/fixed_pairs.h"
#include "core/study/unused_hand_files.h"

#include <fmt/format.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>
#include <unordered_set>

#include "core/registration/registration_cache.h"
#include "core/util/number_text.h"
#include "core/util/parallel.h"

namespace fs = std::filesystem;

namespace ipd {

ScenePairing PipelineScene::counted() const {
  if (!fixed) return automatic;
  ScenePairing p;
  p.stem = automatic.stem;
  p.count_a = automatic.count_a;
  p.count_b = automatic.count_b;
  p.fixed = true;
  p.pairs = fixed->pairs;
  p.excluded_a = fixed->excluded_a;
  p.excluded_b = fixed->excluded_b;
  p.pairs_problems = automatic.pairs_problems;
  return p;
}

namespace {

// Stems with a pairs file in pairs/<a>__<b>/ or pairs/<b>__<a>/, from two directory listings instead of two
// lookups per scene; nullopt when a directory can't be listed (then every scene is looked up).
std::optional<std::unordered_set<std::string>> stems_with_pairs_files(const Study& st, const std::string& a,
                                                                      const std::string& b) {
  std::unordered_set<std::string> out;
  for (const std::string& dir : {st.pairs_dir(a, b), st.pairs_dir(b, a)}) {
    std::error_code ec;
    // A link is not listed: every scene is then looked up, and the lookup refuses it (fixed_pairs.h).
    if (fs::is_symlink(fs::path(st.root) / "pairs", ec) || fs::is_symlink(dir, ec)) return std::nullopt;
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

// "a, b, c, ..." : the first three of a list.
std::string first_three(const std::vector<std::string>& v) {
  std::string s;
  for (size_t k = 0; k < std::min<size_t>(3, v.size()); ++k) s += (k ? ", " : "") + v[k];
  return s + (v.size() > 3 ? ", ..." : "");
}

// Scenes of the domains `in` that `other` lacks. One problem for all of them: a scene missing from one
// domain would otherwise be listed once for each domain pair it misses.
Problem no_counterpart(const std::vector<std::string>& only, const std::vector<std::string>& in,
                       const std::string& other) {
  Problem p;
  p.domain = in.front();
  if (only.size() == 1) p.scene = only.front();
  std::string names;
  for (size_t k = 0; k < in.size(); ++k)
    names += fmt::format("{}'{}'", k == 0 ? "" : k + 1 == in.size() ? " and " : ", ", in[k]);
  p.message = fmt::format("{} scene(s) of {} have no counterpart in '{}' and are skipped: {}", only.size(), names,
                          other, first_three(only));
  return p;
}

// Collects the scenes without a counterpart over the domain pairs, merging the same scenes missing from the
// same domain into the problem that first named them.
class MissingScenes {
 public:
  void add(const std::vector<std::string>& only, const std::string& in, const std::string& other,
           std::vector<Problem>* problems) {
    if (only.empty()) return;
    std::string key = other;
    for (const auto& s : only) key += "\n" + s;
    const auto [it, fresh] = seen_.try_emplace(key, Seen{problems->size(), {}});
    it->second.in.push_back(in);
    if (fresh)
      problems->push_back(no_counterpart(only, it->second.in, other));
    else
      (*problems)[it->second.at] = no_counterpart(only, it->second.in, other);
  }

 private:
  struct Seen {
    size_t at;                    // index of its problem
    std::vector<std::string> in;  // the domains that have these scenes
  };
  std::map<std::string, Seen> seen_;
};

// One scene: its pairs file (when `may_have_file`), else (or also) its registration. Problems of its pairs
// files go to `problems`.
PipelineScene pair_one(const StudyLabels& labels, const std::string& a, const std::string& b, const std::string& stem,
                       const RegistrationOptions& reg, bool register_fixed, bool may_have_file,
                       const RegistrationCache* cache, std::vector<Problem>* problems) {
  PipelineScene s;
  ScenePairing& p = s.automatic;
  p.stem = stem;
  const auto& ga = labels.gt_of(a, stem).boxes;
  const auto& gb = labels.gt_of(b, stem).boxes;
  p.count_a = static_cast<int>(ga.size());
  p.count_b = static_cast<int>(gb.size());
  if (may_have_file) {
    FixedPairsRead read = load_fixed_pairs(labels.study, a, b, stem, ga, gb);
    s.version_ab = read.version_ab;
    s.version_ba = read.version_ba;
    s.pairs_unusable = read.unusable();
    s.pairs_other_class = read.other_class;
    s.pairs_other_class_file = read.other_class_file;
    s.fixed = std::move(read.pairs);
    for (const PairsProblem& w : read.problems) problems->push_back(pairs_file_problem(w, a, b, stem));
    p.pairs_problems = std::move(read.problems);
  }
  if (!s.fixed || register_fixed) {
    p.registration = register_scene(labels, a, b, stem, reg, cache, &p.from_cache);
    p.pairs = p.registration.pairs;
  }
  return s;
}

}  // namespace

RegistrationOptions with_study_aspect(const Study& study, RegistrationOptions reg) {
  if (!reg.aspect) reg.aspect = study.aspect();
  return reg;
}

Problem square_pictures_problem(const Study& study, const RegistrationOptions& options) {
  Problem p;
  const bool pictures =
      std::any_of(study.domains.begin(), study.domains.end(), [](const Domain& d) { return !d.images.empty(); });
  if (options.aspect || study.config.image_width > 0 || pictures) return p;
  p.file = (std::filesystem::path(study.root) / "study.yaml").string();
  p.message =
      "no image_size and no pictures: registration takes the pictures as square (aspect 1), so its angles and "
      "distances are not the pictures' pixels and the pairs can differ from those of the real aspect; add "
      "'image_size: [WIDTH, HEIGHT]' (the pictures' size in pixels), as ipd register --image-size takes it";
  return p;
}

RegistrationReport register_scene(const StudyLabels& labels, const std::string& a, const std::string& b,
                                  const std::string& stem, const RegistrationOptions& options,
                                  const RegistrationCache* cache, bool* from_cache) {
  bool hit = false;
  RegistrationReport r = register_rocks_cached(cache, labels.gt_of(a, stem).boxes, labels.gt_of(b, stem).boxes,
                                               with_study_aspect(labels.study, options), &hit);
  if (from_cache) *from_cache = hit;
  return r;
}

ScenePairing pair_scene(const StudyLabels& labels, const std::string& a, const std::string& b, const std::string& stem,
                        const RegistrationOptions& options, const RegistrationCache* cache) {
  std::vector<Problem> ignored;
  return pair_one(labels, a, b, stem, options, false, true, cache, &ignored).counted();
}

std::vector<Problem> label_problems(const StudyLabels& labels) {
  std::vector<Problem> out;
  auto add = [&](const LabelFile& f, const std::string& domain, const std::string& stem) {
    for (const LabelError& e : f.errors) out.push_back(label_problem(e, domain, stem));
  };
  for (const Domain& d : labels.study.domains) {
    for (const std::string& stem : d.stems) add(labels.gt_of(d.name, stem), d.name, stem);
    for (const std::string& m : d.models)
      for (const std::string& stem : d.stems) add(labels.predictions_of(d.name, m, stem), d.name, stem);
  }
  // How class numbers were read, and prediction sets whose numbers look shifted: the studio lists them too.
  for (const std::string& note : labels.study.classes.notes) out.push_back({{}, 0, {}, {}, {}, note});
  for (const std::string& warning : labels.class_warnings) out.push_back({{}, 0, {}, {}, {}, warning});
  return out;
}

Problem missing_predictions_problem(const Study& study, const std::string& model, const std::string& domain) {
  Problem p;
  p.domain = domain;
  p.message = fmt::format("model '{}' has no predictions for domain '{}' (expected {}/): its cells are empty", model,
                          domain, (fs::path(study.root) / domain / "predictions" / model).string());
  return p;
}

std::optional<Problem> missing_prediction_files_problem(const StudyLabels& labels, const std::string& model,
                                                        const std::string& domain) {
  const Domain* d = labels.study.domain(domain);
  if (!d || !labels.has_predictions(domain, model)) return std::nullopt;
  // Only scenes some other domain has too: a scene without a counterpart is in no IPD (and said so already).
  // Stems are sorted: looked up in each other domain's list, not copied into a set (a table asks this once for
  // each model and domain).
  const auto elsewhere = [&](const std::string& stem) {
    return std::any_of(labels.study.domains.begin(), labels.study.domains.end(), [&](const Domain& other) {
      return other.name != domain && std::binary_search(other.stems.begin(), other.stems.end(), stem);
    });
  };
  const auto& files = labels.predictions.at(domain).at(model);
  std::vector<std::string> missing;
  for (const std::string& stem : d->stems) {
    const auto f = files.find(stem);
    if ((f == files.end() || !f->second.exists) && elsewhere(stem)) missing.push_back(stem);
  }
  if (missing.empty()) return std::nullopt;
  Problem p;
  p.domain = domain;
  if (missing.size() == 1) p.scene = missing.front();
  p.message = fmt::format(
      "model '{}' has no prediction file for {} scene(s) of '{}' (in {}/), each read as a picture without "
      "detections, as YOLOv5 writes no file for one: {}",
      model, grouped_thousands(static_cast<long long>(missing.size())), domain,
      (fs::path(labels.study.root) / domain / "predictions" / model).string(), first_three(missing));
  return p;
}

std::string PipelineOptions::validate() const {
  if (threads < 0) return fmt::format("threads must be >= 0 (0: hardware concurrency), got {}", threads);
  return {};
}

void PipelineOptions::check() const {
  if (const std::string problem = validate(); !problem.empty())
    throw std::invalid_argument("pipeline options: " + problem);
}

PairedStudy pair_study(const StudyLabels& labels, const std::vector<std::pair<std::string, std::string>>& pairs,
                       const PipelineOptions& options) {
  options.check();
  const Study& study = labels.study;
  PairedStudy out;
  struct Job {
    size_t pair, scene;
    const std::string* stem;
    bool may_have_file;
    std::vector<Problem> problems;
    std::string error;
  };
  std::vector<Job> jobs;
  std::set<std::string> reported_missing;  // a domain's missing label file, said once over its domain pairs
  MissingScenes missing;
  for (size_t c = 0; c < pairs.size(); ++c) {
    const auto& [a, b] = pairs[c];
    SceneMatch m = match_scenes(*study.domain(a), *study.domain(b));
    missing.add(m.only_a, a, b, &out.problems);
    missing.add(m.only_b, b, a, &out.problems);
    DomainPairScenes d{a, b, std::vector<PipelineScene>(m.common.size())};
    for (size_t k = 0; k < m.common.size(); ++k) {
      d.scenes[k].automatic.stem = m.common[k];
      // A scene kept by its picture whose label file is gone while its twin has one (a deleted or never
      // copied file, most likely): it reads as a picture without rocks, so it must not pass unsaid.
      for (const auto& [mine, other] : {std::pair(a, b), std::pair(b, a)}) {
        const LabelFile& f = labels.gt_of(mine, m.common[k]);
        if (f.exists || !labels.gt_of(other, m.common[k]).exists || !reported_missing.insert(f.path).second) continue;
        Problem q;
        q.file = f.path;
        q.domain = mine;
        q.other_domain = other;
        q.scene = m.common[k];
        q.message =
            fmt::format("no label file, while '{}' has one for this scene: read as a picture without rocks", other);
        out.problems.push_back(std::move(q));
      }
    }
    out.pairs.push_back(std::move(d));
  }
  for (Problem& p : unused_hand_files(study)) out.problems.push_back(std::move(p));
  for (size_t c = 0; c < pairs.size(); ++c) {
    const auto listed = stems_with_pairs_files(study, pairs[c].first, pairs[c].second);
    const auto& scenes = out.pairs[c].scenes;
    for (size_t k = 0; k < scenes.size(); ++k) {
      const std::string& stem = scenes[k].automatic.stem;
      jobs.push_back({c, k, &stem, !listed || listed->count(stem) > 0, {}, {}});
    }
  }
  const RegistrationOptions reg = with_study_aspect(study, options.registration);
  if (Problem p = square_pictures_problem(study, options.registration); !jobs.empty() && !p.message.empty())
    out.problems.push_back(std::move(p));
  const auto start = std::chrono::steady_clock::now();
  std::atomic<int> done{0};
  const int total = static_cast<int>(jobs.size());
  parallel_for(jobs.size(), options.threads, [&](size_t k) {
    Job& j = jobs[k];
    const auto& [a, b] = pairs[j.pair];
    try {
      out.pairs[j.pair].scenes[j.scene] = pair_one(labels, a, b, *j.stem, reg, options.register_fixed_scenes,
                                                   j.may_have_file, options.cache, &j.problems);
    } catch (const std::exception& e) {
      j.error = e.what();
    }
    const int d = ++done;
    if (options.progress) options.progress(d, total);
  });
  out.registration_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  for (Job& j : jobs) {
    if (!j.error.empty()) throw StudyError(j.error);
    const PipelineScene& s = out.pairs[j.pair].scenes[j.scene];
    out.fixed_scenes += s.fixed.has_value();
    out.registrations += !s.fixed || options.register_fixed_scenes;
    out.cached_registrations += s.automatic.from_cache;
    out.pairs_problems.insert(out.pairs_problems.end(), s.automatic.pairs_problems.begin(),
                              s.automatic.pairs_problems.end());
    for (Problem& p : j.problems) out.problems.push_back(std::move(p));
  }
  return out;
}

}  // namespace ipd
