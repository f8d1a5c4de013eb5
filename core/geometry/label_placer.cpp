#include "core/geometry/label_placer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ipd {

bool overlaps(const LabelRect& a, const LabelRect& b) {
  return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

std::string LabelPlacementOptions::validate() const {
  if (!(bounds.x1 > bounds.x0 && bounds.y1 > bounds.y0)) return "the bounds are empty";
  if (!(gap >= 0)) return "gap must be >= 0";
  if (!(max_leader >= 0)) return "max_leader must be >= 0";
  if (!(exclusive_clearance >= 0)) return "exclusive_clearance must be >= 0";
  return {};
}

void LabelPlacementOptions::check() const {
  if (const std::string problem = validate(); !problem.empty())
    throw std::invalid_argument("label placement: " + problem);
}

namespace {

LabelRect at(double x, double y, double w, double h) { return {x, y, x + w, y + h}; }

bool inside(const LabelRect& r, const LabelRect& bounds) {
  return r.x0 >= bounds.x0 && r.y0 >= bounds.y0 && r.x1 <= bounds.x1 && r.y1 <= bounds.y1;
}

double overlap_area(const LabelRect& a, const LabelRect& b) {
  const double w = std::min(a.x1, b.x1) - std::max(a.x0, b.x0), h = std::min(a.y1, b.y1) - std::max(a.y0, b.y0);
  return (w > 0 && h > 0) ? w * h : 0;
}

// Whether the segment p -> q crosses the rectangle's interior (Liang-Barsky clipping).
bool segment_hits(double px, double py, double qx, double qy, const LabelRect& r) {
  double t0 = 0, t1 = 1;
  const double dx = qx - px, dy = qy - py;
  const double p[4] = {-dx, dx, -dy, dy}, q[4] = {px - r.x0, r.x1 - px, py - r.y0, r.y1 - py};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0) {
      if (q[i] <= 0) return false;
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0)
      t0 = std::max(t0, t);
    else
      t1 = std::min(t1, t);
    if (t0 >= t1) return false;
  }
  return true;
}

// The gap between two rectangles (0 when they touch or overlap).
double distance(const LabelRect& a, const LabelRect& b) {
  const double dx = std::max({0.0, a.x0 - b.x1, b.x0 - a.x1}), dy = std::max({0.0, a.y0 - b.y1, b.y0 - a.y1});
  return std::hypot(dx, dy);
}

// The point of `r` nearest to (x, y).
void nearest(const LabelRect& r, double x, double y, double& nx, double& ny) {
  nx = std::clamp(x, r.x0, r.x1);
  ny = std::clamp(y, r.y0, r.y1);
}

struct Candidate {
  LabelPosition pos;
  LabelRect box;
};

// The spots beside a target, in order of preference: above and below (left- then right-aligned), the inside
// corners when the label fits inside with a gap all round, then left and right.
std::vector<Candidate> spots_beside(const LabelRect& t, double w, double h, double g) {
  std::vector<Candidate> cands = {
      {LabelPosition::kAbove, at(t.x0, t.y0 - g - h, w, h)},
      {LabelPosition::kBelow, at(t.x0, t.y1 + g, w, h)},
      {LabelPosition::kAbove, at(t.x1 - w, t.y0 - g - h, w, h)},
      {LabelPosition::kBelow, at(t.x1 - w, t.y1 + g, w, h)},
  };
  if (w + 2 * g <= t.width() && h + 2 * g <= t.height()) {
    cands.push_back({LabelPosition::kInsideTopLeft, at(t.x0 + g, t.y0 + g, w, h)});
    cands.push_back({LabelPosition::kInsideTopRight, at(t.x1 - g - w, t.y0 + g, w, h)});
    cands.push_back({LabelPosition::kInsideBottomLeft, at(t.x0 + g, t.y1 - g - h, w, h)});
    cands.push_back({LabelPosition::kInsideBottomRight, at(t.x1 - g - w, t.y1 - g - h, w, h)});
  }
  cands.push_back({LabelPosition::kLeft, at(t.x0 - g - w, t.y0, w, h)});
  cands.push_back({LabelPosition::kRight, at(t.x1 + g, t.y0, w, h)});
  return cands;
}

// The greedy placement's state: the requests, the options and every rectangle taken so far.
class LabelPlacer {
 public:
  LabelPlacer(const std::vector<LabelRequest>& requests, const LabelPlacementOptions& o)
      : requests_(requests), o_(o), occupied_(o.taken) {}

  // Label i beside its target; false when no spot there is free and unambiguous.
  bool place_beside(size_t i, PlacedLabel* placed) {
    const LabelRect& t = requests_[i].target;
    const std::vector<Candidate> cands = spots_beside(t, requests_[i].width, requests_[i].height, o_.gap);
    // The first free spot that hides no other target; else the free spot hiding least.
    int best = -1;
    double best_cover = INFINITY;
    for (size_t c = 0; c < cands.size() && best_cover > 0; ++c) {
      if (!free(cands[c].box) || !unambiguous(cands[c].box, i, false)) continue;
      const double cover = covers(cands[c].box, i);
      if (cover < best_cover) best_cover = cover, best = int(c);
    }
    if (best < 0) return false;
    placed->position = cands[best].pos;
    placed->box = cands[best].box;
    occupied_.push_back(placed->box);
    return true;
  }

  // Label i a little way off with a short leader: rings of spots farther out, nearest first, the line crossing
  // no other label; false when none fits within max_leader label heights.
  bool place_with_leader(size_t i, PlacedLabel* placed) {
    const LabelRect& t = requests_[i].target;
    const double w = requests_[i].width, h = requests_[i].height;
    const double cx = 0.5 * (t.x0 + t.x1), cy = 0.5 * (t.y0 + t.y1);
    for (double d = 1; d <= o_.max_leader; d += 0.5) {
      const double r = d * h;
      for (int k = 0; k < 16; ++k) {
        const double a = -M_PI / 2 + k * M_PI / 8;  // starting above, clockwise
        // Box placed so its nearest point lies r beyond the target's edge in direction a.
        const double ux = std::cos(a), uy = std::sin(a);
        const double ex = ux > 0 ? t.x1 : t.x0, ey = uy > 0 ? t.y1 : t.y0;
        const double ax = std::abs(ux) < 1e-9 ? cx : ex + ux * r, ay = std::abs(uy) < 1e-9 ? cy : ey + uy * r;
        const double bx = ux > 1e-9 ? ax : ux < -1e-9 ? ax - w : ax - w / 2;
        const double by = uy > 1e-9 ? ay : uy < -1e-9 ? ay - h : ay - h / 2;
        const LabelRect box = at(bx, by, w, h);
        if (!free(box) || overlaps(box, t) || !unambiguous(box, i, true)) continue;
        double lx0, ly0, lx1, ly1;
        nearest(box, cx, cy, lx1, ly1);
        nearest(t, lx1, ly1, lx0, ly0);
        bool crosses = false;
        for (const LabelRect& q : occupied_) crosses |= segment_hits(lx0, ly0, lx1, ly1, q);
        if (crosses || !leader_clear(lx0, ly0, lx1, ly1, i)) continue;
        placed->position = LabelPosition::kLeader;
        placed->box = box;
        placed->leader_x0 = lx0, placed->leader_y0 = ly0, placed->leader_x1 = lx1, placed->leader_y1 = ly1;
        occupied_.push_back(box);
        return true;
      }
    }
    return false;
  }

 private:
  // Inside the bounds and a gap away from everything taken.
  bool free(const LabelRect& r) const {
    if (!inside(r, o_.bounds)) return false;
    const double g = o_.gap;
    const LabelRect grown{r.x0 - g, r.y0 - g, r.x1 + g, r.y1 + g};
    for (const LabelRect& t : occupied_)
      if (overlaps(grown, t)) return false;
    return true;
  }

  // How much a spot hides other targets (labels may sit on boxes, but preferably not).
  double covers(const LabelRect& r, size_t self) const {
    double a = 0;
    for (size_t k = 0; k < requests_.size(); ++k)
      if (k != self) a += overlap_area(r, requests_[k].target);
    return a;
  }

  // An exclusive label's spot must keep clear of the other exclusive targets (and its leader cross none).
  // Nor does it cover another target that is not on its own (a label over another rock reads as that
  // rock's; over the GT box its own prediction overlaps, it still names the same rock).
  // LabelRequest::nearest_own: beside its target, clearly nearer it than any other of its group.
  bool unambiguous(const LabelRect& box, size_t self, bool leader) const {
    if (!requests_[self].exclusive) return true;
    const LabelRect& own = requests_[self].target;
    const double clearance = leader || !requests_[self].nearest_own
                                 ? o_.exclusive_clearance
                                 : distance(box, own) + std::max(o_.exclusive_clearance, 0.5 * requests_[self].height);
    for (size_t k = 0; k < requests_.size(); ++k) {
      if (k == self) continue;
      const LabelRect& other = requests_[k].target;
      if (requests_[k].exclusive && requests_[k].group == requests_[self].group
              ? distance(box, other) < clearance
              : overlaps(box, other) && !overlaps(other, own))
        return false;
    }
    const double c = requests_[self].keep_off_clearance;
    for (const LabelRect& r : requests_[self].keep_off)
      if (overlaps(box, r) || distance(box, r) < c) return false;
    return true;
  }

  // An exclusive label's leader crosses no other exclusive target of its group and nothing it keeps off.
  bool leader_clear(double x0, double y0, double x1, double y1, size_t self) const {
    if (!requests_[self].exclusive) return true;
    for (size_t k = 0; k < requests_.size(); ++k) {
      if (k == self || !requests_[k].exclusive || requests_[k].group != requests_[self].group) continue;
      const LabelRect& q = requests_[k].target;
      const double c = o_.exclusive_clearance;
      if (segment_hits(x0, y0, x1, y1, {q.x0 - c, q.y0 - c, q.x1 + c, q.y1 + c})) return false;
    }
    const double c = requests_[self].keep_off_clearance;
    for (const LabelRect& q : requests_[self].keep_off)
      if (segment_hits(x0, y0, x1, y1, {q.x0 - c, q.y0 - c, q.x1 + c, q.y1 + c})) return false;
    return true;
  }

  const std::vector<LabelRequest>& requests_;
  const LabelPlacementOptions& o_;
  std::vector<LabelRect> occupied_;  // inflated by the gap when compared
};

}  // namespace

LabelPlacement place_labels(const std::vector<LabelRequest>& requests, const LabelPlacementOptions& o) {
  o.check();
  LabelPlacement out;
  out.labels.resize(requests.size());
  LabelPlacer placer(requests, o);
  for (size_t i = 0; i < requests.size(); ++i) {
    PlacedLabel& placed = out.labels[i];
    if (placer.place_beside(i, &placed)) continue;
    if (placer.place_with_leader(i, &placed)) {
      ++out.with_leader;
      continue;
    }
    ++out.left_out;
    out.left_out_exclusive += requests[i].exclusive;
  }
  return out;
}

}  // namespace ipd
