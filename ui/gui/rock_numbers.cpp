#include "ui/gui/rock_numbers.h"

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

}  // namespace ipd::ui
