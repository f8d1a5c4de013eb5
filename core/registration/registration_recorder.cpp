#include "core/registration/registration_recorder.h"

#include <algorithm>
#include <cmath>

namespace ipd::detail {

double confidence_from_scores(double best, double rival) {
  if (!(best > 0)) return 0.0;  // an answer that scores nothing is no better than any rival
  if (!(rival > 0)) return 1.0;
  return std::clamp(1.0 - rival / best, 0.0, 1.0);
}

SearchRecorder::SearchRecorder(const RegistrationFrame& f, double gate, bool record,
                               std::function<double(double)> to_report, SampleFn sample_of)
    : f_(f), gate2_(gate * gate), record_(record), to_report_(std::move(to_report)), sample_of_(std::move(sample_of)) {
  if (record_) grid_b_ = PointGrid(f.b);
}

bool SearchRecorder::agree(const Affine2& x, const Affine2& y) const {
  if (!x.allFinite() || !y.allFinite()) return false;
  int close = 0;
  for (const auto& p : f_.a) close += (apply(x, p) - apply(y, p)).squaredNorm() < gate2_;
  return 2 * close > static_cast<int>(f_.a.size());
}

void SearchRecorder::track_rival(const Affine2& m, double score) {
  if (!std::isfinite(score)) return;
  if (!has_best_) {
    has_best_ = true;
    best_ = m;
    best_score_ = score;
    return;
  }
  if (score > best_score_) {
    if (!agree(m, best_)) rival_score_ = std::max(rival_score_, best_score_);  // the old best is now the rival
    best_ = m;
    best_score_ = score;
  } else if (score > rival_score_ && !agree(m, best_)) {
    rival_score_ = score;
  }
}

std::vector<int> SearchRecorder::inliers(const Affine2& m) const {
  std::vector<int> out;
  for (size_t i = 0; i < f_.a.size(); ++i) {
    double d2 = INFINITY;
    if (grid_b_.nearest(apply(m, f_.a[i]), &d2, gate2_) >= 0 && d2 < gate2_) out.push_back(static_cast<int>(i));
  }
  return out;
}

void SearchRecorder::on_model(const Affine2& raw, double raw_score, const Affine2& final, double score, bool refined,
                              double best_score, bool new_best) {
  track_rival(final, score);
  if (!record_ || trace_.truncated) {
    loop_best_ = best_score;
    return;
  }
  TraceStep h;
  h.kind = TraceStepKind::kHypothesis;
  if (sample_of_) sample_of_(raw, &h.a_sample, &h.b_sample);
  h.b_from_a = f_.to_image(raw);
  h.inliers_a = inliers(raw);
  h.fit = to_report_(raw_score);
  // The hypothesis as drawn, against the best before it; its refinement (if any) is the next step.
  const double before = loop_best_;
  loop_best_ = best_score;
  h.new_best = raw_score > before;
  h.best_fit = to_report_(std::max(before, raw_score));
  trace_.add(std::move(h));
  if (!refined) return;
  TraceStep r;
  r.kind = TraceStepKind::kRefinement;
  r.b_from_a = f_.to_image(final);
  r.inliers_a = inliers(final);
  r.fit = to_report_(score);
  r.best_fit = to_report_(best_score);
  r.new_best = new_best;
  trace_.add(std::move(r));
}

void SearchRecorder::add_step(TraceStepKind kind, const Affine2& normalised, double report_score, double report_best,
                              bool new_best) {
  if (!record_ || trace_.truncated) return;
  TraceStep s;
  s.kind = kind;
  s.b_from_a = f_.to_image(normalised);
  s.inliers_a = inliers(normalised);
  s.fit = report_score;
  s.best_fit = report_best;
  s.new_best = new_best;
  trace_.add(std::move(s));
}

RegistrationTrace SearchRecorder::take_trace(const std::string& stop) {
  if (record_) trace_.stop = stop;
  return std::move(trace_);
}

}  // namespace ipd::detail
