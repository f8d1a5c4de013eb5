// The default registration: consensus of plausible affines from guided hypotheses.
//
// Cheap hypotheses first (identity, the most voted translations), then triples drawn from local
// neighbourhoods (a rock and two of its nearest neighbours on each side), filtered by what a camera
// misalignment can do (bounded scale, shear and rotation, consistent box sizes) before any scoring.
// Each hypothesis is scored by a soft inlier count with every B rock claimed at most once, so shrinking A
// onto a few rocks earns nothing; a new best is refined by least squares on its inliers (LO-RANSAC); the
// search stops once the consensus cannot reasonably be beaten. Rocks are then paired by an optimal (Hungarian)
// assignment on the IoU of the aligned boxes.
#include <fmt/format.h>
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "core/geometry/affine_estimator.h"
#include "core/geometry/point_grid.h"
#include "core/registration/consensus/consensus_scorer.h"
#include "core/registration/consensus/consensus_search.h"
#include "core/registration/consensus/consensus_second_look.h"
#include "core/registration/pairing.h"
#include "core/registration/registration_frame.h"
#include "core/registration/registration_recorder.h"

namespace ipd::detail {

namespace {

constexpr int kNeighboursA = 5;  // a rock's neighbours used to form triples on side A
constexpr int kNeighboursB = 8;  // more on side B: some of A's neighbours may be hidden or displaced there
constexpr double kBoundSlackScale = 1.25, kBoundSlackDeg = 15.0;
constexpr double kMaxLogSizeGap = 1.1;
// Triangles flatter than this (twice the area over the longest side squared) propose a similarity, not an
// affine: large tier F1 0.9413 -> 0.9457 and 0.9572 -> 0.9588 (seeds 1, 2); 0.1 and 0.2 gained less.
constexpr double kFlatTriple = 0.05;
// Sets with at least this many rocks a side are first registered on their kCoarseRocks largest.
constexpr size_t kCoarseAbove = 160, kCoarseRocks = 64;
// The gate is never under this fraction of the picture's width (unless that is over half the rocks' spacing):
// two labellings put a rock's centre up to ~1% of the width apart however close the rocks are, and 0.3 of the
// spacing in a tight cluster (0.9% of the width) left true pairs outside the gate. Large tier F1, mean of
// seeds 0-6: 0.9697 without the floor, 0.9709 at 1.1%, 0.9721 at 1.5%, 0.9719 at 2%.
constexpr double kMinGateOfWidth = 0.015, kMaxFloorOfSpacing = 0.5;
// The fit that goes out is judged among several (final_fit) when A x B is at most this (64 rocks a side).
constexpr size_t kJudgedFitMaxPairs = 4096;

// Proposes hypotheses as affines directly (estimator = identity pass-through) so that the cheap ones and
// the triple ones share one loop, one budget and one stopping rule.
class GuidedSampler {
  // An edge from a rock to one of its neighbours, with its length.
  struct Edge {
    Eigen::Vector2d v;
    double length;
  };
  static Edge edge_of(const Eigen::Vector2d& v) { return {v, v.norm()}; }

 public:
  // `first`: hypotheses proposed before any other (the coarse pass of a large set).
  GuidedSampler(const RegistrationFrame& f, const Bounds& bounds, double gate, std::uint64_t seed, bool record,
                const std::vector<Affine2>& first)
      : f_(f),
        bounds_(bounds),
        gate2_(gate * gate),
        min_det_(bounds.min_scale * bounds.min_scale),
        max_det_(bounds.max_scale * bounds.max_scale),
        record_(record) {
    // 1. identity in image coordinates
    queue_ = first;
    queue_.push_back(f.from_image(identity_affine()));
    // 2. the most voted translations (identity linear part), votes binned at the gate size
    vote_translations(gate);
    // 3. neighbourhood triples, rocks of A in a seeded order
    // Small sets are cheap to search widely, and need it: fewer rocks keep fewer neighbours in common.
    small_ = f.a.size() <= 16 && f.b.size() <= 16;
    nn_a_ = nearest_neighbours(f.a, small_ ? kNeighboursA + 2 : kNeighboursA);
    // A side that few rocks are left on (the rest out of view): every one of them may be a neighbour.
    nn_b_ = nearest_neighbours(f.b, f.b.size() <= 12 ? static_cast<int>(f.b.size())
                                    : small_         ? kNeighboursB + 3
                                                     : kNeighboursB);
    stars_a_.resize(f.a.size());
    stars_b_.resize(f.b.size());
    order_a_.resize(f.a.size());
    std::iota(order_a_.begin(), order_a_.end(), 0);
    Rng rng(seed);
    for (size_t k = order_a_.size(); k > 1; --k) std::swap(order_a_[k - 1], order_a_[rng.below(static_cast<int>(k))]);
    // For each A rock, B rocks in order of size agreement (after the sets' median size ratio): a rock's
    // partner is usually among the first few, so confirmations come after a handful of expansions.
    auto log_sizes = [](const std::vector<Eigen::Vector2d>& sz) {
      std::vector<double> l;
      for (const auto& s : sz) l.push_back(0.5 * std::log(std::max(s.x() * s.y(), 1e-300)));
      return l;
    };
    log_a_ = log_sizes(f.size_a);
    log_b_ = log_sizes(f.size_b);
    auto median = [](std::vector<double> v) {
      if (v.empty()) return 0.0;
      std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
      return v[v.size() / 2];
    };
    size_offset_ = median(log_b_) - median(log_a_);
    const size_t m = f.b.size();
    first_window_ = std::min(m, std::max<size_t>(6, (m + 2) / 3));
    b_by_size_.resize(f.a.size());  // rows sorted when their A rock is first expanded (most never are)
  }

  const std::vector<int>& b_by_size(int i) {
    auto& row = b_by_size_[i];
    if (row.empty() && !f_.b.empty()) {
      row.resize(f_.b.size());
      std::iota(row.begin(), row.end(), 0);
      const double want = log_a_[i] + size_offset_;
      std::stable_sort(row.begin(), row.end(),
                       [&](int x, int y) { return std::abs(log_b_[x] - want) < std::abs(log_b_[y] - want); });
    }
    return row;
  }

  bool next(Affine2* out) {
    has_sample = false;
    if (q_pos_ < queue_.size()) {
      anchor = -1 - static_cast<long>(q_pos_);
      *out = queue_[q_pos_++];
      return true;
    }
    // Triples that two more neighbours confirm come first, anchor by anchor: in a first pass each A rock
    // meets the third of B closest to it in size, in a second pass the rest. Triples only one more
    // neighbour confirms are kept aside until both passes are done.
    while (pending_.empty()) {
      if (pass_ >= 2) {
        if (deferred_pos_ >= deferred_.size() && !unsupported_.empty()) {
          // Last, for small sets: triples nothing else confirms (an overlap of three or four rocks).
          deferred_.insert(deferred_.end(), unsupported_.begin(), unsupported_.end());
          deferred_samples_.insert(deferred_samples_.end(), unsupported_samples_.begin(), unsupported_samples_.end());
          unsupported_.clear();
        }
        if (deferred_pos_ >= deferred_.size()) return false;
        anchor = deferred_[deferred_pos_].first;
        if (record_) sample = deferred_samples_[deferred_pos_], has_sample = true;
        *out = deferred_[deferred_pos_++].second;
        return true;
      }
      const size_t lo = pass_ == 0 ? 0 : first_window_, hi = pass_ == 0 ? first_window_ : f_.b.size();
      if (jb_ < lo) jb_ = lo;
      if (ia_ >= f_.a.size() || lo >= hi) {
        ++pass_;
        ia_ = 0;
        jb_ = 0;
        continue;
      }
      const int i = order_a_[ia_];
      pending_anchor_ = i;
      expand(i, b_by_size(i)[jb_]);
      if (++jb_ >= hi) jb_ = lo, ++ia_;
    }
    anchor = pending_anchor_;  // rock of A the hypothesis grew from; a wrong match rarely repeats
    *out = pending_.back();
    pending_.pop_back();
    if (record_) sample = pending_samples_.back(), has_sample = true, pending_samples_.pop_back();
    return true;
  }

  long anchor = -1;
  // The current hypothesis' rocks (record mode): A's three then B's three, in matching order.
  std::array<int, 6> sample{};
  bool has_sample = false;

 private:
  void vote_translations(double gate) {
    const Affine2 id = f_.from_image(identity_affine());
    if (f_.a.size() * f_.b.size() > 250000) return;  // huge sets: the triples alone are cheaper
    for (const auto& t : top_translations(id.leftCols<2>(), f_.a, f_.b, gate, 3)) {
      Affine2 m = id;
      m.col(2) = t;
      queue_.push_back(m);
    }
  }

  // All plausible triples anchored at A rock i and B rock j: pairs of compatible neighbour edges, each
  // kept only if another neighbour of i lands near a neighbour of j (local verification is far cheaper
  // than scoring the whole set).
  void expand(int i, int j) {
    if (!sizes_agree(i, j)) return;
    const auto& ni = nn_a_[i];
    const auto& nj = nn_b_[j];
    edges_.clear();
    const Star& sa = star(i, f_.a, nn_a_, &stars_a_);
    const Star& sb = star(j, f_.b, nn_b_, &stars_b_);
    const size_t na = ni.size(), nb = nj.size();
    for (size_t u = 0; u < ni.size(); ++u)
      for (size_t x = 0; x < nj.size(); ++x)
        if (sizes_agree(ni[u], nj[x]) && edge_plausible(sa.edges[u], sb.edges[x])) edges_.emplace_back(u, x);
    for (size_t e1 = 0; e1 < edges_.size(); ++e1)
      for (size_t e2 = e1 + 1; e2 < edges_.size(); ++e2) {
        const auto [u1, x1] = edges_[e1];
        const auto [u2, x2] = edges_[e2];
        if (u1 == u2 || x1 == x2) continue;
        // Before solving: the triangle's orientation must survive (no reflection) and its area ratio is the
        // affine's determinant, bounded by the squared scale bounds. Two cross products reject most pairs.
        const double area_a = sa.cross[u1 * na + u2], area_b = sb.cross[x1 * nb + x2];
        // Nearly collinear (often the only true pairs of a small overlap): labelling noise decides the affine
        // across the line, even the triangle's orientation, so only the similarity along it is tried.
        const bool flat = sa.flat[u1 * na + u2] || sb.flat[x1 * nb + x2];
        const Eigen::Vector2d& a1 = sa.edges[u1].v;
        const Eigen::Vector2d& a2 = sa.edges[u2].v;
        const Eigen::Vector2d& b1 = sb.edges[x1].v;
        const Eigen::Vector2d& b2 = sb.edges[x2].v;
        if (!flat) {
          if (!(area_a * area_b > 0)) continue;
          const double det = area_b / area_a;
          if (det < min_det_ || det > max_det_) continue;
        } else {
          // A similarity keeps the angle between the two edges (on a line: both one way, or opposite) and
          // scales both alike; cheap tests before its least squares (about a fifth of all triples are flat).
          if (a1.dot(a2) * b1.dot(b2) < 0) continue;
          const double r1 = b1.squaredNorm() * a2.squaredNorm(), r2 = b2.squaredNorm() * a1.squaredNorm();
          if (r1 > 4 * r2 || r2 > 4 * r1) continue;
        }
        const Eigen::Vector2d src[3] = {f_.a[i], f_.a[ni[u1]], f_.a[ni[u2]]};
        const Eigen::Vector2d dst[3] = {f_.b[j], f_.b[nj[x1]], f_.b[nj[x2]]};
        Affine2 m;
        if (flat) {
          if (!similarity_fits(src, dst, &m)) continue;
        } else {
          // From the edges and cross product at hand (the triangle is not flat: area_a is well away from 0).
          affine_from_edges(a1, a2, b1, b2, area_a, f_.a[i], f_.b[j], &m);
          if (!m.allFinite() || !bounds_.plausible(m.leftCols<2>())) continue;
        }
        const int support = ni.size() >= 4 ? local_support(m, i, j, u1, u2) : 2;
        if (support >= 2)
          pending_.push_back(m);
        else if (support == 1)
          deferred_.emplace_back(i, m);
        else if (small_)
          unsupported_.emplace_back(i, m);
        if (record_ && (support >= 1 || small_))
          (support >= 2   ? pending_samples_
           : support == 1 ? deferred_samples_
                          : unsupported_samples_)
              .push_back({i, ni[u1], ni[u2], j, nj[x1], nj[x2]});
      }
    std::reverse(pending_.begin(), pending_.end());  // pop_back hands them out in generation order
    std::reverse(pending_samples_.begin(), pending_samples_.end());
  }

  // A rock's edges to its neighbours (vector, length) and, for every ordered pair of them (n x n, row p), the
  // cross product and whether their triangle is flat; filled on first use. A rock anchors many expansions, and
  // the edge-pairing loop redid all of this per pair (large tier: 8% fewer instructions in all, callgrind).
  struct Star {
    std::vector<Edge> edges;
    std::vector<double> cross;
    std::vector<char> flat;
  };
  static const Star& star(int k, const std::vector<Eigen::Vector2d>& p, const std::vector<std::vector<int>>& nn,
                          std::vector<Star>* stars) {
    Star& s = (*stars)[k];
    if (!s.edges.empty() || nn[k].empty()) return s;
    for (int u : nn[k]) s.edges.push_back(edge_of(p[u] - p[k]));
    const size_t n = s.edges.size();
    s.cross.assign(n * n, 0.0);
    s.flat.assign(n * n, 1);
    for (size_t a = 0; a < n; ++a)
      for (size_t b = a + 1; b < n; ++b) {
        const Eigen::Vector2d &e = s.edges[a].v, &g = s.edges[b].v;
        const double c = e.x() * g.y() - e.y() * g.x();
        s.cross[a * n + b] = c, s.cross[b * n + a] = -c;
        s.flat[a * n + b] = s.flat[b * n + a] = flat_triangle(c, e, g);
      }
    return s;
  }

  // triangle_conditioning() < kFlatTriple, from the edges and cross product expand() already has.
  static bool flat_triangle(double cross, const Eigen::Vector2d& e1, const Eigen::Vector2d& e2) {
    const double longest = std::max({e1.squaredNorm(), e2.squaredNorm(), (e2 - e1).squaredNorm()});
    return !(std::abs(cross) >= kFlatTriple * longest);
  }
  // The least-squares similarity of a flat triple, when it puts each of the three within the gate.
  bool similarity_fits(const Eigen::Vector2d src[3], const Eigen::Vector2d dst[3], Affine2* m) const {
    if (!similarity_least_squares(src, dst, 3, m) || !bounds_.plausible(m->leftCols<2>())) return false;
    for (int k = 0; k < 3; ++k)
      if ((apply(*m, src[k]) - dst[k]).squaredNorm() >= gate2_) return false;
    return true;
  }

  // How many other neighbours of i land within the gate of a neighbour of j (counted up to 2).
  int local_support(const Affine2& m, int i, int j, size_t u1, size_t u2) const {
    const auto& ni = nn_a_[i];
    const auto& nj = nn_b_[j];
    int support = 0;
    for (size_t u = 0; u < ni.size() && support < 2; ++u) {
      if (u == u1 || u == u2) continue;
      const Eigen::Vector2d p = apply(m, f_.a[ni[u]]);
      for (int x : nj)
        if ((f_.b[x] - p).squaredNorm() < gate2_) {
          ++support;
          break;
        }
    }
    return support;
  }

  // An edge of A can only map onto an edge of B whose length ratio lies within the scale bounds and whose
  // direction turned by at most the rotation bound plus what shear and anisotropic scale can add.
  bool edge_plausible(const Edge& ea, const Edge& eb) const {
    const double la = ea.length, lb = eb.length;
    if (!(la > 0) || !(lb > 0)) return false;
    const double ratio = lb / la;
    if (ratio < bounds_.min_scale || ratio > bounds_.max_scale) return false;
    return ea.v.dot(eb.v) >= bounds_.cos_edge_turn * la * lb;
  }

  // Two labellings of one rock differ in log size by < 0.56 in 99% of POLAR-Sim pairs; 1.1 leaves room for
  // the box growth a rotation causes and for the offset's error: the sets' median sizes differ by more than
  // the scale when one side keeps only part of the rocks (clipped, or missing its small ones). 0.8 lost the
  // true triples of such cases (large tier F1 0.924 -> 0.936 with it, 100 cases).
  bool sizes_agree(int i, int j) const { return std::abs(log_b_[j] - log_a_[i] - size_offset_) < kMaxLogSizeGap; }

  const RegistrationFrame& f_;
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

struct PassThroughEstimator {
  void estimate(const Affine2& m, std::vector<Affine2>* out) const { out->push_back(m); }
};

// The second look (consensus_second_look.h) when the search ended unconfirmed (it ran out of hypotheses or
// trials: 15% of the large tier's cases) on a small set: its candidates and the search's best are judged on
// the pairing each produces, and the best judged wins. Confirmed searches keep their answer: looking again
// there changed nothing on the benchmark.
void second_look(const RegistrationFrame& f, const std::vector<Box>& boxes_a, const std::vector<Box>& boxes_b,
                 const RegistrationOptions& o, const Bounds& bounds, ConsensusScorer* scorer, SearchRecorder* recorder,
                 MethodOutcome* out) {
  const double na = static_cast<double>(f.a.size()), nb = static_cast<double>(f.b.size());
  if (out->stop == StopReason::kCannotBeBeaten) return;
  if (na < 2 || nb < 2 || na * (na - 1) / 2 * nb * (nb - 1) > kMaxEdgePairs) return;
  EdgeSearch edges = edge_candidates(f, bounds, scorer, kEdgeCandidates);
  out->hypotheses += edges.hypotheses;
  out->work += edges.work;
  std::vector<Affine2> pool{out->affine_normalised};
  for (const auto& m : edges.candidates)
    if (std::none_of(pool.begin(), pool.end(), [&](const Affine2& p) { return recorder->agree(p, m); }))
      pool.push_back(m);
  std::vector<Judgement> judged;
  for (const auto& m : pool)
    judged.push_back(judge_candidate(f, boxes_a, boxes_b, m, scorer->score(m), pairing_rule(o)));
  size_t best = 0;
  for (size_t k = 1; k < pool.size(); ++k)
    if (judged[k].total > judged[best].total) best = k;
  double rival = -INFINITY;
  for (size_t k = 0; k < pool.size(); ++k)
    if (k != best) rival = std::max(rival, judged[k].total);
  // Replays show the candidates the second look judged, then the one it kept (when not the search's best).
  for (size_t k = 1; k < pool.size(); ++k)
    recorder->add_step(TraceStepKind::kRefinement, pool[k], judged[k].consensus, out->score, false);
  out->note += fmt::format("{}second look: {} similarities from rock pairs, {} candidates judged; ",
                           out->note.empty() ? "" : "; ", edges.hypotheses, pool.size() - 1);
  if (best != 0) {
    out->affine_normalised = pool[best];
    out->score = judged[best].consensus;
    recorder->add_step(TraceStepKind::kPolish, pool[best], out->score, out->score, true);
    out->note += "one of them replaced the search's best";
  } else {
    out->note += "the search's best kept";
  }
  // The judged pool now holds the rivals: confidence compares the best judgement with the next distinct one.
  out->confidence = confidence_from_scores(judged[best].total, rival);
}

// Large sets first register their largest rocks alone. Both labellings see the large rocks, which are few
// and far apart, so a few hypotheses find their alignment; proposed first on the whole set, it is refined and
// usually ends the search at once. Without it a dense layout of 500 rocks a side needed ~100 hypotheses,
// each anchored on a third of B (8.2 ms against 1.4 at 200 rocks: twice the n log n trend), and under the
// large tier's misalignment it mostly failed (synthetic 500 rocks: F1 0.54 -> 0.86, ceiling 0.86).
std::vector<Affine2> coarse_hypotheses(const RegistrationFrame& f, const std::vector<Box>& boxes_a,
                                       const std::vector<Box>& boxes_b, const RegistrationOptions& o) {
  const size_t rocks = kCoarseRocks;
  if (boxes_a.size() < kCoarseAbove || boxes_b.size() < kCoarseAbove) return {};
  auto largest = [&](const std::vector<Box>& boxes) {
    std::vector<int> order(boxes.size());
    std::iota(order.begin(), order.end(), 0);
    // Ties by index, so the subset never depends on the sort's implementation.
    std::partial_sort(order.begin(), order.begin() + rocks, order.end(), [&](int x, int y) {
      const double ax = boxes[x].w * boxes[x].h, ay = boxes[y].w * boxes[y].h;
      return ax != ay ? ax > ay : x < y;
    });
    std::vector<Box> out;
    for (size_t k = 0; k < rocks; ++k) out.push_back(boxes[order[k]]);
    return out;
  };
  RegistrationOptions sub = o;
  sub.record_trace = false;
  const RegistrationReport r = register_rocks(largest(boxes_a), largest(boxes_b), sub);
  if (r.inliers < 3) return {};
  return {f.from_image(r.affine)};
}

// The fit that goes out, judged on the pairing it gives (consensus + IoU - unpaired rocks) among the polished
// one, the search's own (polishing fits every inlier alike, a wrong one included) and plain least squares on
// the inliers (the consensus' kernel can prefer an exact fit of three rocks that pairs worse than a fit of all
// of them). Large tier F1, mean of seeds 0-6: 0.9705 with the polished fit always, 0.9715 judged against the
// search's, 0.9721 with least squares too (seed 1: 0.9675, 0.9691, 0.9705); no seed lost more than 0.0002 at
// either step. Small sets only: with many inliers one wrong pair barely moves the polish, and the three
// pairings would add a third to 500 rocks a side (callgrind: 21.4 -> 29.1 million instructions).
Affine2 final_fit(const RegistrationFrame& f, const std::vector<Box>& boxes_a, const std::vector<Box>& boxes_b,
                  const RegistrationOptions& o, const Bounds& bounds, double gate, ConsensusScorer* scorer,
                  const Affine2& searched) {
  Affine2 polished = searched;
  scorer->polish(&polished);
  if (f.a.size() * f.b.size() > kJudgedFitMaxPairs) return polished;
  std::vector<Affine2> fits{polished, searched};
  std::vector<Eigen::Vector2d> src, dst;
  scorer->inlier_pairs(searched, gate * gate, &src, &dst);
  Affine2 least_squares;
  if (src.size() >= 3 && affine_least_squares(src, dst, &least_squares) &&
      bounds.plausible(least_squares.leftCols<2>()))
    fits.push_back(least_squares);
  Affine2 out = polished;
  double best_total = -INFINITY;
  for (const auto& m : fits) {
    const double total = judge_candidate(f, boxes_a, boxes_b, m, scorer->score(m), pairing_rule(o)).total;
    if (total > best_total) best_total = total, out = m;
  }
  return out;
}

}  // namespace

MethodOutcome register_consensus(const RegistrationFrame& f, const std::vector<Box>& boxes_a,
                                 const std::vector<Box>& boxes_b, const RegistrationOptions& o,
                                 const Deadline& deadline) {
  MethodOutcome out;
  // A triple of nearby rocks carries their labelling noise into its affine (several degrees, tens of
  // percent of scale), so hypotheses are held to the user's bounds with that much slack.
  const Bounds bounds{o.min_scale / kBoundSlackScale, o.max_scale * kBoundSlackScale,
                      (o.max_rotation_deg + kBoundSlackDeg) * M_PI / 180.0, o.max_anisotropy};
  // The gate: 0.3 of the typical spacing of B's rocks, within [0.02, 0.2] of the layout's spread (normalised
  // units, so shifting or scaling a layout within the picture keeps it), and not under kMinGateOfWidth.
  double gate = o.inlier_gate / f.spread;
  if (!(gate > 0)) {
    const double spacing = median_nn_distance(f.b);
    gate = std::max(std::clamp(0.3 * spacing, 0.02, 0.2),
                    std::min(kMinGateOfWidth / f.spread, kMaxFloorOfSpacing * spacing));
  }
  out.affine_normalised = f.from_image(identity_affine());
  if (!f.a.empty() && !f.b.empty()) {
    GuidedSampler sampler(f, bounds, gate, o.seed, o.record_trace, coarse_hypotheses(f, boxes_a, boxes_b, o));
    ConsensusScorer scorer(f, gate, bounds, o.max_trials, &sampler.anchor);
    PassThroughEstimator estimator;
    RobustLoopOptions lo;
    lo.max_trials = o.max_trials;
    lo.max_work = work_budget(o, f.a.size(), f.b.size());
    lo.work_per_model = static_cast<double>(f.a.size());  // one nearest-neighbour query per A rock
    auto sample_of = [&](const Affine2&, std::vector<int>* sa, std::vector<int>* sb) {
      if (!sampler.has_sample) return;  // identity and voted translations are not built from rocks
      sa->assign(sampler.sample.begin(), sampler.sample.begin() + 3);
      sb->assign(sampler.sample.begin() + 3, sampler.sample.end());
    };
    SearchRecorder recorder(
        f, gate, o.record_trace, [](double s) { return s; }, sample_of);
    DeadlineSampler<GuidedSampler> timed{sampler, deadline, o.max_trials};
    auto r = run_robust_loop<Affine2, Affine2>(timed, estimator, scorer, lo, recorder);
    r.stop = timed.stop(r.stop);
    out.trials = r.trials;
    out.hypotheses = r.hypotheses;
    out.work = r.work;
    out.stop = r.stop;
    if (r.found && std::isfinite(r.best_score) && deadline.passed()) {
      // Each stage after the search scores whole sets again (tens of milliseconds on 5,000 rocks): with the
      // time budget spent the answer is the search's best as it stands, judged against the rivals it scored.
      out.affine_normalised = r.best;
      out.score = r.best_score;
      out.stop = StopReason::kTimeBudget;
      out.confidence = confidence_from_scores(r.best_score, recorder.rival_score());
      out.note = "time budget spent: the search's best, without the rival placements, polish or second look";
    } else if (r.found && std::isfinite(r.best_score)) {
      out.affine_normalised = r.best;
      out.score = r.best_score;
      // The search stops as soon as its best can't be beaten, often before a rival is scored. Shifted
      // placements are the rivals a small overlap allows (a patch of rocks that fits in several places), so
      // the translations most rock pairs agree on under the best's linear part are scored too.
      const ShiftedPlacements shifted =
          shifted_placements(&scorer, recorder, f, r.best, r.best.leftCols<2>(), gate, false);
      double answer = r.best_score, rival = std::max(recorder.rival_score(), shifted.rival);
      // Never hand out an alignment a placement we scored beats (a 7 x 7 grid and the same grid one column on
      // stopped at the identity, 42 of 49 rocks, while the shift fits all). When the search's own alignment,
      // placed better, fits at least as well as the rival, that is the answer (least squares cannot refine
      // rocks on a line); otherwise the rival is, flagged. Only then: adopting the better placed own
      // alignment every time lost two large-tier cases (F1 0.9705 -> 0.9693).
      if (shifted.rival > answer && shifted.same >= shifted.rival) {
        out.affine_normalised = shifted.same_model;
        out.score = answer = shifted.same;
        recorder.add_step(TraceStepKind::kRefinement, out.affine_normalised, answer, answer, true);
      } else if (shifted.rival > answer) {
        Affine2 m = shifted.rival_model;
        double s = shifted.rival;
        scorer.improve(&m, &s);
        out.affine_normalised = m;
        // Against the search's best and the adopted placement's own rivals (the grid's other shifts).
        const double others = shifted_placements(&scorer, recorder, f, m, m.leftCols<2>(), gate, false).rival;
        rival = std::max({answer, shifted.same, others});
        out.score = answer = s;
        out.beaten = true;
        recorder.add_step(TraceStepKind::kRefinement, m, s, s, true);
        out.note = "a shifted placement scored after the search fitted better than its best: used";
      }
      // A confirmed best only: an unconfirmed one is judged against the second look's candidates next, and
      // raising it alone would tilt that comparison (3 true pairs among 15 rocks: seed 5 of
      // SmallOverlap.ThreeTruePairsAmongFifteenRocksAt25Degrees).
      if (r.stop == StopReason::kCannotBeBeaten && scorer.soft_refine(&out.affine_normalised, &out.score))
        recorder.add_step(TraceStepKind::kRefinement, out.affine_normalised, out.score, out.score, true);
      out.affine_normalised = final_fit(f, boxes_a, boxes_b, o, bounds, gate, &scorer, out.affine_normalised);
      recorder.add_step(TraceStepKind::kPolish, out.affine_normalised, out.score, out.score, false);
      out.confidence = confidence_from_scores(answer, rival);  // both as searched, before the soft refinement
      second_look(f, boxes_a, boxes_b, o, bounds, &scorer, &recorder, &out);
    } else if (r.stop == StopReason::kTimeBudget) {
      out.note = "time budget spent before a plausible affine was found: identity used";
      out.confidence = 0;
    } else {
      out.note = "no plausible affine found: identity used";
      out.confidence = 0;
    }
    out.trace = recorder.take_trace(describe_stop(r.stop, r.trials, r.hypotheses, r.work, lo.max_work));
    out.inliers = scorer.count_inliers(out.affine_normalised);
    if (f.a.size() < 3 || f.b.size() < 3) out.note = "fewer than 3 rocks on a side: translation at most";
  } else {
    out.stop = StopReason::kTooFewPoints;
    out.note = "a side has no rocks: nothing to register";
  }
  out.pairs = pair_aligned_boxes(f.to_image(out.affine_normalised), boxes_a, boxes_b, pairing_rule(o));
  return out;
}

}  // namespace ipd::detail
