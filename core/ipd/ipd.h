// The paper's Algorithm 1: performance-values per rock, rock pairs per image pair, IPD per domain pair and
// model, and the cross table (rows: models by training domain; columns: domain pairs).
#pragma once

#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/io/label_io.h"
#include "core/registration/registration.h"
#include "core/study/study.h"
#include "core/util/nested_lookup.h"

namespace ipd {

// Every label file of a study, parsed once, with all problems found.
struct StudyLabels {
  Study study;
  std::map<std::string, std::map<std::string, LabelFile>> gt;  // domain -> stem -> GT
  // domain -> model -> stem -> predictions; a model absent here has no predictions for that domain
  ByDomainModelStem<LabelFile> predictions;
  std::vector<LabelError> errors;
  // The class: study.config.rock_class is the class every number is about (settle_class), `requested_class` what
  // study.yaml or --class asked for; GT boxes per class as read; why a class must be chosen ("" when it needn't).
  int requested_class = kNoClassChosen;
  std::map<int, long> gt_boxes_by_class;
  std::string class_choice_needed;
  std::vector<std::string> class_warnings;  // prediction sets whose class numbers look shifted
  // The task (study.config.task): why its instances can't be scored ("" when they can: segment needs an outline
  // on every instance), and a note when outlines are read as boxes (detect).
  std::string task_needs_outlines;
  std::string task_note;
  // label_set_fingerprint(study) when the parsed-study cache knows it (every GT file read back unchanged, or read
  // and hashed by this load); "" when nobody computed it yet (label_set_fingerprint_of then reads the files).
  std::string label_fingerprint;

  const LabelFile& gt_of(const std::string& domain, const std::string& stem) const;
  const LabelFile& predictions_of(const std::string& domain, const std::string& model, const std::string& stem) const;
  bool has_predictions(const std::string& domain, const std::string& model) const;
};

// Lets load_labels take a file parsed earlier (study_cache.h): called from worker threads before each file
// is read (model empty for GT); true when it filled `out` exactly as reading the file would have.
using LabelReuse = std::function<bool(const std::string& domain, const std::string& model, const std::string& stem,
                                      const std::string& path, LabelFile* out)>;

// Reads every label and prediction file (class filter and confidence threshold from the study config).
// `progress` (optional) is called from worker threads with files read so far. `only_domains` (empty: every
// domain) reads those domains' files alone, the study staying whole (its other domains' scenes still known): a
// ranking run again reads the reference and the candidates it computes, nothing else (rank_cache.h).
StudyLabels load_labels(const Study& study, const std::function<void(int done, int total)>& progress = {},
                        const LabelReuse& reuse = {}, const std::vector<std::string>& only_domains = {});

// Every number is about one class (as pycocotools evaluates per category). Counts the GT boxes of each class;
// when none was asked for and the ground truth holds one class, that class is chosen (predictions of others are
// dropped); when it holds more, class_choice_needed says so, listing the classes and their box counts.
void settle_class(StudyLabels* labels);
std::string class_choice_message(const StudyLabels& labels);
// Throws StudyError(class_choice_needed) when a class must be chosen: no output may mix classes unasked.
void require_class_choice(const StudyLabels& labels);
// Checks the instances against the task (task_choice.cpp): under segment every instance needs an outline, under
// detect outlines are read as their bounds (with a note).
void settle_task(StudyLabels* labels);
// Throws StudyError when a class must be chosen or the task can't score the instances: every command that prints
// a number calls it.
void require_choices(const StudyLabels& labels);
// The class a number is about, for provenance: "rock (class 0)", "class 2", "all, class-blind (--class all)".
std::string class_statement(const StudyLabels& labels);
// Prediction sets whose boxes detect (IoU >= 0.5) GT of one other class far more than GT of their own class: the
// signature of class numbers shifted between two tools, with the --class-map that would undo it.
std::vector<std::string> shifted_class_warnings(const StudyLabels& labels);

// How the rocks of one image pair were paired.
struct ScenePairing {
  std::string stem;
  RockPairs pairs;
  bool fixed = false;  // from pairs/<A>__<B>/<stem>.json
  std::vector<int> excluded_a, excluded_b;
  int count_a = 0, count_b = 0;
  RegistrationReport registration;  // meaningful when !fixed
  bool from_cache = false;          // registration read from the on-disk cache
  // The pairs files' problems (rocks found again by box, pairs files in both name orders, hand pairs
  // unusable because a stored rock is gone: then !fixed and registration counts).
  std::vector<PairsProblem> pairs_problems;
};

class RegistrationCache;
// One scene as pair_study (study_pipeline.h) pairs it: its fixed pairs, else its registration.
// `cache` (may be null): registration results on disk (registration_cache.h).
ScenePairing pair_scene(const StudyLabels& labels, const std::string& a, const std::string& b, const std::string& stem,
                        const RegistrationOptions& options, const RegistrationCache* cache = nullptr);

// One image pair's contribution for one model.
struct SceneIpd {
  std::string stem;
  std::vector<double> perf_a, perf_b;  // per pair, in pairing order
  RockPairs counted;                   // the (index in A, index in B) of each counted pair, same order
  double sum_abs_diff = 0;
  int pairs = 0, unpaired_a = 0, unpaired_b = 0;
  double ipd() const;  // NaN when there are no pairs
};

// The one rule for a scene's counts (the engine's table and the GUI's header both use it): a pair counts
// unless one of its rocks is excluded; a rock in two pairs counts once; `unpaired` counts rocks in no pair
// that are not excluded (an excluded rock, or the partner of one, is out of the IPD, not unpaired).
// `perf_a`/`perf_b`: each rock's performance value. Pair indices must be in range.
SceneIpd scene_contribution(const std::string& stem, const RockPairs& pairs, const std::vector<int>& excluded_a,
                            const std::vector<int>& excluded_b, const std::vector<double>& perf_a,
                            const std::vector<double>& perf_b);

// `task`: what a performance value is (box or mask IoU; study.config.task).
SceneIpd scene_ipd(const ScenePairing& pairing, const std::vector<Box>& gt_a, const std::vector<Box>& pred_a,
                   const std::vector<Box>& gt_b, const std::vector<Box>& pred_b, Task task);

struct TableCell {
  std::string model, trained_on, a, b;
  double ipd = 0;  // NaN when no pairs or no predictions
  // scene-bootstrap interval and standard error (ipd/study_statistics.h); NaN until computed
  double ci_low = std::nan(""), ci_high = std::nan(""), se = std::nan("");
  long pairs = 0, unpaired_a = 0, unpaired_b = 0;
  int scenes = 0;
  double sum_abs_diff = 0;               // over the scenes counted: ipd is this / pairs (settle_table_cell)
  bool involves_training_domain = true;  // false: computed, but shown as "–" like the paper
  bool missing_predictions = false;
  // Why the cell is not a number although both domains have prediction sets (no_predictions_reason):
  // "no predictions at or above 0.98 in real and principled". Shown beside its "–"; empty for a number.
  std::string no_value_reason;
  std::vector<SceneIpd> per_scene;
};

// The rule for "no predictions is not a perfect renderer": when neither domain has a prediction left (after
// the class filter and the confidence threshold) in the scenes compared, every rock's performance value is 0
// on both sides and IPD 0 would say "identical" about two empty prediction sets, so there is no number. One
// side without predictions is a number (every rock there missed: a real, if alarming, gap) and a warning.
// Returns the reason ("no predictions at or above 0.98 in real and principled", "no predictions in real and
// principled" without a threshold), or "" when either side has predictions.
std::string no_predictions_reason(long predictions_a, long predictions_b, const std::string& a, const std::string& b,
                                  double threshold);
// The warning when only `domain` has none: "model 'det' has no predictions at or above 0.98 in 'real' (its scenes
// compared with 'principled'): every rock there counts as missed, as a detector that found nothing".
std::string one_side_without_predictions(const std::string& model, const std::string& domain, const std::string& other,
                                         double threshold);
// Predictions of `model` left in `domain` over the scenes of `pairings`.
long count_predictions(const StudyLabels& labels, const std::string& domain, const std::string& model,
                       const std::vector<ScenePairing>& pairings);

// A cell for `model` on domains (a, b), numbers still empty; total_table_cell fills them from per_scene.
TableCell make_table_cell(const ModelInfo& model, const std::string& a, const std::string& b);
// Pairs, unpaired counts, scenes and the pooled IPD (Σ|diff| / pairs; NaN without pairs) from per_scene.
void total_table_cell(TableCell& cell);
// The running form of total_table_cell, for a view that swaps one scene's contribution after an edit (ipd-studio
// keeps per_scene beside the cell): adds scene `s` to the cell's sums (sign -1 takes it away) and settles the value.
void count_scene_in_cell(TableCell& cell, const SceneIpd& s, int sign = +1);
// The cell's value from its sums: the pooled IPD, NaN without pairs or with a no_value_reason (no predictions
// on either side is no number, whatever the sums).
void settle_table_cell(TableCell& cell);
// Marks a cell whose model has no prediction set for one of its domains (missing_predictions, with the reason
// its "n/a" is footnoted with: "no predictions of det for real and synth"). Returns the domains without one.
std::vector<std::string> mark_missing_predictions(TableCell& cell, const StudyLabels& labels);

struct CrossTable {
  std::vector<ModelInfo> models;
  std::vector<std::pair<std::string, std::string>> columns;  // domain pairs
  std::vector<TableCell> cells;                              // row-major: models x columns
  std::vector<std::vector<ScenePairing>> pairings;           // per column, in the cells' per_scene order
  std::vector<std::string> warnings;                         // skipped scenes, missing predictions
  // Every scene's pairs-file problems, in column and scene order; the ones that are not `unusable` are also
  // in `warnings`. An unusable one is an error for the CLI (exit 1 unless --skip-bad-lines).
  std::vector<PairsProblem> pairs_problems;
  int registrations = 0, fixed_scenes = 0;
  int cached_registrations = 0;  // of `registrations`, read from the on-disk cache
  double registration_ms = 0;

  const TableCell* cell(const std::string& model, const std::string& a, const std::string& b) const;
};

// Domain pairs, each in either name order; empty: every domain pair there is.
using DomainPairFilter = std::vector<std::pair<std::string, std::string>>;
// Whether (a, b) is one of `only`'s pairs, in either name order, or `only` is empty (every pair).
bool includes_pair(const DomainPairFilter& only, const std::string& a, const std::string& b);

struct TableOptions {
  std::vector<std::string> models;   // empty: all
  std::vector<std::string> domains;  // empty: all
  RegistrationOptions registration;
  int threads = 0;  // 0: hardware concurrency
  std::function<void(int done, int total)> progress;
  std::string cache_dir;  // registration cache (registration_cache_dir()); empty: register every scene
  const RegistrationCache* registration_cache = nullptr;  // used instead of one in cache_dir when set
  // Register only the domain pairs where some chosen model's cell is shown (its training domain is in the pair):
  // the text, Markdown and LaTeX tables print "–" for the others, so registering them is wasted work. The
  // hidden columns' cells then have no scenes and no value (CSV and JSON print every cell: leave this off).
  bool shown_cells_only = false;
  // Register and compute only these domain pairs (either name order), the ones an output reads: a ranking's
  // (reference, candidate) pairs and never a candidate-vs-candidate one, a comparison's two, a breakdown's or a
  // gallery's one. The other columns' cells then have no scenes and no value. Empty: every pair (or the shown
  // ones).
  DomainPairFilter only_pairs;

  // Empty when usable; otherwise the field that is wrong and the accepted range, in one sentence. The
  // registration options check themselves where a scene is registered (a fully cached table needs none).
  std::string validate() const;
  // Throws std::invalid_argument("table options: " + validate()) when not usable.
  void check() const;
};

// The domain pairs (i < j in study order) of the chosen domains.
std::vector<std::pair<std::string, std::string>> domain_pairs(const Study& study,
                                                              const std::vector<std::string>& domains);

// Throws StudyError for unknown model or domain names, or fewer than two domains.
CrossTable compute_cross_table(const StudyLabels& labels, const TableOptions& options);

}  // namespace ipd
