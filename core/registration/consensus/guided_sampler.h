// Internal: the consensus registration's sampler. It proposes hypotheses as affines directly, cheapest first
// (the coarse pass of a large set, the identity, the most voted translations), then triples drawn from local
// neighbourhoods (a rock and two of its nearest neighbours on each side), filtered by what a camera misalignment
// can do before any scoring. Each hypothesis carries the A rock it grew from (its anchor), which the stop rule
// counts confirmations by.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/geometry/geometry.h"
#include "core/registration/consensus/consensus_bounds.h"
#include "core/registration/registration_frame.h"

namespace ipd::detail {

struct GuidedHypothesis {
  Affine2 affine = identity_affine();
  // The rock of A the hypothesis grew from (a wrong match rarely repeats from another); the queued cheap
  // hypotheses get -1 - their position.
  long anchor = -1;
};

class GuidedSampler {
 public:
  // `first`: hypotheses proposed before any other (the coarse pass of a large set). `record`: keep each
  // hypothesis' rocks for the trace. `deadline` (may be null): once it has passed the set-up stops early and the
  // sampler must not be used (the caller reads the deadline after constructing it).
  GuidedSampler(const RegistrationFrame& f, const Bounds& bounds, double gate, std::uint64_t seed, bool record,
                const std::vector<Affine2>& first, const Deadline* deadline = nullptr);

  // False when every hypothesis has been proposed, or when the deadline passed while expanding anchors (one call
  // can expand hundreds of rock pairs that propose nothing).
  bool next(GuidedHypothesis* out);

  // The last hypothesis' rocks (record mode): A's three then B's three, in matching order; has_sample is false
  // for the cheap hypotheses, which are not built from rocks.
  std::array<int, 6> sample{};
  bool has_sample = false;

 private:
  // An edge from a rock to one of its neighbours, with its length.
  struct Edge {
    Eigen::Vector2d v;
    double length;
  };
  // A rock's edges to its neighbours and, for every ordered pair of them (n x n, row p), the cross product and
  // whether their triangle is flat; filled on first use: a rock anchors many expansions, and redoing this per
  // pair cost 8% more instructions on the large tier (callgrind).
  struct Star {
    std::vector<Edge> edges;
    std::vector<double> cross;
    std::vector<char> flat;
  };
  static const Star& star(int k, const std::vector<Eigen::Vector2d>& p, const std::vector<std::vector<int>>& nn,
                          std::vector<Star>* stars);
  static bool flat_triangle(double cross, const Eigen::Vector2d& e1, const Eigen::Vector2d& e2);

  const std::vector<int>& b_by_size(int i);
  bool next_deferred(GuidedHypothesis* out);
  void vote_translations(double gate);
  void expand(int i, int j);
  bool triple_affine(int i, int j, size_t u1, size_t u2, size_t x1, size_t x2, const Star& sa, const Star& sb,
                     Affine2* m) const;
  bool similarity_fits(const Eigen::Vector2d src[3], const Eigen::Vector2d dst[3], Affine2* m) const;
  int local_support(const Affine2& m, int i, int j, size_t u1, size_t u2) const;
  bool edge_plausible(const Edge& ea, const Edge& eb) const;
  bool sizes_agree(int i, int j) const;

  const RegistrationFrame& f_;
  const Deadline* deadline_;  // may be null; next() reads it every 64 expansions
  Bounds bounds_;
  double gate2_;
  double min_det_, max_det_;  // the determinant lies between the squared singular-value bounds
  std::vector<Affine2> queue_, pending_;
  bool record_;
  bool small_ = false;
  std::vector<std::pair<long, Affine2>> deferred_, unsupported_;
  std::vector<std::array<int, 6>> pending_samples_, deferred_samples_, unsupported_samples_;  // record mode only
  size_t deferred_pos_ = 0;
  size_t q_pos_ = 0;
  std::vector<std::vector<int>> nn_a_, nn_b_;
  std::vector<int> order_a_;
  std::vector<std::vector<int>> b_by_size_;  // per A rock, B rocks by size agreement (filled lazily)
  std::vector<double> log_a_, log_b_;
  double size_offset_ = 0;
  std::vector<std::pair<size_t, size_t>> edges_;
  std::vector<Star> stars_a_, stars_b_;  // per rock, see star()
  size_t ia_ = 0, jb_ = 0, first_window_ = 0;
  int pass_ = 0;
  long pending_anchor_ = 0;
};

// The sampler's hypotheses are models already: the estimator passes them on.
struct PassThroughEstimator {
  void estimate(const GuidedHypothesis& h, std::vector<Affine2>* out) const { out->push_back(h.affine); }
};

}  // namespace ipd::detail
