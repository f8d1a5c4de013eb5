// Session's edits and their files: applying an edit, undo and redo, the save jobs they produce, and
// run_save_job, which carries a job out on disk (atomically, below the study, checked against DiskVersions).
#include <fcntl.h>
#include <unistd.h>

#include <fmt/format.h>
#include <algorithm>
#include <filesystem>
#include <optional>

#include "core/session/session.h"
#include "core/study/hand_work_class.h"
#include "core/util/atomic_file.h"
#include "core/util/contained_file.h"

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

// `path` below `root`, as the relative name contained_file.h walks.
std::string relative_to(const std::string& root_in, const std::string& path) {
  const std::string root =
      root_in.size() > 1 && root_in.back() == '/' ? root_in.substr(0, root_in.size() - 1) : root_in;
  if (path.size() <= root.size() + 1 || path.compare(0, root.size(), root) != 0 || path[root.size()] != '/')
    throw IoError(fmt::format("{}: is not inside {}; not saved", path, root));
  return path.substr(root.size() + 1);
}

// Refuses the job (nothing written yet) when a file it touches holds neither what this window last saw
// there nor what the job would leave there (a retried job may find its own result).
void check_expected(const SaveJob& job) {
  if (job.expected.empty()) return;
  std::vector<std::string> paths = {job.path};
  paths.insert(paths.end(), job.also_remove.begin(), job.also_remove.end());
  if (job.expected.size() != paths.size()) throw IoError(job.path + ": a save job with the wrong number of versions");
  std::vector<std::optional<std::string>> texts;
  std::vector<DiskVersion> now;
  for (const auto& p : paths) {
    texts.push_back(read_file_beneath(job.root, relative_to(job.root, p)));
    now.push_back(version_of(texts.back()));
  }
  for (size_t k = 0; k < paths.size(); ++k) {
    const DiskVersion target = k == 0 ? version_of(job.contents) : DiskVersion{};
    if (now[k] == job.expected[k] || now[k] == target) continue;
    throw SaveConflict(fmt::format("{}: changed on disk since this window read it (another window or program saved "
                                   "it); not overwritten: keep one version",
                                   paths[k]),
                       paths[k], texts[k], now);
  }
}

// The check of the job's k-th file (0: `path`, then `also_remove`) made right before it is replaced or removed,
// on what it holds then: a SaveConflict when that is neither what this window last saw nor the job's result.
Recheck recheck_of(const SaveJob& job, size_t k) {
  if (job.expected.size() <= k) return {};
  return [&job, k](const std::optional<std::string>& text) {
    const DiskVersion now = version_of(text);
    const DiskVersion target = k == 0 ? version_of(job.contents) : DiskVersion{};
    if (now == job.expected[k] || now == target) return;
    const std::string& path = k == 0 ? job.path : job.also_remove[k - 1];
    std::vector<DiskVersion> observed = job.expected;
    observed[k] = now;
    throw SaveConflict(fmt::format("{}: changed on disk since this window read it (another window or program saved "
                                   "it); not overwritten: keep one version",
                                   path),
                       path, text, observed);
  };
}

void run_unchecked_save_job(const SaveJob& job, const WriteStepHook& hook) {
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
}  // namespace

void run_save_job(const SaveJob& job, const WriteStepHook& hook) {
  if (job.root.empty()) return run_unchecked_save_job(job, hook);
  // Every file the job touches is looked at first: a link on the way refuses the job before anything changed.
  const std::string rel = relative_to(job.root, job.path);
  check_beneath(job.root, rel);
  for (const auto& p : job.also_remove) check_beneath(job.root, relative_to(job.root, p));
  check_expected(job);
  // Checked again right before the rename (or the removal): an edit by an editor, a script or a sync client
  // that lands while the temp file is written and synced (seconds on a slow disk) is a conflict, not lost.
  // `path` is the name order read_fixed_pairs tries first: while it exists, the other one doesn't count.
  const Recheck recheck = recheck_of(job, 0);
  if (job.contents) {
    write_file_beneath(job.root, rel, *job.contents, hook, recheck);
    for (size_t k = 0; k < job.also_remove.size(); ++k) {
      const std::string& p = job.also_remove[k];
      remove_file_beneath(job.root, relative_to(job.root, p), {}, recheck_of(job, k + 1));
      if (hook) hook("other removed");
    }
  } else {
    for (size_t k = 0; k < job.also_remove.size(); ++k) {
      const std::string& p = job.also_remove[k];
      remove_file_beneath(job.root, relative_to(job.root, p), {}, recheck_of(job, k + 1));
      if (hook) hook("other removed");
    }
    remove_file_beneath(job.root, rel, {}, recheck);
    if (hook) hook("removed");
  }
}

SaveJob Session::job_for(int pair, int scene, const std::string& root) const {
  const auto& [a, b] = pairs_[pair];
  const SceneState& s = scenes_[pair][scene];
  SaveJob job;
  job.root = root;
  job.path = (fs::path(root) / fixed_pairs_relative_path(a, b, s.stem)).string();
  job.also_remove.push_back((fs::path(root) / fixed_pairs_relative_path(b, a, s.stem)).string());
  if (s.edited)
    job.contents = fixed_pairs_json(s.current, labels_->gt_of(a, s.stem).boxes, labels_->gt_of(b, s.stem).boxes,
                                    hand_work_class(labels_->study));
  if (root == labels_->study.root) job.expected = {s.disk_ab, s.disk_ba};
  job.pair = pair;
  job.stem = s.stem;
  return job;
}

SaveJob Session::set_scene(int pair, int scene, const FixedPairs& fp, bool edited) {
  SceneState& s = scenes_[pair].edit(scene);  // the only scene that changes: its chunk alone is copied
  s.current = fp;
  std::sort(s.current.pairs.begin(), s.current.pairs.end());
  s.edited = edited;
  // Only this scene's contribution changes: swap it in every model's totals.
  for (auto& [key, list] : contributions_) {
    if (key.second != pair) continue;
    TableCell& t = totals_[key];
    count_scene_in_cell(t, list[scene], -1);
    list.set(scene, contribution(key.first, pair, scene));
    count_scene_in_cell(t, list[scene]);
  }
  apply_kept_checks(pair, scene);
  reaudit(pair, scene);
  last_scene_ = scene;
  SaveJob job = job_for(pair, scene, labels_->study.root);
  // From now on this window's version is what the job leaves on disk.
  s.disk_ab = version_of(job.contents);
  s.disk_ba = DiskVersion{};
  return job;
}

std::pair<std::string, std::string> Session::stale_pairs_of(int pair, int scene) const {
  const SceneState& s = scenes_[pair][scene];
  if (!s.pairs_unusable) return {};
  const auto it =
      std::find_if(s.pairs_problems.begin(), s.pairs_problems.end(), [](const PairsProblem& p) { return p.unusable; });
  const std::string file =
      it != s.pairs_problems.end()
          ? it->file
          : (fs::path(labels_->study.root) / fixed_pairs_relative_path(pairs_[pair].first, pairs_[pair].second, s.stem))
                .string();
  const std::string why =
      it != s.pairs_problems.end() ? it->why_unusable : "its stored rocks are not in the label files";
  return {file, why};
}

void Session::refuse_other_class_edit(int pair, int scene) const {
  const SceneState& s = scenes_[pair][scene];
  if (s.pairs_other_class == kNoClassChosen) return;
  const StudyClasses& c = labels_->study.classes;
  const std::string theirs = s.pairs_other_class == kAllClasses ? "all" : c.name_of(s.pairs_other_class);
  throw StudyError(
      fmt::format("{}: edit refused: this scene's hand pairs are of {}, and saving an edit made while showing {} would "
                  "overwrite them; choose {} in the class menu to edit them",
                  s.pairs_other_class_file, s.pairs_other_class == kAllClasses ? "all classes" : theirs,
                  class_statement(*labels_), theirs));
}

void Session::refuse_stale_pairs_edit(int pair, int scene) const {
  refuse_other_class_edit(pair, scene);
  const SceneState& s = scenes_[pair][scene];
  if (!s.pairs_unusable) return;
  const auto [file, why] = stale_pairs_of(pair, scene);
  // The scene shows registration's pairs, so a save now would replace the hand pairs with them: refused.
  throw StudyError(
      fmt::format("{}: edit refused: this file's hand pairs no longer match the label files ({}), and saving the "
                  "edit would overwrite them. To keep them, correct the label file and open the study again; to "
                  "discard them and start from registration's pairs, use \"reset to automatic\" on scene \"{}\"",
                  file, why, s.stem));
}

bool matches_automatic(const SceneState& s, const FixedPairs& fp) {
  if (!s.registered || !fp.excluded_a.empty() || !fp.excluded_b.empty()) return false;
  RockPairs automatic = s.automatic.pairs, pairs = fp.pairs;
  std::sort(automatic.begin(), automatic.end());
  std::sort(pairs.begin(), pairs.end());
  return automatic == pairs;
}

SaveJob Session::apply(int scene, Edit e) {
  if (e.kind != Edit::Kind::kResetToAutomatic) refuse_stale_pairs_edit(pair_, scene);
  refuse_other_class_edit(pair_, scene);  // reset too: it would remove the other class's file
  if (e.kind == Edit::Kind::kResetToAutomatic) register_scene(pair_, scene);  // the pairs it goes back to
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
      if (std::find(list.begin(), list.end(), e.a) != list.end())
        drop(list, e.a);
      else
        list.push_back(e.a);
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
  if (e.kind == Edit::Kind::kPair || e.kind == Edit::Kind::kReplacePairs) {
    const auto& [a, b] = pairs_[pair_];
    if (const auto why = pair_across_classes(next, labels_->gt_of(a, s.stem).boxes, labels_->gt_of(b, s.stem).boxes, a,
                                             b, labels_->study.classes))
      throw StudyError("edit refused: " + *why);
  }
  // Pairs made by hand that are registration's own, with no rock excluded, are the automatic pairing again: the
  // scene is no longer hand-edited and its pairs file goes (the history keeps the step).
  if (edited && matches_automatic(s, next)) edited = false;
  // Discarding a stale pairs file is no step undo can take back: the scene showed registration's pairs before
  // and after, and the file is gone (the dialog says so). An entry would "undo" by changing nothing.
  if (!(e.kind == Edit::Kind::kResetToAutomatic && s.pairs_unusable)) {
    history_.truncate(undo_pos_);
    history_.push_back({pair_, scene, s.current, next, s.edited, edited, {}});
    ++undo_pos_;
  }
  SaveJob job = set_scene(pair_, scene, next, edited);
  if (e.kind == Edit::Kind::kResetToAutomatic) {
    // The user discarded a pairs file that no longer applied: the job removes it, the scene is editable again.
    SceneState& reset = scenes_[pair_].edit(scene);
    reset.pairs_unusable = false;
    reset.pairs_problems.clear();
  }
  return job;
}

std::optional<SaveJob> Session::undo() {
  if (!can_undo()) return std::nullopt;
  // Undo writes the scene's pairs too: a file that went stale since (reloaded) is refused as an edit is.
  if (history_[undo_pos_ - 1].review.kind == ReviewToggle::Kind::kNone)
    refuse_stale_pairs_edit(history_[undo_pos_ - 1].pair, history_[undo_pos_ - 1].scene);
  const HistoryEntry h = history_[--undo_pos_];
  pair_ = h.pair;
  if (h.review.kind != ReviewToggle::Kind::kNone) return apply_review_toggle(h.pair, h.scene, h.review);
  return set_scene(h.pair, h.scene, h.before, h.edited_before);
}

std::optional<SaveJob> Session::redo() {
  if (!can_redo()) return std::nullopt;
  if (history_[undo_pos_].review.kind == ReviewToggle::Kind::kNone)
    refuse_stale_pairs_edit(history_[undo_pos_].pair, history_[undo_pos_].scene);
  const HistoryEntry h = history_[undo_pos_++];
  pair_ = h.pair;
  if (h.review.kind != ReviewToggle::Kind::kNone) return apply_review_toggle(h.pair, h.scene, h.review);
  return set_scene(h.pair, h.scene, h.after, h.edited_after);
}

std::vector<SaveJob> Session::save_all_to(const std::string& other_root) const {
  std::vector<SaveJob> jobs;
  for (size_t p = 0; p < scenes_.size(); ++p)
    for (size_t s = 0; s < scenes_[p].size(); ++s)
      if (scenes_[p][s].edited) jobs.push_back(job_for(static_cast<int>(p), static_cast<int>(s), other_root));
  for (size_t p = 0; p < reviews_.size(); ++p)
    if (!reviews_[p]->empty()) jobs.push_back(review_job(static_cast<int>(p), other_root));
  return jobs;
}

void Session::reload_scene(int pair, const std::string& stem) {
  if (pair < 0 || pair >= static_cast<int>(scenes_.size())) return;
  if (stem.empty()) return reload_review(pair);
  const auto& list = scenes_[pair];
  const auto it = std::find_if(list.begin(), list.end(), [&](const SceneState& sc) { return sc.stem == stem; });
  if (it == list.end()) return;
  const int scene = static_cast<int>(it - list.begin());
  register_scene(pair, scene);  // without a pairs file the scene goes back to its automatic pairs
  const auto& [a, b] = pairs_[pair];
  FixedPairsRead read =
      load_fixed_pairs(labels_->study, a, b, stem, labels_->gt_of(a, stem).boxes, labels_->gt_of(b, stem).boxes);
  const SceneState& old = scenes_[pair][scene];
  FixedPairs next;
  next.pairs = old.automatic.pairs;
  const bool edited = read.pairs.has_value();
  if (read.pairs) next = std::move(*read.pairs);
  std::sort(next.pairs.begin(), next.pairs.end());
  history_.truncate(undo_pos_);
  history_.push_back({pair, scene, old.current, next, old.edited, edited, {}});
  ++undo_pos_;
  set_scene(pair, scene, next, edited);  // its job would write what is on disk: not needed
  SceneState& s = scenes_[pair].edit(scene);
  s.disk_ab = read.version_ab;
  s.disk_ba = read.version_ba;
  s.fixed_on_disk = edited;
  s.pairs_unusable = read.unusable();
  s.pairs_other_class = read.other_class;
  s.pairs_other_class_file = read.other_class_file;
  s.pairs_problems = std::move(read.problems);
}

SaveJob Session::overwrite(SaveJob job, const SaveConflict& conflict) {
  if (conflict.observed.size() == job.expected.size()) job.expected = conflict.observed;
  return job;
}

}  // namespace ipd
