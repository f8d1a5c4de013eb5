// Session's review marks (review_state.h): reading them with the study, toggling them as undoable edits,
// and the save job of a domain pair's review file.
#include <algorithm>
#include <filesystem>

#include "core/session/session.h"

namespace fs = std::filesystem;

namespace ipd {

ReviewScenes Session::review_scenes(int pair) const {
  ReviewScenes r;
  const auto& list = scenes_[pair];
  for (const SceneState& s : list) r.stems.push_back(s.stem);
  const auto& [a, b] = pairs_[pair];
  r.gt = [this, pair, a = a, b = b](int scene, bool side_a) -> const std::vector<Box>& {
    return labels_->gt_of(side_a ? a : b, scenes_[pair][scene].stem).boxes;
  };
  r.pairs = [this, pair](int scene) -> const RockPairs& { return scenes_[pair][scene].current.pairs; };
  r.take_class_of(labels_->study);
  return r;
}

std::vector<Problem> Session::load_reviews() {
  std::vector<Problem> problems;
  reviews_.clear();
  review_disk_.clear();
  for (size_t p = 0; p < pairs_.size(); ++p) {
    ReviewRead read =
        load_review(labels_->study.root, pairs_[p].first, pairs_[p].second, review_scenes(static_cast<int>(p)));
    reviews_.push_back(std::make_shared<const ReviewState>(std::move(read.state)));
    review_disk_.push_back(version_of(read.text));
    problems.insert(problems.end(), read.problems.begin(), read.problems.end());
  }
  return problems;
}

SaveJob Session::review_job(int pair, const std::string& root) const {
  const auto& [a, b] = pairs_[pair];
  SaveJob job;
  job.root = root;
  job.path = (fs::path(root) / review_relative_path(a, b)).string();
  // Nothing reviewed or checked any more: no file, as a study that was never reviewed.
  if (!reviews_[pair]->empty()) job.contents = review_json(*reviews_[pair], review_scenes(pair));
  if (root == labels_->study.root) job.expected = {review_disk_[pair]};
  job.pair = pair;  // stem stays empty: the conflict dialog's "keep theirs" reads the review file again
  return job;
}

SaveJob Session::apply_review_toggle(int pair, int scene, const ReviewToggle& t) {
  auto next = std::make_shared<ReviewState>(*reviews_[pair]);
  if (t.kind == ReviewToggle::Kind::kScene)
    next->toggle_reviewed(scene);
  else
    next->toggle_checked(scene, t.a, t.b);
  // The file's text first: a mark it can't hold (a scene name that is not UTF-8, and JSON is) throws here and
  // changes nothing, so the marks already made are still saved with the next one.
  if (!next->empty()) (void)review_json(*next, review_scenes(pair));
  reviews_[pair] = std::move(next);
  reaudit(pair, scene);
  last_scene_ = scene;
  SaveJob job = review_job(pair, labels_->study.root);
  review_disk_[pair] = version_of(job.contents);  // from now on, what this window's job leaves on disk
  return job;
}

SaveJob Session::toggle_reviewed(int scene) {
  ReviewToggle t;
  t.kind = ReviewToggle::Kind::kScene;
  SaveJob job = apply_review_toggle(pair_, scene, t);  // first: a mark that can't be saved is no step to undo
  history_.truncate(undo_pos_);
  const SceneState& s = scenes_[pair_][scene];
  history_.push_back({pair_, scene, s.current, s.current, s.edited, s.edited, t});
  ++undo_pos_;
  return job;
}

std::optional<SaveJob> Session::toggle_checked(int scene, int left, int right) {
  const SceneState& s = scenes_[pair_][scene];
  ReviewToggle t;
  t.kind = ReviewToggle::Kind::kPair;
  t.a = swapped_ ? right : left;
  t.b = swapped_ ? left : right;
  const auto& now = s.current.pairs;
  if (std::find(now.begin(), now.end(), std::make_pair(t.a, t.b)) == now.end()) return std::nullopt;
  SaveJob job = apply_review_toggle(pair_, scene, t);
  history_.truncate(undo_pos_);
  history_.push_back({pair_, scene, s.current, s.current, s.edited, s.edited, t});
  ++undo_pos_;
  return job;
}

void Session::apply_kept_checks(int pair, int scene) {
  const ReviewState& now = *reviews_[pair];
  const std::string& stem = scenes_[pair][scene].stem;
  if (std::none_of(now.kept_checks.begin(), now.kept_checks.end(), [&](const KeptCheck& k) { return k.scene == stem; }))
    return;
  const auto& [a, b] = pairs_[pair];
  auto next = std::make_shared<ReviewState>(now);
  // The file need not be saved for it: it holds the same checks, by the same boxes.
  if (next->apply_kept_checks(scene, stem, labels_->gt_of(a, stem).boxes, labels_->gt_of(b, stem).boxes,
                              scenes_[pair][scene].current.pairs))
    reviews_[pair] = std::move(next);
}

void Session::reload_review(int pair) {
  const auto& [a, b] = pairs_[pair];
  ReviewRead read = load_review(labels_->study.root, a, b, review_scenes(pair));
  reviews_[pair] = std::make_shared<const ReviewState>(std::move(read.state));
  review_disk_[pair] = version_of(read.text);
  for (size_t k = 0; k < scenes_[pair].size(); ++k) reaudit(pair, static_cast<int>(k));
}

bool Session::checked(int scene, int left, int right) const {
  return swapped_ ? reviews_[pair_]->is_checked(scene, right, left) : reviews_[pair_]->is_checked(scene, left, right);
}

Session::ReviewProgress Session::review_progress() const {
  ReviewProgress p;
  p.scenes = static_cast<int>(scenes_[pair_].size());
  p.reviewed = reviews_[pair_]->reviewed_scenes;
  for (const SceneAudit& a : audits_[pair_]) p.suspects_left += a.suspects;
  return p;
}

}  // namespace ipd
