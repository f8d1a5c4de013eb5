// Collision-avoiding placement of text labels (rock numbers, confidences, legends) for figures: each label
// tries positions around its target (above, below, inside corners, left, right), then a spot a little way
// off with a short leader line, and is left out (counted) only when nothing fits. An exclusive label also
// stays clear of the other exclusive targets, so it reads as its own target's. Pure and deterministic:
// labels are placed greedily in the order given (put the important ones first).
#pragma once

#include <string>
#include <vector>

namespace ipd {

struct LabelRect {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // y down
  double width() const { return x1 - x0; }
  double height() const { return y1 - y0; }
};
bool overlaps(const LabelRect& a, const LabelRect& b);  // interiors intersect

struct LabelRequest {
  LabelRect target;              // what the label names (a point is an empty rect)
  double width = 0, height = 0;  // the text's box
  // Among exclusive labels a reader must tell which target each names (e.g. confidences of overlapping
  // boxes of one colour): the label keeps `exclusive_clearance` from every other exclusive target, and a
  // leader crosses none; when no spot does, the label is left out (counted in left_out_exclusive).
  bool exclusive = false;
  // Exclusive labels only keep clear of the exclusive targets of their own group (rock numbers and
  // confidences are two groups: a number may sit beside a prediction box, not beside another rock).
  int group = 0;
  // Other things an exclusive label must not read as naming: its box keeps `keep_off_clearance` from each
  // (0: may touch, not overlap) and its leader crosses none (e.g. a confidence and every GT box but the one
  // its prediction matches; a registration number and every other marker).
  std::vector<LabelRect> keep_off = {};
  double keep_off_clearance = 0;
  // An exclusive label attached by nearness alone (beside its target, no leader) must also lie nearer its
  // own target than any other exclusive target of its group by max(exclusive_clearance, half its height):
  // a "15" a gap above box 15 and 2 pt below box 1 reads as either's (the pairs figure's rock numbers). A
  // leader draws the attachment, so a leader spot keeps the plain clearance.
  bool nearest_own = false;
};

enum class LabelPosition {
  kAbove,
  kBelow,
  kInsideTopLeft,
  kInsideTopRight,
  kInsideBottomLeft,
  kInsideBottomRight,
  kLeft,
  kRight,
  kLeader,
  kLeftOut
};

struct PlacedLabel {
  LabelPosition position = LabelPosition::kLeftOut;
  LabelRect box;                                                      // where the text goes (meaningless when left out)
  double leader_x0 = 0, leader_y0 = 0, leader_x1 = 0, leader_y1 = 0;  // kLeader: target edge -> label
  bool shown() const { return position != LabelPosition::kLeftOut; }
};

struct LabelPlacementOptions {
  LabelRect bounds;                // labels stay inside
  std::vector<LabelRect> taken;    // already occupied (titles, captions, legends)
  double gap = 1;                  // clearance between a label and its target and between labels
  double max_leader = 3;           // the farthest a leader goes, in label heights
  double exclusive_clearance = 1;  // see LabelRequest::exclusive (more than gap: nearer its own target)
  // Empty when usable (bounds non-empty, gap, max_leader and exclusive_clearance >= 0); otherwise the field
  // that is wrong and the accepted range, in one sentence.
  std::string validate() const;
  // Throws std::invalid_argument("label placement: " + validate()) when not usable.
  void check() const;
};

struct LabelPlacement {
  std::vector<PlacedLabel> labels;  // one per request, same order
  int left_out = 0;                 // every label left out, exclusive ones included
  int left_out_exclusive = 0;       // exclusive labels left out
  int with_leader = 0;
};

LabelPlacement place_labels(const std::vector<LabelRequest>& requests, const LabelPlacementOptions& options);

}  // namespace ipd
