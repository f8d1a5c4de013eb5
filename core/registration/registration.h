// Rock pairing between two images of one scene: 2-D point-set registration of GT box centres, then an
// assignment of rocks. Methods share one interface; `paper` is the paper's RANSAC exactly.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/geometry/geometry.h"
#include "core/registration/registration_trace.h"
#include "core/registration/robust_loop.h"

namespace ipd {

enum class RegistrationMethod { kPaper, kConsensus, kCpd };

// The one table of registration methods, read by the CLI (--method help and validation), study.yaml and
// ipd-studio's method combo. The default comes first.
struct RegistrationMethodInfo {
  RegistrationMethod method;
  const char* name;         // as typed: --method NAME, registration: {method: NAME}
  const char* description;  // one line
  const char* defaults;     // what it runs with unless told otherwise
};
const std::vector<RegistrationMethodInfo>& registration_methods();
const RegistrationMethodInfo& method_info(RegistrationMethod m);

const char* to_string(RegistrationMethod m);
// Parses a name of the table; false for anything else.
bool parse_method(const std::string& name, RegistrationMethod* out);
std::vector<std::string> method_names();  // in table order
std::string method_choices();             // "consensus, paper or cpd", for messages
std::string methods_help();               // one line per method: name, description, defaults

using RockPairs = std::vector<std::pair<int, int>>;  // (index in A, index in B)

// The consensus method's own settings: its search budget and what it holds plausible.
struct ConsensusParams {
  int max_hypotheses = 1000;                // hypotheses scored at most (--trials)
  double min_scale = 0.5, max_scale = 2.0;  // singular values of the linear part
  double max_rotation_deg = 30.0;           // a camera misalignment, not an arbitrary rotation
  // Largest ratio of the linear part's singular values (one axis stretched this much more than the other).
  // Wrong alignments of a small overlap are often strongly stretched (2.3-5x on the large tier's failures), a
  // camera misalignment is not.
  double max_anisotropy = 2.0;
  std::optional<double> inlier_gate;  // fraction of image width; unset: from the rock spacing

  // Empty when usable; otherwise the field that is wrong and the accepted range, in one sentence.
  std::string validate() const;
};

// The paper's RANSAC's own settings.
struct PaperParams {
  int samples = 1000;  // K samples, each tried in all 6 orders (--trials)
  // Rocks are paired as mutual nearest neighbours closer than this fraction of the centres' RMS spread
  // (scale-free; 0.2 is about 5% of the image width for rocks spread over the picture).
  double pair_gate = 0.2;

  std::string validate() const;  // as ConsensusParams::validate
};

// Coherent Point Drift's own settings.
struct CpdParams {
  int iterations = 100;  // EM iterations (--trials)
  double outlier_weight = 0.2;

  std::string validate() const;  // as ConsensusParams::validate
};

// The settings every method shares, and each method's own beside them.
struct RegistrationOptions {
  RegistrationMethod method = RegistrationMethod::kConsensus;
  std::uint64_t seed = 0;
  // Image width / height: distances and angles are measured in pixels. Unset: 1 (in a study, the study's).
  std::optional<double> aspect;
  std::optional<double> time_budget_ms;  // unset: no time limit
  // Bound on the work per pair, in point evaluations (one mapped rock scored, or one A-B term of an EM step).
  // Unset: automatic, growing as n log n in the rock count, so 5,000 rocks a side stop within seconds.
  std::optional<double> work_budget;
  bool record_trace = false;  // fill RegistrationReport::trace (ipd-studio's replay); off in batch runs
  // consensus, cpd: aligned boxes pair when they overlap by IoU > min_pair_iou, or when their centres are
  // closer than pair_noise_floor (fraction of the image width) and their sides agree within
  // pair_max_size_ratio (PairingRule). The floor is off by default: 0.0125 (24 px of 1936) lifts the large
  // tier's recall under 30 px from 0.967 to 0.978 on held-out terrains but costs that band precision
  // (0.979 -> 0.976), see docs/method.md.
  double min_pair_iou = 0.1;
  double pair_noise_floor = 0;
  double pair_max_size_ratio = 2.0;
  ConsensusParams consensus;
  PaperParams paper;
  CpdParams cpd;

  // The search budget of `method`, as --trials and study.yaml's registration.trials set it: paper's samples,
  // consensus' hypothesis cap, cpd's EM iterations.
  int& trials();
  int trials() const;
  double aspect_ratio() const { return aspect.value_or(1.0); }

  // Empty when usable; otherwise the field that is wrong and the accepted range, in one sentence.
  std::string validate() const;
  // Throws std::invalid_argument("registration options: " + validate()) when not usable.
  void check() const;
};

// Why a registration is flagged ambiguous (kNone: it is not). A number is only as good as the pairs behind it,
// so an answer that nothing singles out is flagged, never reported with a confidence it has not earned.
enum class Ambiguity : std::uint8_t {
  kNone,
  kRival,        // another alignment fits as well or almost as well (confidence below kAmbiguousBelow)
  kNoSupport,    // the alignment pairs no rock
  kFewPairs,     // fewer than 3 rocks paired: too few to fix an affine, any other placement fits as well
  kDegenerate,   // the paired rocks lie on a line, or the alignment squashes them onto one
  kBeaten,       // a rival the method scored after its search fitted better; that rival is the answer
  kUnchecked,    // the time budget ended before the answer was compared with another: the identity, the largest
                 // rocks' alignment or EM's fit, unjudged
  kNoPlausible,  // no hypothesis within the bounds was found: the identity, unjudged
};
inline constexpr int kAmbiguityCount = 8;  // values of Ambiguity, for the caches' range checks

// The reason a flagged registration is ambiguous, worded once for the studio, `ipd register` and `ipd table`.
inline constexpr const char* kAmbiguousReason =
    "another alignment fits as well or almost as well (e.g. a small overlap or a repetitive layout)";
const char* ambiguity_reason(Ambiguity a);  // "" for kNone

// How a method measures its answer's fit. Each method measures in its own unit and direction, so a fit always
// travels with its measure: a bare number would read a distance (lower is better) as a count (higher is better).
enum class FitMeasure : std::uint8_t {
  kNotScored,     // nothing was scored: identical layouts need no search, or the time budget ended first
  kMeanDistance,  // paper: mean nearest-neighbour distance of the aligned centres, fraction of the image width
  kSoftInliers,   // consensus: soft inlier count (each aligned centre weighted by its distance within the gate)
  kMixtureWidth,  // cpd: the Gaussian mixture's final width, fraction of the image width
};
FitMeasure fit_measure_of(RegistrationMethod m);  // the measure a method scores its hypotheses in

struct FitScore {
  FitMeasure measure = FitMeasure::kNotScored;
  double value = 0;  // in `measure`; meaningless when not scored

  bool scored() const { return measure != FitMeasure::kNotScored; }
};
bool lower_is_better(FitMeasure m);  // a distance or a width; a count is better higher
// "mean distance", "soft inliers", "mixture width", "not scored": the words every report prints.
const char* fit_measure_name(FitMeasure m);
// "mean_distance", "soft_inliers", "mixture_width": `ipd register --json`'s score_measure (null when not scored).
const char* fit_measure_key(FitMeasure m);
// "mean distance 0.0004", "soft inliers 16.8972", "not scored": a fit in words at `decimals` decimals, as the
// studio and `ipd register` print it (a rounded -0 prints as 0).
std::string fit_text(const FitScore& fit, int decimals);

struct RegistrationReport {
  RegistrationMethod method = RegistrationMethod::kConsensus;
  Affine2 affine = identity_affine();  // maps normalised A centres onto B's
  RockPairs pairs;                     // sorted by A index
  // What the search counted: paper and consensus draw minimal samples (paper's K) and score hypotheses; cpd runs
  // EM iterations (each also counted as a hypothesis, the alignment it scores).
  int samples = 0;
  int em_iterations = 0;
  int hypotheses = 0;  // affines scored
  int inliers = 0;     // A centres within the gate of a B centre after alignment
  FitScore fit;        // the answer's fit, in its method's measure; not scored when no hypothesis was
  StopReason stop = StopReason::kNotRun;
  std::string note;  // why a fallback was used, if one was
  double elapsed_ms = 0;
  // The final pairing's part of elapsed_ms. A time budget turns it greedy but cannot end it, since every rock is
  // paired or left alone by it: where many rocks overlap (thousands of allowed pairs) it runs past the budget.
  double pairing_ms = 0;
  double work = 0, work_budget = 0;  // point evaluations spent, and the bound they were held to
  // How much better the answer fits than the best distinct alternative the method evaluated: 1 - (rival's
  // score / answer's score), in [0, 1]; 1 when no rival came close. 0 when nothing singles the answer out:
  // no rock paired, fewer than 3 pairs, or a degenerate alignment (see Ambiguity). `ambiguous` is set, and
  // `ambiguity` says why, when confidence < 0.2 or for any reason Ambiguity lists.
  double confidence = 1.0;
  bool ambiguous = false;
  Ambiguity ambiguity = Ambiguity::kNone;
  RegistrationTrace trace;  // empty unless options.record_trace
};

// Registers A's GT boxes onto B's and pairs the rocks. Throws std::invalid_argument for bad options.
RegistrationReport register_rocks(const std::vector<Box>& a, const std::vector<Box>& b,
                                  const RegistrationOptions& options);

}  // namespace ipd
