// The state of an inspection session, apart from any drawing: a loaded study, the rock pairs of every
// image pair (automatic or hand-fixed), edits with undo/redo, and IPD figures kept up to date
// incrementally (an edit touches one scene's contribution, never the whole study).
//
// It owns no thread and does no file I/O after loading (apart from reload_scene, which the user asks for):
// edits produce SaveJobs that the caller writes (the GUI hands them to its saver thread).
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/ipd/ipd.h"
#include "core/ipd/study_cache.h"
#include "core/session/audit.h"
#include "core/session/review_state.h"
#include "core/study/problem.h"
#include "core/util/atomic_file.h"
#include "core/util/cow_vector.h"

namespace ipd {

enum class Side { kA, kB };

struct Edit {
  enum class Kind { kPair, kUnpair, kToggleExclude, kResetToAutomatic, kReplacePairs } kind;
  int a = -1, b = -1;  // kPair: both; kUnpair / kToggleExclude: the rock on `side`
  Side side = Side::kA;
  RockPairs pairs;  // kReplacePairs: (left, right) pairs, e.g. from re-running registration

  static Edit pair(int left, int right) { return {Kind::kPair, left, right, Side::kA, {}}; }
  static Edit unpair(Side side, int rock) { return {Kind::kUnpair, rock, -1, side, {}}; }
  static Edit toggle_exclude(Side side, int rock) { return {Kind::kToggleExclude, rock, -1, side, {}}; }
  static Edit reset() { return {Kind::kResetToAutomatic, -1, -1, Side::kA, {}}; }
  static Edit replace(RockPairs pairs) { return {Kind::kReplacePairs, -1, -1, Side::kA, std::move(pairs)}; }
};

// A file to write (atomically) or remove, so that `ipd table` sees what the session shows.
struct SaveJob {
  std::string path;
  std::optional<std::string> contents;   // nullopt: remove the file (back to automatic pairing)
  std::vector<std::string> also_remove;  // the same scene's file under the other name order
  // The study (or the folder chosen to save into) the paths are in: no symbolic link below it is written
  // through or deleted through (contained_file.h). Empty: a path the user gave, written as given.
  std::string root;
  // What this window last read or wrote at `path` and at each of `also_remove` (same order): the save is
  // refused with SaveConflict when the disk holds anything else. Empty: not checked.
  std::vector<DiskVersion> expected;
  int pair = -1;  // the domain pair (Session::domain_pairs()) and scene stem, for the conflict dialog
  std::string stem;
};

// A save refused because the file changed on disk since this window read or wrote it (another window, or
// an editor): the edit stays in memory; the user keeps one version (Session::reload_scene or an overwrite).
struct SaveConflict : IoError {
  SaveConflict(const std::string& message, std::string file, std::optional<std::string> on_disk,
               std::vector<DiskVersion> now)
      : IoError(message), file(std::move(file)), on_disk(std::move(on_disk)), observed(std::move(now)) {}
  std::string file;                    // the file that changed
  std::optional<std::string> on_disk;  // its contents now (nullopt: removed)
  std::vector<DiskVersion> observed;   // what the disk held at each path of the job (its `expected` order)
};

// Carries out a save job: atomic write, or removal. Throws IoError naming the file (SaveConflict when the
// disk no longer holds what the job expects; nothing is written then). Every file it would remove is
// checked before the first write: a symbolic link on the way refuses the whole job.
// Order: the file read first (`path`) is written (temp, fsync, rename, fsync of the directory) before the
// other name order is removed; going back to automatic removes the other name order first. A crash or a
// failure at any instant leaves the old pairs or the new ones, never neither. `hook` is called after each
// step ("temp written", "renamed", "directory synced", "other removed", "removed"); tests throw from it.
void run_save_job(const SaveJob& job, const WriteStepHook& hook = {});

struct SceneState {
  std::string stem;
  ScenePairing automatic;  // what registration found (meaningful when `registered`)
  // False for a scene opened with its hand pairs: it is registered when first needed (register_scene),
  // until then its audit says it waits for the registration.
  bool registered = true;
  FixedPairs current;   // what counts now
  bool edited = false;  // current differs from automatic and is saved as fixed pairs
  bool fixed_on_disk = false;
  // Problems of the scene's pairs files found when the study was opened (rocks found again by their
  // boxes, unusable hand pairs: then the automatic pairs count, `pairs_unusable`, and the file is kept:
  // edits of the scene are refused until the user resets it to automatic, which removes the file).
  std::vector<PairsProblem> pairs_problems;
  bool pairs_unusable = false;
  // The scene's pairs file holds another class's hand pairs (-1: it doesn't): registration counts here and
  // edits are refused, since saving them would overwrite that class's work.
  int pairs_other_class = -1;
  std::string pairs_other_class_file;
  // What this window last read or wrote at pairs/<A>__<B>/<stem>.json and pairs/<B>__<A>/<stem>.json.
  DiskVersion disk_ab, disk_ba;
};

// True when `fp` is the registered scene's automatic pairing: the same pairs, no rock excluded. An edit that
// arrives there leaves the scene automatic (no pairs file), not hand-edited.
bool matches_automatic(const SceneState& s, const FixedPairs& fp);

struct SceneSummary {
  std::string stem;
  double ipd = 0;  // NaN when no pairs
  int pairs = 0, unpaired_a = 0, unpaired_b = 0;
  bool edited = false;
  int suspects = 0;        // suspect pairs (audit_pairs), less those checked as correct (review_state.h)
  bool reviewed = false;   // marked as looked at (review_state.h)
  bool ambiguous = false;  // registration could not decide (RegistrationReport::ambiguous)
  // Why `ipd` is NaN although the scene has pairs: neither domain has a prediction left in it for the model
  // (no_predictions_reason, ipd.h). Its rocks still count in the cell, as rocks both domains missed.
  std::string no_value_reason;
  Ambiguity ambiguity = Ambiguity::kNone;  // and why (ambiguity_reason())
};

struct SessionOptions {
  const RegistrationOptions* registration = nullptr;  // null: the study's own
  std::string cache_dir;  // registration cache (registration_cache_dir()); empty: register every scene
  // Session::open: the parsed-study cache (parsed_study_cache_path(), study_cache.h); empty: none.
  std::string study_cache_path;
  // Session::open: > 0 opens only the first N scenes (by stem, the same cut in every domain): a first look
  // at a big study while the whole of it loads. Scene k of a domain pair is scene k of the whole study.
  size_t first_scenes = 0;
  // Used instead of a cache in `cache_dir` when set (Session::open passes one preloaded from the file).
  const RegistrationCache* registration_cache = nullptr;
  // Called from worker threads while opening: stage ("labels", "registration"), done, total.
  std::function<void(const char* stage, int done, int total)> progress;
  // Session::open: the class to show (a name, a number or "all"); empty: study.yaml's rock_class, else the first
  // class the study names, else the ground truth's lowest class when it holds more than one (class_note says so).
  std::string class_word;

  // Always empty: every value here is usable (null and empty mean "none"; any scene count is a cut), and the
  // registration options check themselves where a scene is registered.
  std::string validate() const { return {}; }
};

class Session {
 public:
  // Loads labels and pairs every image pair of every domain pair (the heavy part: run it off the UI thread).
  static Session open(const std::string& study_root, const RegistrationOptions* registration = nullptr);
  static Session open(const std::string& study_root, const SessionOptions& options);
  explicit Session(StudyLabels labels, const RegistrationOptions* registration = nullptr);
  Session(StudyLabels labels, const SessionOptions& options);
  // Copies are cheap enough to publish a snapshot after every change: labels are shared, not copied, and
  // the per-scene records, audits, contributions and undo history are CowVectors (a copy shares them; an
  // edit copies only the chunk of scenes it changes), so a copy costs one pointer per 128 scenes.

  const Study& study() const { return labels_->study; }
  const StudyLabels& labels() const { return *labels_; }
  // Which class is shown and why, when the study holds more than one: "showing rock (class 0) of rock, shadow;
  // the class menu picks another"; empty for a study with one class.
  const std::string& class_note() const { return class_note_; }
  int cached_registrations() const { return cached_; }
  // What the engine found wrong with the study's data while opening it (study_pipeline.h).
  // Opening's problems (its pairs files' as they are now: see Problem::pairs_file), then those of the current
  // threshold (a domain without predictions for a model).
  std::vector<Problem> problems() const;  // scenes whose registration came from the cache
  const StudyCacheStats& study_cache_stats() const { return study_cache_stats_; }  // Session::open only
  const std::vector<std::pair<std::string, std::string>>& domain_pairs() const { return pairs_; }
  bool read_only() const { return read_only_; }
  // Why the study is read-only ("the study folder is not writable", "held by ..."); empty when it is not.
  const std::string& read_only_reason() const { return read_only_reason_; }
  // Makes the session read-only (edits stay in memory, save_all_to still works), e.g. because another
  // window holds the study's lock (study_lock.h).
  void set_read_only(const std::string& reason);

  // Every scene's pairs-file problems, by domain pair then scene (for the problem list).
  std::vector<PairsProblem> pairs_problems() const;

  // The domain pair in view (index into domain_pairs()) and the model whose predictions count.
  int pair_index() const { return pair_; }
  const std::string& model() const { return model_; }
  void select(int pair_index, const std::string& model);
  // Finds the domain pair (a, b) in either order; false when it is not one.
  bool select_domains(const std::string& a, const std::string& b);
  bool swapped() const { return swapped_; }  // the view shows (b, a): left is the pair's second domain
  const std::string& left_domain() const;
  const std::string& right_domain() const;

  // Scenes of the current domain pair, in stem order.
  const CowVector<SceneState>& scenes() const { return scenes_[pair_]; }
  // Scenes of any domain pair (index into domain_pairs()), in stem order.
  const CowVector<SceneState>& scenes_of(int pair_index) const { return scenes_.at(pair_index); }
  int scene_index(const std::string& stem) const;
  SceneSummary summary(int scene) const;
  std::vector<SceneSummary> summaries() const;  // every scene of the current domain pair
  // The audit of a scene's current pairs against its registration affine, in the domain pair's (A, B)
  // orientation (audit.pairs[k].a indexes A even when the view is swapped).
  const SceneAudit& audit(int scene) const { return audits_[pair_][scene]; }
  // Registers a hand-paired scene opened without its registration (the studio does it when the scene is
  // shown): its automatic pairs, affine and audit; the counted pairs stay the hand pairs. False when it
  // was registered already.
  bool register_scene(int pair, int scene);
  // Per rock of a view side: 1 when its pair is suspect.
  std::vector<char> suspect_rocks(Side side, int scene) const;
  // The current pairs of a scene oriented as (left index, right index).
  RockPairs view_pairs(int scene) const;
  const std::vector<Box>& gt(Side side, int scene) const;
  const std::vector<Box>& predictions(Side side, int scene) const;
  const PerformanceValues& performance(Side side, int scene) const;
  bool excluded(Side side, int scene, int rock) const;

  // IPD of the current domain pair for the current model, and any cell of the cross table.
  // The cross table's cells as the engine makes them (make_table_cell, count_scene_in_cell, settle_table_cell: one
  // rule with `ipd table`), kept current after every edit; per_scene stays empty (contributions_for holds it).
  TableCell cell() const { return cell_for(model_, pair_); }
  TableCell cell_for(const std::string& model, int pair_index) const;
  // Each scene's contribution to a cell (scene order of the domain pair; `counted` in (A, B) indices);
  // empty when the model lacks predictions for a domain. For the statistics (session_statistics.h).
  const CowVector<SceneIpd>& contributions_for(const std::string& model, int pair_index) const;

  // Edits of one scene; sides refer to the view (left = A unless swapped). Returns the save job.
  // In a scene whose pairs file no longer matches its label files (SceneState::pairs_unusable) every edit
  // but reset is refused with a StudyError naming the file (saving would overwrite the hand pairs with
  // registration's); reset discards the file, the user's explicit choice.
  SaveJob apply(int scene, Edit edit);
  // The scene's pairs file and why its hand pairs are not applied, when it no longer matches its label files
  // (the view shows registration's pairs and edits are refused); {"", ""} otherwise.
  std::pair<std::string, std::string> stale_pairs(int scene) const { return stale_pairs_of(pair_, scene); }
  bool can_undo() const { return undo_pos_ > 0; }
  bool can_redo() const { return undo_pos_ < history_.size(); }
  std::optional<SaveJob> undo();  // nullopt when there is nothing to undo
  std::optional<SaveJob> redo();
  int last_edited_scene() const { return last_scene_; }

  // Drops predictions below `threshold` (on top of the study's own) and recomputes every IPD.
  void set_conf_threshold(double threshold);
  double conf_threshold() const { return conf_threshold_; }

  // Review marks of the current domain pair (review_state.h), undone and redone with the edits; each
  // returns the job writing review/<A>__<B>.json. A checked pair no longer counts as suspect.
  SaveJob toggle_reviewed(int scene);
  // (left, right): a current pair in view orientation; nullopt when it is not one.
  std::optional<SaveJob> toggle_checked(int scene, int left, int right);
  bool reviewed(int scene) const { return reviews_[pair_]->reviewed[scene] != 0; }
  // The review marks of any domain pair (index into domain_pairs()).
  const ReviewState& review_of(int pair_index) const { return *reviews_.at(pair_index); }
  bool checked(int scene, int left, int right) const;  // view orientation
  struct ReviewProgress {
    int scenes = 0, reviewed = 0, suspects_left = 0;
  };
  ReviewProgress review_progress() const;  // of the current domain pair

  // Every hand-edited scene's pairs, and every domain pair's review marks, written under another study root
  // (for read-only studies).
  std::vector<SaveJob> save_all_to(const std::string& other_root) const;

  // After a SaveConflict the user keeps the disk's version: the scene of domain pair `pair` is read again
  // from its pairs files (as an edit that undo takes back); an empty stem reads the domain pair's review
  // file again. Throws StudyError for a bad file.
  void reload_scene(int pair, const std::string& stem);
  // The user keeps this window's version: the job again, expecting what the disk held at the conflict.
  static SaveJob overwrite(SaveJob job, const SaveConflict& conflict);

 private:
  // A review mark toggled (its own inverse): a scene's, or a pair's (a, b in the domain pair's order).
  struct ReviewToggle {
    enum class Kind { kNone, kScene, kPair } kind = Kind::kNone;
    int a = -1, b = -1;
  };
  struct HistoryEntry {
    int pair, scene;
    FixedPairs before, after;
    bool edited_before, edited_after;
    ReviewToggle review;  // kNone: a pairs edit
  };
  SaveJob apply_review_toggle(int pair, int scene, const ReviewToggle& t);
  SaveJob review_job(int pair, const std::string& root) const;
  ReviewScenes review_scenes(int pair) const;
  void reload_review(int pair);
  // A check kept from the review file (it did not apply when read) applies again once its rocks are a pair.
  void apply_kept_checks(int pair, int scene);
  std::vector<Problem> load_reviews();  // every domain pair's review file; the marks dropped
  SaveJob set_scene(int pair, int scene, const FixedPairs& pairs, bool edited);
  void refuse_stale_pairs_edit(int pair, int scene) const;
  // Throws StudyError when the scene's pairs file is another class's (SceneState::pairs_other_class).
  void refuse_other_class_edit(int pair, int scene) const;
  std::pair<std::string, std::string> stale_pairs_of(int pair, int scene) const;  // {file, why}; empty: usable
  SaveJob job_for(int pair, int scene, const std::string& root) const;
  void recompute_performance();
  void rebuild_totals();
  long shown_predictions(const std::string& domain, const std::string& model, int pair) const;
  double effective_threshold() const;
  SceneIpd contribution(const std::string& model, int pair, int scene) const;
  SceneAudit audit_of(int pair, int scene) const;  // checked pairs are not suspect
  void reaudit(int pair, int scene);
  Side pair_side(Side view_side) const;  // view side -> side of the domain pair
  const std::string& domain_of(Side view_side) const;

  std::string class_note_;
  std::shared_ptr<const StudyLabels> labels_;
  std::vector<std::pair<std::string, std::string>> pairs_;
  RegistrationOptions registration_;  // what register_scene registers with, and its cache
  std::string cache_dir_;
  std::vector<CowVector<SceneState>> scenes_;  // per domain pair
  std::vector<CowVector<SceneAudit>> audits_;  // per domain pair, per scene
  int cached_ = 0;
  std::shared_ptr<const std::vector<Problem>> problems_;  // opening's (fixed once open)
  std::vector<Problem> threshold_problems_;
  StudyCacheStats study_cache_stats_;
  int pair_ = 0;
  bool swapped_ = false;
  std::string model_;
  bool read_only_ = false;
  std::string read_only_reason_;
  double conf_threshold_ = 0;
  // domain -> model -> stem -> performance values; and the filtered predictions they came from
  // (shared between snapshots: replaced whole when the threshold changes, never modified)
  std::shared_ptr<const ByDomainModelStem<PerformanceValues>> perf_;
  std::shared_ptr<const ByDomainModelStem<std::vector<Box>>> shown_predictions_;
  // (model, pair) -> totals, and each scene's contribution to them
  std::map<std::pair<std::string, int>, TableCell> totals_;
  std::map<std::pair<std::string, int>, CowVector<SceneIpd>> contributions_;
  // Per domain pair: review marks (replaced whole on a change, so snapshots share them) and what this window
  // last read or wrote at review/<A>__<B>.json.
  std::vector<std::shared_ptr<const ReviewState>> reviews_;
  std::vector<DiskVersion> review_disk_;
  CowVector<HistoryEntry> history_;
  size_t undo_pos_ = 0;
  int last_scene_ = -1;
};

}  // namespace ipd
