// Internal: what registration searches report besides their best model. A SearchRecorder observes a robust
// loop (see robust_loop.h): it keeps the best *distinct* rival of the best hypothesis, for the confidence
// measure, and, only when asked, records every step into a RegistrationTrace (affines in image coordinates).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/geometry/point_grid.h"
#include "core/registration/registration_frame.h"

namespace ipd::detail {

// Confidence from the best and the best distinct rival, both "higher is better" and >= 0:
// 1 - rival / best in [0, 1]; 1 when there is no rival (or it scored nothing); 0 when the best scored nothing.
double confidence_from_scores(double best, double rival);

// Below this confidence a second, different alignment explains the rocks almost as well: ambiguous.
constexpr double kAmbiguousBelow = 0.2;

class SearchRecorder {
 public:
  // `gate`: inlier distance in normalised units. `to_report` turns a loop score (higher is better) into the
  // method's reported score. `sample_of` fills the rocks the current model was built from (record mode only).
  using SampleFn = std::function<void(const Affine2& normalised, std::vector<int>* a, std::vector<int>* b)>;
  SearchRecorder(const RegistrationFrame& f, double gate, bool record, std::function<double(double)> to_report,
                 SampleFn sample_of);

  void on_model(const Affine2& raw, double raw_score, const Affine2& final, double score, bool refined,
                double best_score, bool new_best);

  // A step outside the loop (a final polish, an EM iteration), recorded as is.
  void add_step(TraceStepKind kind, const Affine2& normalised, double report_score, double report_best, bool new_best);

  // Loop-score of the best distinct rival seen (-inf when none).
  double rival_score() const { return rival_score_; }
  // True when the two affines put more than half of A's rocks within the gate of each other.
  bool agree(const Affine2& x, const Affine2& y) const;

  bool recording() const { return record_; }
  RegistrationTrace take_trace(const std::string& stop);

 private:
  void track_rival(const Affine2& m, double score);
  std::vector<int> inliers(const Affine2& m) const;

  const RegistrationFrame& f_;
  double gate2_;
  bool record_;
  std::function<double(double)> to_report_;
  SampleFn sample_of_;
  PointGrid grid_b_;  // built only when recording
  bool has_best_ = false;
  Affine2 best_ = identity_affine();
  double best_score_ = -INFINITY, rival_score_ = -INFINITY;
  double loop_best_ = -INFINITY;  // the loop's best before the current model
  RegistrationTrace trace_;
};

}  // namespace ipd::detail
