// Review marks of one domain pair: which scenes someone has looked at ("reviewed") and which pairs were
// judged correct although the audit finds them suspect ("checked"; stereo parallax is the typical case).
// They let an audit of thousands of scenes be split over days or between people, and a checked pair stops
// counting as suspect. Kept beside the pairs, in STUDY/review/<A>__<B>.json (A, B in the domain pair's order):
//
//   {"reviewed": ["scene_0001", "scene_0004"],
//    "checked": [{"scene": "scene_0002", "rock_a": [0.41, 0.52, 0.05, 0.04], "rock_b": [0.43, 0.52, 0.05, 0.04]}]}
//
// A checked pair is stored by its two rocks' boxes (cx, cy, w, h, as fixed pairs store them: rows are not
// stable when a label file is re-exported). When read, a check whose boxes are no longer a current pair of
// its scene, and a mark of a scene the domain pair does not have, are dropped with a problem listed.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry/geometry.h"
#include "core/registration/registration.h"
#include "core/study/problem.h"

namespace ipd {

struct ReviewState {
  std::vector<char> reviewed;      // per scene of the domain pair (the Session's scene order)
  std::vector<RockPairs> checked;  // per scene: (index in A, index in B) of pairs judged correct, sorted
  int reviewed_scenes = 0;

  explicit ReviewState(size_t scenes = 0) : reviewed(scenes, 0), checked(scenes) {}
  int checked_pairs() const;  // over every scene
  bool empty() const;         // nothing reviewed, nothing checked: no file is kept
  bool is_checked(int scene, int a, int b) const;
  // Toggles, returning the new state's value.
  bool toggle_reviewed(int scene);
  bool toggle_checked(int scene, int a, int b);
};

// What load_review needs of one domain pair's scenes (indices of its scene list).
struct ReviewScenes {
  std::vector<std::string> stems;  // sorted, as Session keeps them
  std::function<const std::vector<Box>&(int scene, bool side_a)> gt;
  std::function<const RockPairs&(int scene)> pairs;  // the scene's current (A, B) pairs
};

// "review/<a>__<b>.json"
std::string review_relative_path(const std::string& a, const std::string& b);

struct ReviewRead {
  ReviewState state;
  std::vector<Problem> problems;    // marks dropped: a scene not in the domain pair, a check not a current pair
  std::optional<std::string> text;  // the file as read (nullopt: none), for its DiskVersion
};

// Reads STUDY/review/<a>__<b>.json (at most kMaxPairsFileBytes, no link followed) against the scenes now.
// Throws StudyError naming the file and what was expected for bad JSON, duplicate keys, unknown keys, or
// values of the wrong kind.
ReviewRead load_review(const std::string& study_root, const std::string& a, const std::string& b,
                       const ReviewScenes& scenes);

// The file's text for `state`: reviewed scenes by stem, and every check that is a current pair of its
// scene, by its rocks' boxes.
std::string review_json(const ReviewState& state, const ReviewScenes& scenes);

}  // namespace ipd
