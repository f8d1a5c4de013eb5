// The counted rock pairs of the current cell (domain pair and model) as points, for the studio's linked rock
// view (a scatter of any two of their values) and its paired-rock gallery (the worst |diff| pairs first), and
// for `ipd figure gallery`. Pure functions of an immutable Session: no drawing, no file I/O.
#pragma once

#include <string>
#include <vector>

#include "core/session/session.h"

namespace ipd {

// One counted pair, in the view's orientation (left = A unless the view is swapped), as the cell counts it.
struct RockPairPoint {
  int scene = -1;                // index into Session::scenes()
  int rock_a = -1, rock_b = -1;  // left and right rock indices
  double perf_a = 0, perf_b = 0, abs_diff = 0;
  // The left rock's area in pixels (the size breakdown's rule: the domain's picture size, else the
  // normalised area x 10^6) and its box centre in normalised image coordinates.
  double size = 0, x = 0, y = 0;
  // Confidence of each rock's best-IoU prediction; NaN when no prediction overlaps it.
  double conf_a = 0, conf_b = 0;
};

// Every counted pair of the session's current cell, by scene then in counting order. `scenes` (optional):
// only those scene indices (e.g. the filtered scene list); empty: every scene. A model without predictions
// for a domain counts nothing: empty.
std::vector<RockPairPoint> rock_pair_points(const Session& session, const std::vector<int>& scenes = {});

// The pairs of one scene list as the studio's Rock pairs window shows them (gathered off the UI thread), with
// the cell they belong to: scene indices stay valid while the domain pair, its order and the model do.
struct RockPointSet {
  std::vector<int> scenes;  // the scene indices asked for, ascending
  std::vector<RockPairPoint> points;
  int pair = -1;
  bool swapped = false;
  std::string model;
};

// What a scatter axis plots.
enum class PairAxis { kPerfA, kPerfB, kAbsDiff, kSize, kX, kY, kConfA, kConfB };
double axis_value(const RockPairPoint& p, PairAxis axis);
const char* axis_name(PairAxis axis);  // "perf A", "perf B", "|diff|", "size (px²)", "x", "y", "conf A", "conf B"

// The axis names of scripts (ipd-studio --replay): perf-a, perf-b, diff, size, x, y, conf-a, conf-b.
bool parse_pair_axis(const std::string& word, PairAxis* axis);
inline constexpr const char* kPairAxisWords = "perf-a, perf-b, diff, size, x, y, conf-a or conf-b";

// Indices of `points` in the gallery's order: largest |diff| first; ties by scene, then left rock, then right
// rock, so the order never depends on how the points were gathered.
std::vector<int> gallery_order(const std::vector<RockPairPoint>& points);
// The gallery's sort keys, each largest first; ties keep gallery_order (so |diff| breaks no ties).
enum class GallerySort { kDiff, kPerfA, kPerfB, kSize };
// "diff", "perf-a", "perf-b", "size": the words of `ipd figure gallery --sort` and of scripts
// (ipd-studio --replay `gallery sort WORD`).
bool parse_gallery_sort(const std::string& word, GallerySort* sort);
inline constexpr const char* kGallerySortWords = "diff, perf-a, perf-b or size";
inline constexpr GallerySort kGallerySorts[] = {GallerySort::kDiff, GallerySort::kPerfA, GallerySort::kPerfB,
                                                GallerySort::kSize};
const char* gallery_sort_name(GallerySort sort);  // "|diff|", "perf A", "perf B", "size"
// As a reader sees it, the domains named: "|diff|", "perf real", "perf synthetic", "size".
std::string gallery_sort_label(GallerySort sort, const std::string& a, const std::string& b);
std::vector<int> gallery_sorted(const std::vector<RockPairPoint>& points, GallerySort sort);

// The counted pairs of one cross-table cell, in the cell's orientation (A left), for a gallery without a
// Session (`ipd figure gallery`): `scene` is the index into cell.per_scene, the size and confidences follow
// rock_pair_points' rules. `labels` must be the ones the table was computed from (threshold applied).
std::vector<RockPairPoint> cell_pair_points(const StudyLabels& labels, const TableCell& cell);

// A pair's identity: its scene and its two rocks, in the view's orientation. It holds when the points are gathered
// again or plotted on other axes, so a selection keeps its pairs highlighted through both.
struct RockPairKey {
  int scene = -1, rock_a = -1, rock_b = -1;
  bool operator<(const RockPairKey& o) const;
  bool operator==(const RockPairKey& o) const;
};
RockPairKey key_of(const RockPairPoint& p);

// A drag-box selection on a scatter of (x_axis, y_axis): the points inside the box (corners in either order,
// edges included; a NaN value is never inside) and the scenes they are in.
struct PairSelection {
  std::vector<int> points;         // indices into the points, ascending
  std::vector<int> scenes;         // scene indices, ascending, each once
  std::vector<RockPairKey> pairs;  // the selected pairs, ascending
  // The scene list's filter chip: "selection: 37 pairs in 12 scenes".
  std::string label() const;
};
PairSelection select_in_box(const std::vector<RockPairPoint>& points, PairAxis x_axis, PairAxis y_axis, double x0,
                            double y0, double x1, double y1);
// Which of `points` are among `pairs` (ascending, as PairSelection keeps them): 1 for each that is.
std::vector<char> marked_pairs(const std::vector<RockPairPoint>& points, const std::vector<RockPairKey>& pairs);

}  // namespace ipd
