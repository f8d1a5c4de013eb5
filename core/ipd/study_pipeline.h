// The one way a study's scenes become rock pairs, used by `ipd table` (compute_cross_table) and by the
// studio's Session: for each domain pair, the scenes present in both domains, each scene's hand-fixed pairs
// (pairs/<A>__<B>/<stem>.json) or its registration (through the registration cache), and the problems found
// on the way (scenes without a counterpart, pairs files that are ignored).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/ipd/ipd.h"
#include "core/study/problem.h"

namespace ipd {

class RegistrationCache;

struct PipelineOptions {
  // The registration of every scene without fixed pairs; an aspect left at 1.0 takes the study's own.
  RegistrationOptions registration;
  // Also register scenes that have fixed pairs (their automatic pairs); the studio leaves them for later
  // (register_scene) so a study with hand pairs opens without registering scenes nobody looks at.
  bool register_fixed_scenes = false;
  int threads = 0;                           // 0: hardware concurrency; the result does not depend on it
  const RegistrationCache* cache = nullptr;  // may be null: register every scene
  // Called from worker threads after each scene, with scenes done so far over all domain pairs.
  std::function<void(int done, int total)> progress;

  // Empty when usable; otherwise the field that is wrong and the accepted range, in one sentence. The
  // registration options check themselves where a scene is registered (hand-paired scenes need none).
  std::string validate() const;
  // Throws std::invalid_argument("pipeline options: " + validate()) when not usable.
  void check() const;
};

// One scene of a domain pair.
struct PipelineScene {
  // The registration's pairs (registration meaningful unless the scene has fixed pairs and
  // register_fixed_scenes was off); never fixed.
  ScenePairing automatic;
  std::optional<FixedPairs> fixed;  // the pairs file's, when there is one and it can be used
  bool pairs_unusable = false;      // a pairs file whose stored rocks are gone: registration counts
  int pairs_other_class = -1;       // the pairs file is another class's hand work (fixed_pairs.h), or -1
  std::string pairs_other_class_file;
  DiskVersion version_ab, version_ba;  // the pairs files as read (a save checks nobody changed them since)

  // What counts for the IPD: the fixed pairs when there are some, else the automatic ones.
  ScenePairing counted() const;
};

struct DomainPairScenes {
  std::string a, b;
  std::vector<PipelineScene> scenes;  // the scenes present in both domains, in stem order
};

struct PairedStudy {
  std::vector<DomainPairScenes> pairs;  // in the order asked for
  // Scenes without a counterpart (every domain pair's, in order), then ignored pairs files (scene order).
  std::vector<Problem> problems;
  // Every scene's pairs-file problems (rocks found again by box, both name orders, unusable hand pairs), in
  // domain-pair then scene order; also in `problems`.
  std::vector<PairsProblem> pairs_problems;
  int registrations = 0;         // scenes registered (fixed ones only with register_fixed_scenes)
  int cached_registrations = 0;  // of those, read from the cache
  int fixed_scenes = 0;          // scenes whose pairs file counts
  double registration_ms = 0;
};

// Every problem of the study's label and prediction files (malformed lines, unreadable files), in the order
// the files were read (each domain's GT, then its prediction sets), each with its domain and scene.
// A labels-only study whose study.yaml gives no image_size registers its scenes as square pictures: said once
// (study.yaml's problem, for ipd table's stderr and ipd-studio's Problems window), as ipd register says it
// without --image-size. Empty message when the aspect is known (image_size, or options.aspect given).
Problem square_pictures_problem(const Study& study, const RegistrationOptions& options);
std::vector<Problem> label_problems(const StudyLabels& labels);

// A model without a predictions folder for a domain: its cells for that domain are empty.
Problem missing_predictions_problem(const Study& study, const std::string& model, const std::string& domain);

// Scenes of `domain` whose prediction file of `model` is missing although the model's folder is there: each is
// read as a picture without detections (YOLOv5 writes no file for one), which can be right or a lost file, so
// it is said once, with the count and the first scenes. Only scenes another domain has count (the rest are in
// no IPD). Nothing when every such scene has its file.
std::optional<Problem> missing_prediction_files_problem(const StudyLabels& labels, const std::string& model,
                                                        const std::string& domain);

// The registration options every scene of the study is registered with: the study's aspect unless `reg` sets one.
RegistrationOptions with_study_aspect(const Study& study, RegistrationOptions reg);

// One scene's registration exactly as pair_study registers it (the study's aspect when `options` leave it at
// 1.0; through `cache`, which may be null): for a hand-paired scene opened without it. `from_cache` may be null.
RegistrationReport register_scene(const StudyLabels& labels, const std::string& a, const std::string& b,
                                  const std::string& stem, const RegistrationOptions& options,
                                  const RegistrationCache* cache, bool* from_cache = nullptr);

// Pairs every scene of every domain pair in `pairs` (domain names of the study). Throws StudyError for a
// pairs file that can't be used (the first one in domain-pair then scene order).
PairedStudy pair_study(const StudyLabels& labels, const std::vector<std::pair<std::string, std::string>>& pairs,
                       const PipelineOptions& options);

}  // namespace ipd
