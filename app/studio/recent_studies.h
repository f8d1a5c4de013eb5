// The studies ipd-studio opened last, kept in the user cache (recent.txt, one path a line, the newest first):
// a convenience, never an edit. A list that can't be written is said as what it is, and no save of the study
// counts it as a lost edit.
#pragma once

#include <string>
#include <vector>

namespace ipd::studio {

inline constexpr size_t kRecentStudies = 10;

// The list in `cache_root` (usable_user_cache_root()); empty when there is none or no cache.
std::vector<std::string> read_recent_studies(const std::string& cache_root);

// `opened` put first in `list` (once; at most kRecentStudies kept).
std::vector<std::string> with_recent_study(std::vector<std::string> list, const std::string& opened);

// Writes the list into `cache_root` (atomically, never through a link there); "" when written, else
// "the recent-studies list was not saved: WHY" (`cache_problem` when there is no usable cache).
std::string save_recent_studies(const std::string& cache_root, const std::vector<std::string>& list,
                                const std::string& cache_problem = "");

}  // namespace ipd::studio
