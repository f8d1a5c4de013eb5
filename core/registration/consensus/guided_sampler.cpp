#include "core/registration/consensus/guided_sampler.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/geometry/affine_estimator.h"
#include "core/registration/consensus/consensus_search.h"
#include "core/registration/consensus/consensus_tuning.h"

namespace ipd::detail {

GuidedSampler::GuidedSampler(const RegistrationFrame& f, const Bounds& bounds, double gate, std::uint64_t seed,
                             bool record, const std::vector<Affine2>& first, const Deadline* deadline)
    : f_(f),
      deadline_(deadline),
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
  small_ = f.a.size() <= kTuning.small_set && f.b.size() <= kTuning.small_set;
  nn_a_ = nearest_neighbours(f.a, small_ ? kTuning.neighbours_a + 2 : kTuning.neighbours_a, deadline);
  if (deadline != nullptr && deadline->passed()) return;
  // A side that few rocks are left on (the rest out of view): every one of them may be a neighbour.
  nn_b_ = nearest_neighbours(f.b,
                             f.b.size() <= kTuning.all_neighbours_below ? static_cast<int>(f.b.size())
                             : small_                                   ? kTuning.neighbours_b + 3
                                                                        : kTuning.neighbours_b,
                             deadline);
  if (deadline != nullptr && deadline->passed()) return;
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

const std::vector<int>& GuidedSampler::b_by_size(int i) {
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

bool GuidedSampler::next(GuidedHypothesis* out) {
  has_sample = false;
  if (q_pos_ < queue_.size()) {
    out->anchor = -1 - static_cast<long>(q_pos_);
    out->affine = queue_[q_pos_++];
    return true;
  }
  // Triples that two more neighbours confirm come first, anchor by anchor: in a first pass each A rock
  // meets the third of B closest to it in size, in a second pass the rest. Triples only one more
  // neighbour confirms are kept aside until both passes are done.
  for (int expanded = 0; pending_.empty(); ++expanded) {
    if (deadline_ != nullptr && (expanded & 63) == 63 && deadline_->passed()) return false;
    if (pass_ >= 2) return next_deferred(out);
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
  out->anchor = pending_anchor_;
  out->affine = pending_.back();
  pending_.pop_back();
  if (record_) sample = pending_samples_.back(), has_sample = true, pending_samples_.pop_back();
  return true;
}

bool GuidedSampler::next_deferred(GuidedHypothesis* out) {
  if (deferred_pos_ >= deferred_.size() && !unsupported_.empty()) {
    // Last, for small sets: triples nothing else confirms (an overlap of three or four rocks).
    deferred_.insert(deferred_.end(), unsupported_.begin(), unsupported_.end());
    deferred_samples_.insert(deferred_samples_.end(), unsupported_samples_.begin(), unsupported_samples_.end());
    unsupported_.clear();
  }
  if (deferred_pos_ >= deferred_.size()) return false;
  out->anchor = deferred_[deferred_pos_].first;
  if (record_) sample = deferred_samples_[deferred_pos_], has_sample = true;
  out->affine = deferred_[deferred_pos_++].second;
  return true;
}

void GuidedSampler::vote_translations(double gate) {
  const Affine2 id = f_.from_image(identity_affine());
  if (f_.a.size() * f_.b.size() > kTuning.max_vote_pairs) return;  // huge sets: the triples alone are cheaper
  for (const auto& t : top_translations(id.leftCols<2>(), f_.a, f_.b, gate, 3)) {
    Affine2 m = id;
    m.col(2) = t;
    queue_.push_back(m);
  }
}

// All plausible triples anchored at A rock i and B rock j: pairs of compatible neighbour edges, each
// kept only if another neighbour of i lands near a neighbour of j (local verification is far cheaper
// than scoring the whole set).
void GuidedSampler::expand(int i, int j) {
  if (!sizes_agree(i, j)) return;
  const auto& ni = nn_a_[i];
  const auto& nj = nn_b_[j];
  edges_.clear();
  const Star& sa = star(i, f_.a, nn_a_, &stars_a_);
  const Star& sb = star(j, f_.b, nn_b_, &stars_b_);
  for (size_t u = 0; u < ni.size(); ++u)
    for (size_t x = 0; x < nj.size(); ++x)
      if (sizes_agree(ni[u], nj[x]) && edge_plausible(sa.edges[u], sb.edges[x])) edges_.emplace_back(u, x);
  for (size_t e1 = 0; e1 < edges_.size(); ++e1)
    for (size_t e2 = e1 + 1; e2 < edges_.size(); ++e2) {
      const auto [u1, x1] = edges_[e1];
      const auto [u2, x2] = edges_[e2];
      if (u1 == u2 || x1 == x2) continue;
      Affine2 m;
      if (!triple_affine(i, j, u1, u2, x1, x2, sa, sb, &m)) continue;
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

// The affine of the triple (i, its neighbours u1, u2) -> (j, its neighbours x1, x2), when it is plausible.
bool GuidedSampler::triple_affine(int i, int j, size_t u1, size_t u2, size_t x1, size_t x2, const Star& sa,
                                  const Star& sb, Affine2* m) const {
  const auto& ni = nn_a_[i];
  const auto& nj = nn_b_[j];
  const size_t na = ni.size(), nb = nj.size();
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
    if (!(area_a * area_b > 0)) return false;
    const double det = area_b / area_a;
    if (det < min_det_ || det > max_det_) return false;
  } else {
    // A similarity keeps the angle between the two edges (on a line: both one way, or opposite) and
    // scales both alike; cheap tests before its least squares (about a fifth of all triples are flat).
    if (a1.dot(a2) * b1.dot(b2) < 0) return false;
    const double r1 = b1.squaredNorm() * a2.squaredNorm(), r2 = b2.squaredNorm() * a1.squaredNorm();
    if (r1 > 4 * r2 || r2 > 4 * r1) return false;
  }
  if (flat) {
    const Eigen::Vector2d src[3] = {f_.a[i], f_.a[ni[u1]], f_.a[ni[u2]]};
    const Eigen::Vector2d dst[3] = {f_.b[j], f_.b[nj[x1]], f_.b[nj[x2]]};
    return similarity_fits(src, dst, m);
  }
  // From the edges and cross product at hand (the triangle is not flat: area_a is well away from 0).
  affine_from_edges(a1, a2, b1, b2, area_a, f_.a[i], f_.b[j], m);
  return m->allFinite() && bounds_.plausible(m->leftCols<2>());
}

const GuidedSampler::Star& GuidedSampler::star(int k, const std::vector<Eigen::Vector2d>& p,
                                               const std::vector<std::vector<int>>& nn, std::vector<Star>* stars) {
  Star& s = (*stars)[k];
  if (!s.edges.empty() || nn[k].empty()) return s;
  for (int u : nn[k]) {
    const Eigen::Vector2d v = p[u] - p[k];
    s.edges.push_back({v, v.norm()});
  }
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

// triangle_conditioning() < kTuning.flat_triple, from the edges and cross product expand() already has.
bool GuidedSampler::flat_triangle(double cross, const Eigen::Vector2d& e1, const Eigen::Vector2d& e2) {
  const double longest = std::max({e1.squaredNorm(), e2.squaredNorm(), (e2 - e1).squaredNorm()});
  return !(std::abs(cross) >= kTuning.flat_triple * longest);
}

// The least-squares similarity of a flat triple, when it puts each of the three within the gate.
bool GuidedSampler::similarity_fits(const Eigen::Vector2d src[3], const Eigen::Vector2d dst[3], Affine2* m) const {
  if (!similarity_least_squares(src, dst, 3, m) || !bounds_.plausible(m->leftCols<2>())) return false;
  for (int k = 0; k < 3; ++k)
    if ((apply(*m, src[k]) - dst[k]).squaredNorm() >= gate2_) return false;
  return true;
}

// How many other neighbours of i land within the gate of a neighbour of j (counted up to 2).
int GuidedSampler::local_support(const Affine2& m, int i, int j, size_t u1, size_t u2) const {
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
bool GuidedSampler::edge_plausible(const Edge& ea, const Edge& eb) const {
  const double la = ea.length, lb = eb.length;
  if (!(la > 0) || !(lb > 0)) return false;
  const double ratio = lb / la;
  if (ratio < bounds_.min_scale || ratio > bounds_.max_scale) return false;
  return ea.v.dot(eb.v) >= bounds_.cos_edge_turn * la * lb;
}

// Two labellings of one rock differ in log size by < 0.56 in 99% of POLAR-Sim pairs; kTuning.max_log_size_gap
// leaves room for the box growth a rotation causes and for the offset's error (the sets' median sizes differ by
// more than the scale when one side keeps only part of the rocks).
bool GuidedSampler::sizes_agree(int i, int j) const {
  return std::abs(log_b_[j] - log_a_[i] - size_offset_) < kTuning.max_log_size_gap;
}

}  // namespace ipd::detail
