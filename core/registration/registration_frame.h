// Internal: the common frame registration methods work in. Centres are made isotropic (pixels, in units of
// the image width), then each set is centred on its own centroid and both are divided by one shared spread,
// so solves are well conditioned at any coordinate scale or offset and scale bounds keep their meaning.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/geometry/geometry.h"
#include "core/registration/deadline.h"
#include "core/registration/registration.h"

namespace ipd::detail {

struct RegistrationFrame {
  std::vector<Eigen::Vector2d> a, b;            // normalised centres
  std::vector<Eigen::Vector2d> size_a, size_b;  // box (w, h) in the same units
  Eigen::Vector2d centroid_a{0, 0}, centroid_b{0, 0};
  double aspect = 1.0;
  double spread = 1.0;  // one normalised unit, in fractions of the image width

  RegistrationFrame(const std::vector<Box>& boxes_a, const std::vector<Box>& boxes_b, double aspect);
  // Converts an affine between normalised sets into one between normalised image coordinates.
  Affine2 to_image(const Affine2& m) const;
  // And back.
  Affine2 from_image(const Affine2& m) const;
};

// What a method returns before the shared bookkeeping (timing, sorting) is done.
struct MethodOutcome {
  Affine2 affine_normalised = identity_affine();
  RockPairs pairs;
  int samples = 0, em_iterations = 0, hypotheses = 0, inliers = 0;  // as RegistrationReport's
  double fit = 0;  // the answer's fit in the method's measure (fit_measure_of); read only when hypotheses > 0
  StopReason stop = StopReason::kNotRun;
  std::string note;
  double confidence = 1.0;
  // The search's own best lost to a rival scored after it (which is then the answer): flagged kBeaten.
  bool beaten = false;
  // Why the method itself knows its answer is not singled out, whatever the pairs look like (kNone: it does not):
  // an answer the time budget left uncompared (kUnchecked), the identity when nothing plausible was found
  // (kNoPlausible), or one left by degenerate samples (kDegenerate).
  Ambiguity unjudged = Ambiguity::kNone;
  double work = 0;          // point evaluations spent (see RegistrationOptions::work_budget)
  double pairing_ms = 0;    // the final pairing's wall time (RegistrationReport::pairing_ms)
  RegistrationTrace trace;  // filled when options.record_trace
};

// Flags what nothing singles out (see Ambiguity) and sets the report's ambiguity; shared by every method so
// that no method's confidence can vouch for a non-answer.
Ambiguity judge_answer(const RegistrationFrame& f, const RockPairs& pairs, const Affine2& normalised,
                       const MethodOutcome& out, double* confidence);
// Minor over major axis of a point set's spread (standard deviations): 0 on a line, 1 for a round cloud.
double flatness(const std::vector<Eigen::Vector2d>& p);

// The work bound of a registration of na against nb rocks: options.work_budget, or when that is unset one that
// grows as n log n in the rock count (about a second of work at 5,000 a side).
double work_budget(const RegistrationOptions& o, size_t na, size_t nb);

// Median distance between a point and its nearest other point (0 for fewer than two points). With a deadline that
// passes (read every 256 points) it stops early and its answer must not be used.
double median_nn_distance(const std::vector<Eigen::Vector2d>& p, const Deadline* deadline = nullptr);

// The stop reason in words, with the numbers behind it.
std::string describe_stop(StopReason stop, int samples, int hypotheses, double work, double budget);
// "1 sample", "89,700 point evaluations": a count (rounded) with thousands separators and the noun's number,
// as the stop descriptions print them (they are shown in ipd-studio: no "8.97e+04", no "1 samples").
std::string count_of(double n, const char* singular, const char* plural);
std::string grouped(double n);  // 89700 -> "89,700"

// register_rocks with its time budget given as a Deadline: tests drive it with a fake clock, and the coarse pass
// of a large set runs under its caller's deadline.
RegistrationReport register_rocks_until(const std::vector<Box>& a, const std::vector<Box>& b,
                                        const RegistrationOptions& options, const Deadline& deadline);

// A method's final pairing (pair_aligned_boxes by `image_affine`) into out->pairs, timed in out->pairing_ms. Under a
// time budget it gets what is left of it: pair_aligned_boxes_within, and when that had to pair greedily it says so
// in out->note and sets out->stop to the budget.
void pair_final(const Affine2& image_affine, const std::vector<Box>& a, const std::vector<Box>& b,
                const RegistrationOptions& o, const Deadline& deadline, MethodOutcome* out);
// Adds a sentence to a note ("a; b").
void add_note(std::string* note, const std::string& sentence);

// `deadline` holds options.time_budget_ms from the start of register_rocks, so the set-up counts against it.
MethodOutcome register_paper(const RegistrationFrame& f, const RegistrationOptions& o, const Deadline& deadline);
MethodOutcome register_consensus(const RegistrationFrame& f, const std::vector<Box>& boxes_a,
                                 const std::vector<Box>& boxes_b, const RegistrationOptions& o,
                                 const Deadline& deadline);
MethodOutcome register_cpd(const RegistrationFrame& f, const std::vector<Box>& boxes_a, const std::vector<Box>& boxes_b,
                           const RegistrationOptions& o, const Deadline& deadline);

// A small deterministic generator (the standard distributions differ between library versions).
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : s_(seed * 0x9E3779B97F4A7C15ull + 0x2545F4914F6CDD1Dull) {}
  std::uint64_t next() {  // splitmix64
    std::uint64_t z = (s_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  int below(int n) { return static_cast<int>(next() % static_cast<std::uint64_t>(n)); }
  double uniform() { return static_cast<double>(next() >> 11) * (1.0 / 9007199254740992.0); }

 private:
  std::uint64_t s_;
};

}  // namespace ipd::detail
