// Hand-fixed rock pairs: STUDY/pairs/<A>__<B>/<stem>.json, replacing registration for one image pair.
//
//   {"pairs": [[0, 2], [1, 0]], "excluded_a": [3],
//    "rocks_a": [[0, 0.2, 0.2, 0.1, 0.1], [1, ...], [3, ...]], "rocks_b": [[0, ...], [2, ...]]}
//
// Indices are rock rows of the label files (the first index belongs to the first domain of the folder's
// name). Each paired or excluded rock's box (cx, cy, w, h, the shortest decimals that read back to the
// values in its label file) is stored with its index, so the pairs stay on the same rocks when a label file
// is re-exported with its rows reordered: a rock no longer at its row is found again by its box (and a
// warning says so); a rock no longer in its label file makes the scene's hand pairs unusable. A box is the
// same rock when it agrees within kSameRockTolerance (same_rock_box), far below what a label can tell apart.
// Files without "rocks_a"/"rocks_b" (written before boxes were stored) are read by index and gain the
// boxes on their next save.
//
// "class": N (or "all") says which class's rocks the indices are of, in a study with more than one class: read
// with another class chosen, the file is another class's hand work, not this class's pairs (nor a problem), and
// ipd-studio refuses edits of that scene rather than overwrite it. A file without "class" holds for every class.
//
// Nothing below the study is followed through a symbolic link (contained_file.h).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry/geometry.h"
#include "core/registration/registration.h"
#include "core/study/problem.h"

namespace ipd {

struct Study;
struct StudyClasses;

// How far a box may move and still be the same rock, in each of cx, cy, w, h (fractions of the picture).
// Label files are written with 6 decimals (YOLO's own writer, `ipd demo`, most converters), so re-exporting
// one, rounding its numbers through float32 (7 significant digits) or a tool that rounds the last digit the
// other way moves a box by about 1e-6, which must not orphan the hand work stored by box. 1e-5 is ten units
// of that last decimal: 0.02 pixels across a 1936-pixel picture, while a box edge drawn by hand is placed
// to about a pixel, so two boxes this close are one rock, never two neighbours.
constexpr double kSameRockTolerance = 1e-5;
// True when `b` and (cx, cy, w, h) differ by at most kSameRockTolerance in every coordinate.
bool same_rock_box(const Box& b, double cx, double cy, double w, double h);

// Hand-fixed pairs for one image pair, oriented as (index in A, index in B).
struct FixedPairs {
  RockPairs pairs;
  std::vector<int> excluded_a, excluded_b;  // rocks left out of the IPD on purpose
};

// Something found while reading a pairs file, as plain data for the CLI's messages and the GUI's problem
// list: `file` is the pairs file, `line` 0 (the file as a whole).
struct PairsProblem {
  std::string file;
  int line = 0;
  std::string message;
  // The scene's hand pairs are not used (a stored rock is in neither label file row): registration counts
  // instead, and `ipd table` exits 1 unless --skip-bad-lines. False: a warning (rocks found again).
  bool unusable = false;
  std::string why_unusable;  // when unusable: what no longer matches ("a stored box is no longer in ...")
  std::string to_string() const { return file + ": " + message; }
};

// The problem of scene `stem`'s pairs file of the domain pair (a, b), for the study's problem list.
Problem pairs_file_problem(const PairsProblem& w, const std::string& a, const std::string& b, const std::string& stem);

// What a pairs file held when read: a content hash, so a save can tell whether someone else changed it
// since (present = false: there was no file).
struct DiskVersion {
  bool present = false;
  std::uint64_t hash = 0;
  bool operator==(const DiskVersion& o) const { return present == o.present && hash == o.hash; }
  bool operator!=(const DiskVersion& o) const { return !(*this == o); }
};
DiskVersion version_of(const std::optional<std::string>& contents);

// One scene's pairs files, as read.
struct FixedPairsRead {
  std::optional<FixedPairs> pairs;     // nullopt: no file, or unusable (see problems)
  std::vector<PairsProblem> problems;  // in file order: rocks found again, unusable, both name orders
  DiskVersion version_ab, version_ba;  // pairs/<a>__<b>/<stem>.json and pairs/<b>__<a>/<stem>.json
  // The file holds another class's hand pairs (kNoClassChosen: it doesn't): `pairs` is then empty.
  int other_class = -1;
  std::string other_class_file;
  bool unusable() const;
};

// Reads pairs/<A>__<B>/<stem>.json or pairs/<B>__<A>/<stem>.json (swapping indices), binding stored rocks
// to `gt_a`/`gt_b` by box. Throws StudyError naming the file for bad JSON, unknown keys, indices out of
// range (in files without boxes), a rock paired twice, a pair of two classes' rocks, a paired rock without a stored
// box, a symbolic link on the way, or an unreadable file. When both exist, A__B counts and a problem names B__A.
FixedPairsRead load_fixed_pairs(const Study& study, const std::string& a, const std::string& b, const std::string& stem,
                                const std::vector<Box>& gt_a, const std::vector<Box>& gt_b);

// load_fixed_pairs for callers without a problem list: unusable pairs are a StudyError, other problems go
// to `warnings` (as "FILE: message").
std::optional<FixedPairs> read_fixed_pairs(const Study& study, const std::string& a, const std::string& b,
                                           const std::string& stem, const std::vector<Box>& gt_a,
                                           const std::vector<Box>& gt_b, std::vector<std::string>* warnings = nullptr);

// A pair joins two rocks of one class: rocks of two classes are two different things, whatever their boxes (a
// class-blind study can show both). The message naming the first pair of `pairs` that joins two classes ("pairs
// real rock 3 (rock) with synth rock 5 (shadow): ..."), rocks numbered from 1 as the panes show them; nullopt
// when every pair is within a class.
std::optional<std::string> pair_across_classes(const FixedPairs& pairs, const std::vector<Box>& gt_a,
                                               const std::vector<Box>& gt_b, const std::string& a, const std::string& b,
                                               const StudyClasses& classes);

// The file's text, with each paired or excluded rock's box from `gt_a`/`gt_b`, and "class" when `cls` is set.
std::string fixed_pairs_json(const FixedPairs& pairs, const std::vector<Box>& gt_a, const std::vector<Box>& gt_b,
                             std::optional<int> cls);

// The file name of a scene's pairs below the study root: "pairs/<a>__<b>/<stem>.json".
std::string fixed_pairs_relative_path(const std::string& a, const std::string& b, const std::string& stem);

// Writes pairs/<A>__<B>/<stem>.json atomically, never through a symbolic link.
void write_fixed_pairs(const Study& study, const std::string& a, const std::string& b, const std::string& stem,
                       const FixedPairs& pairs, const std::vector<Box>& gt_a, const std::vector<Box>& gt_b);

}  // namespace ipd
