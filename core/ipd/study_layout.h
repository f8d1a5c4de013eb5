// What is wrong when a study's layout leaves a number without its scenes or rocks: two domains that share no
// scene (or share less than half of them), labels kept only in sub-folders of labels/, a prediction set nested
// one level too deep, and ground truth without a box of the chosen class. Each is its own message saying where
// the files are, instead of a table of "no predictions" cells or a number computed from what was left.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/ipd/ipd.h"

namespace ipd {

struct LayoutProblem {
  std::string message;
  // The problem took more than half of a number's scenes or rocks away: a command printing numbers stops
  // (exit 1) unless leniency is asked for (--skip-bad-lines), since what it would print is not the study's.
  bool removes_most = false;
};

// The layout problems of the domain pairs `pairs` (the table's columns) for `models`, in domain, pair, then
// model order. Folders are looked at without following links (contained_file.h).
std::vector<LayoutProblem> layout_problems(const StudyLabels& labels,
                                           const std::vector<std::pair<std::string, std::string>>& pairs,
                                           const std::vector<ModelInfo>& models);

// Two stems' difference when one is the other with a prefix or suffix added ("the prefix '1a2b3c4d-'"); "" when
// they differ otherwise.
std::string name_difference(const std::string& a, const std::string& b);

}  // namespace ipd
