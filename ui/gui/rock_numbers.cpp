#include "ui/gui/rock_numbers.h"

#include <algorithm>
#include <cstddef>
#include <deque>
#include <tuple>

namespace ipd::ui {

namespace {
bool same(const LabelRect& a, const LabelRect& b) {
  return std::tie(a.x0, a.y0, a.x1, a.y1) == std::tie(b.x0, b.y0, b.x1, b.y1);
}
bool same(const std::vector<LabelRect>& a, const std::vector<LabelRect>& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](auto& x, auto& y) { return same(x, y); });
}

// The panes ask for the same placement every frame while nothing moves (two panes, numbers and confidences:
// a few distinct requests). Placing thousands of labels each frame cost a dense scene most of its frame, so
// the last few answers are kept and an identical request (compared exactly, O(labels)) gets its answer back.
template <class Key>
class RecentPlacements {
 public:
  template <class Place>
  const LabelPlacement& get(Key key, Place place) {
    for (const auto& [k, v] : entries_)
      if (k == key) return v;
    if (entries_.size() == kKept) entries_.pop_back();
    entries_.emplace_front(std::move(key), place());
    return entries_.front().second;
  }

 private:
  static constexpr std::size_t kKept = 4;
  std::deque<std::pair<Key, LabelPlacement>> entries_;
};

struct NumbersKey {
  std::vector<RockNumberTag> tags;
  LabelRect pane;
  bool operator==(const NumbersKey& o) const {
    return same(pane, o.pane) && tags.size() == o.tags.size() &&
           std::equal(tags.begin(), tags.end(), o.tags.begin(), [](const RockNumberTag& x, const RockNumberTag& y) {
             return same(x.rock, y.rock) && x.width == y.width && x.height == y.height;
           });
  }
};

struct ConfidencesKey {
  std::vector<ConfidenceTag> tags;
  std::vector<LabelRect> gt, taken;
  LabelRect pane;
  bool operator==(const ConfidencesKey& o) const {
    return same(pane, o.pane) && same(gt, o.gt) && same(taken, o.taken) && tags.size() == o.tags.size() &&
           std::equal(tags.begin(), tags.end(), o.tags.begin(), [](const ConfidenceTag& x, const ConfidenceTag& y) {
             return same(x.prediction, y.prediction) && x.width == y.width && x.height == y.height &&
                    x.matched_gt == y.matched_gt;
           });
  }
};

LabelPlacement place_rock_numbers_now(const std::vector<RockNumberTag>& tags, const LabelRect& pane);
LabelPlacement place_confidences_now(const std::vector<ConfidenceTag>& tags, const std::vector<LabelRect>& gt,
                                     const std::vector<LabelRect>& taken, const LabelRect& pane);
}  // namespace

LabelPlacement place_rock_numbers(const std::vector<RockNumberTag>& tags, const LabelRect& pane) {
  thread_local RecentPlacements<NumbersKey> recent;
  return recent.get(NumbersKey{tags, pane}, [&] { return place_rock_numbers_now(tags, pane); });
}

LabelPlacement place_confidences(const std::vector<ConfidenceTag>& tags, const std::vector<LabelRect>& gt,
                                 const std::vector<LabelRect>& taken, const LabelRect& pane) {
  thread_local RecentPlacements<ConfidencesKey> recent;
  return recent.get(ConfidencesKey{tags, gt, taken, pane},
                    [&] { return place_confidences_now(tags, gt, taken, pane); });
}

namespace {
LabelPlacement place_rock_numbers_now(const std::vector<RockNumberTag>& tags, const LabelRect& pane) {
  std::vector<LabelRequest> requests;
  requests.reserve(tags.size());
  for (const RockNumberTag& t : tags) requests.push_back({t.rock, t.width, t.height});
  LabelPlacementOptions o;
  o.bounds = pane;
  o.gap = 1;         // one pixel between a number and its box, and between numbers
  o.max_leader = 3;  // a leader longer than three lines of text no longer reads as pointing at its rock
  return place_labels(requests, o);
}

// Within `margin` of each other: only such GT boxes can be where a label of the prediction's would go.
bool near(const LabelRect& a, const LabelRect& b, double margin) {
  return a.x0 < b.x1 + margin && b.x0 < a.x1 + margin && a.y0 < b.y1 + margin && b.y0 < a.y1 + margin;
}

LabelPlacement place_confidences_now(const std::vector<ConfidenceTag>& tags, const std::vector<LabelRect>& gt,
                                     const std::vector<LabelRect>& taken, const LabelRect& pane) {
  std::vector<LabelRequest> requests;
  requests.reserve(tags.size());
  for (const ConfidenceTag& t : tags) {
    LabelRequest r{t.prediction, t.width, t.height, true, 1};
    for (std::size_t j = 0; j < gt.size(); ++j)
      if (static_cast<int>(j) != t.matched_gt && near(gt[j], t.prediction, t.width + 3 * t.height))
        r.keep_off.push_back(gt[j]);
    requests.push_back(std::move(r));
  }
  LabelPlacementOptions o;
  o.bounds = pane;
  o.taken = taken;
  o.gap = 1;
  o.max_leader = 2;  // a confidence far from its box reads as another's
  return place_labels(requests, o);
}

}  // namespace

}  // namespace ipd::ui
