// Review marks of one domain pair: which scenes someone has looked at ("reviewed") and which pairs were
// judged correct although the audit finds them suspect ("checked"; stereo parallax is the typical case).
// They let an audit of thousands of scenes be split over days or between people, and a checked pair stops
// counting as suspect. Kept beside the pairs, in STUDY/review/<A>__<B>.json (A, B in the domain pair's order):
//
//   {"reviewed": ["scene_0001", "scene_0004"],
//    "checked": [{"scene": "scene_0002", "rock_a": [0.41, 0.52, 0.05, 0.04], "rock_b": [0.43, 0.52, 0.05, 0.04]}]}
//
// A checked pair is stored by its two rocks' boxes (cx, cy, w, h, as fixed pairs store them: rows are not
// stable when a label file is re-exported). When read, a check whose boxes are not a current pair of its
// scene, and a mark of a scene the domain pair does not have, do not apply now: a problem says so, and they
// are kept as read and written back with the next save, so a temporary change (another registration
// method, a typo in a label file) never deletes the user's record; they apply again once read when their
// pair (or scene) is back.
//
// In a study where another class can be chosen, each mark names the class its rocks were shown under, as hand
// pairs do (hand_work_class.h): {"scene": "scene_0001", "class": 0} in "reviewed", "class": 0 in a check. Marks
// of another class than the one shown are that class's: kept as read and written back, neither applied nor
// reported. A mark without "class" holds for every class.
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry/geometry.h"
#include "core/registration/registration.h"
#include "core/study/problem.h"

namespace ipd {

struct Study;

// A check read from the file that does not apply now (its rocks are not a pair of its scene, or the domain
// pair has no such scene), kept as read.
struct KeptCheck {
  std::string scene;
  std::array<double, 4> rock_a, rock_b;  // cx, cy, w, h
  std::optional<int> cls;                // as read ("class"); none: every class
  bool other_class = false;              // of another class than the one shown: never applies here
};

// A review mark of a scene read from the file that does not apply now (no such scene, or another class's).
struct KeptReviewed {
  std::string scene;
  std::optional<int> cls;  // as read
};

struct ReviewState {
  std::vector<char> reviewed;      // per scene of the domain pair (the Session's scene order)
  std::vector<RockPairs> checked;  // per scene: (index in A, index in B) of pairs judged correct, sorted
  int reviewed_scenes = 0;
  // Marks of the file that do not apply now, written back as read (load_review's problems name them).
  std::vector<KeptReviewed> kept_reviewed;  // scenes the domain pair does not have now, other classes' marks
  std::vector<KeptCheck> kept_checks;

  explicit ReviewState(size_t scenes = 0) : reviewed(scenes, 0), checked(scenes) {}
  int checked_pairs() const;  // over every scene
  bool empty() const;         // nothing reviewed, nothing checked, nothing kept: no file is kept
  // The kept checks of scene `scene` (named `stem`) whose rocks are one of its (A, B) `pairs` now apply
  // again: they become checks of those pairs. False when none did.
  bool apply_kept_checks(int scene, const std::string& stem, const std::vector<Box>& gt_a, const std::vector<Box>& gt_b,
                         const RockPairs& pairs);
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
  int shown_class = -1;                              // study.config.rock_class (kNoClassChosen: none chosen)
  std::optional<int> written_class;                  // hand_work_class: the class marks made now are of
  // Takes shown_class and written_class from the study.
  void take_class_of(const Study& study);
};

// "review/<a>__<b>.json"
std::string review_relative_path(const std::string& a, const std::string& b);

struct ReviewRead {
  ReviewState state;
  std::vector<Problem> problems;    // marks kept that don't apply: a scene not in the domain pair, a check not a pair
  std::optional<std::string> text;  // the file as read (nullopt: none), for its DiskVersion
};

// Reads STUDY/review/<a>__<b>.json (at most kMaxPairsFileBytes, no link followed) against the scenes now.
// Throws StudyError naming the file and what was expected for bad JSON, duplicate keys, unknown keys, or
// values of the wrong kind.
ReviewRead load_review(const std::string& study_root, const std::string& a, const std::string& b,
                       const ReviewScenes& scenes);

// The file's text for `state`: reviewed scenes by stem, every check by its rocks' boxes (also one whose pair
// was edited away since: it applies again if the pair comes back), then the kept marks as they were read.
std::string review_json(const ReviewState& state, const ReviewScenes& scenes);

}  // namespace ipd
