#include "ui/figures/figure_input.h"

#include <algorithm>
#include <stdexcept>

#include "core/geometry/affine_estimator.h"
#include "core/geometry/confidence_threshold.h"
#include "core/picture/picture_codec.h"
#include "core/report/provenance.h"
#include "core/session/review_state.h"
#include "ui/figures/figure_provenance.h"

namespace ipd::ui {

namespace {

int domain_rank(const Study& st, const std::string& d) {
  for (size_t k = 0; k < st.domains.size(); ++k)
    if (st.domains[k].name == d) return int(k);
  return -1;
}

// The affine a -> b that explains the pairs when they aren't registration's own (trimmed: one wrong hand
// pair shows as one long line, not as every pair bent).
Affine2 affine_of_pairs(const SceneFigureInput& in) {
  std::vector<Eigen::Vector2d> src, dst;
  for (const auto& [i, j] : in.pairs) src.push_back(in.gt_a[i].centre()), dst.push_back(in.gt_b[j].centre());
  Affine2 m;
  return affine_least_squares_trimmed(src, dst, &m) ? m : identity_affine();
}

// The review marks of scene `stem` of the domain pair (a, b) in the study's order, against its pairs now.
void read_scene_review(const StudyLabels& labels, const std::string& a, const std::string& b, const std::string& stem,
                       const RockPairs& pairs, SceneFigureInput& in) {
  ReviewScenes one;
  one.stems = {stem};
  one.gt = [&](int, bool side_a) -> const std::vector<Box>& { return labels.gt_of(side_a ? a : b, stem).boxes; };
  one.pairs = [&](int) -> const RockPairs& { return pairs; };
  one.take_class_of(labels.study);
  const ReviewRead read = load_review(labels.study.root, a, b, one);  // other scenes' marks are dropped
  in.reviewed = read.state.reviewed_scenes > 0;
  in.pairs_checked = static_cast<int>(read.state.checked.at(0).size());
}

}  // namespace

SceneFigureInput scene_input_from_study(const StudyLabels& labels, const std::string& a, const std::string& b,
                                        const std::string& model, const std::string& stem, double conf_threshold,
                                        const RegistrationOptions& registration) {
  const Study& st = labels.study;
  SceneFigureInput in;
  in.stem = stem, in.a = a, in.b = b, in.model = model;
  in.conf_threshold = std::max(conf_threshold, st.config.conf_threshold);
  in.gt_a = labels.gt_of(a, stem).boxes;
  in.gt_b = labels.gt_of(b, stem).boxes;
  if (!model.empty()) {
    in.pred_a = predictions_kept(labels.predictions_of(a, model, stem).boxes, conf_threshold);
    in.pred_b = predictions_kept(labels.predictions_of(b, model, stem).boxes, conf_threshold);
  }
  const bool swapped = domain_rank(st, a) > domain_rank(st, b);
  const ScenePairing p = pair_scene(labels, swapped ? b : a, swapped ? a : b, stem, registration);
  in.pairs = p.pairs;
  in.excluded_a = swapped ? p.excluded_b : p.excluded_a;
  in.excluded_b = swapped ? p.excluded_a : p.excluded_b;
  if (swapped) {  // as the GUI shows a swapped pair
    for (auto& q : in.pairs) std::swap(q.first, q.second);
    std::sort(in.pairs.begin(), in.pairs.end());
  }
  in.pairs_fixed = p.fixed;
  in.pairs_stale =
      std::any_of(p.pairs_problems.begin(), p.pairs_problems.end(), [](const PairsProblem& w) { return w.unusable; });
  in.method = to_string(p.registration.method);
  in.affine = (p.fixed || swapped) ? affine_of_pairs(in) : p.registration.affine;
  if (st.config.image_width > 0) in.image_w = st.config.image_width, in.image_h = st.config.image_height;
  in.label_fingerprint = label_set_fingerprint_of(labels);
  in.class_name = provenance_class(labels);
  in.task = labels.study.config.task;
  read_scene_review(labels, swapped ? b : a, swapped ? a : b, stem, p.pairs, in);
  return in;
}

SceneFigureInput scene_input_from_session(const Session& s, int scene) {
  const SceneState& state = s.scenes().at(scene);
  SceneFigureInput in;
  in.stem = state.stem;
  in.a = s.left_domain();
  in.b = s.right_domain();
  in.model = s.model();
  in.conf_threshold = std::max(s.conf_threshold(), s.study().config.conf_threshold);
  in.gt_a = s.gt(Side::kA, scene);
  in.gt_b = s.gt(Side::kB, scene);
  if (!in.model.empty()) {
    in.pred_a = s.predictions(Side::kA, scene);
    in.pred_b = s.predictions(Side::kB, scene);
  }
  in.pairs = s.view_pairs(scene);
  for (int k = 0; k < int(in.gt_a.size()); ++k)
    if (s.excluded(Side::kA, scene, k)) in.excluded_a.push_back(k);
  for (int k = 0; k < int(in.gt_b.size()); ++k)
    if (s.excluded(Side::kB, scene, k)) in.excluded_b.push_back(k);
  in.pairs_fixed = state.edited;
  in.pairs_stale = state.pairs_unusable;
  in.method = to_string(state.automatic.registration.method);
  in.affine = (state.edited || s.swapped()) ? affine_of_pairs(in) : state.automatic.registration.affine;
  const Study& st = s.study();
  if (st.config.image_width > 0) in.image_w = st.config.image_width, in.image_h = st.config.image_height;
  in.label_fingerprint = label_set_fingerprint_of(s.labels());
  in.class_name = provenance_class(s.labels());
  in.task = s.labels().study.config.task;
  const ReviewState& review = s.review_of(s.pair_index());
  in.reviewed = review.reviewed.at(scene) != 0;
  // Checks that are pairs now (one whose pair was edited away is kept, but does not apply).
  const RockPairs& now = state.current.pairs;
  for (const auto& p : review.checked.at(scene))
    in.pairs_checked += std::find(now.begin(), now.end(), p) != now.end() ? 1 : 0;
  return in;
}

void load_pictures(SceneFigureInput& in, const Study& study) {
  auto load = [&](const std::string& domain, cv::Mat& picture, std::string& problem) {
    const Domain* d = study.domain(domain);
    if (!d) return;
    const auto it = d->images.find(in.stem);
    if (it == d->images.end()) return;
    PictureRead read = read_study_picture(study.root, it->second, cv::IMREAD_COLOR);
    picture = std::move(read.image);
    problem = std::move(read.problem);
  };
  load(in.a, in.picture_a, in.problem_a);
  load(in.b, in.picture_b, in.problem_b);
}

void draw_scene_figure(DisplayList& out, const std::string& kind, const SceneFigureInput& in, const FigureOptions& o) {
  if (kind == "pairs")
    draw_pairs_figure(out, in, o);
  else if (kind == "registration")
    draw_registration_figure(out, in, o);
  else
    throw std::invalid_argument("unknown scene figure kind '" + kind + "' (expected pairs or registration)");
  // The scene's own edits: its pairs when set by hand, the rocks it leaves out; and its review marks.
  const int excluded = static_cast<int>(in.excluded_a.size() + in.excluded_b.size());
  Provenance p = scene_provenance(in.pairs_fixed, static_cast<int>(in.pairs.size()), excluded, in.label_fingerprint);
  p.scenes_with_stale_hand_pairs = in.pairs_stale ? 1 : 0;
  p.class_name = in.class_name;
  p.scenes_reviewed = in.reviewed ? 1 : 0;
  p.pairs_checked = in.pairs_checked;
  add_provenance(out, p, o);
}

}  // namespace ipd::ui
