#include "ui/gui/rock_numbers.h"

#include <cstddef>

namespace ipd::ui {

LabelPlacement place_rock_numbers(const std::vector<RockNumberTag>& tags, const LabelRect& pane) {
  std::vector<LabelRequest> requests;
  requests.reserve(tags.size());
  for (const RockNumberTag& t : tags) requests.push_back({t.rock, t.width, t.height});
  LabelPlacementOptions o;
  o.bounds = pane;
  o.gap = 1;         // one pixel between a number and its box, and between numbers
  o.max_leader = 3;  // a leader longer than three lines of text no longer reads as pointing at its rock
  return place_labels(requests, o);
}

namespace {
// Within `margin` of each other: only such GT boxes can be where a label of the prediction's would go.
bool near(const LabelRect& a, const LabelRect& b, double margin) {
  return a.x0 < b.x1 + margin && b.x0 < a.x1 + margin && a.y0 < b.y1 + margin && b.y0 < a.y1 + margin;
}
}  // namespace

LabelPlacement place_confidences(const std::vector<ConfidenceTag>& tags, const std::vector<LabelRect>& gt,
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

}  // namespace ipd::ui
