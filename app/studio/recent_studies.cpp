#include "app/studio/recent_studies.h"

#include <algorithm>

#include "core/util/contained_file.h"

namespace ipd::studio {

namespace {
constexpr size_t kMaxRecentBytes = size_t{1} << 20;  // ten paths; anything larger is not ours
}

std::vector<std::string> read_recent_studies(const std::string& cache_root) {
  std::vector<std::string> out;
  if (cache_root.empty()) return out;
  std::optional<std::string> text;
  try {
    text = read_file_beneath(cache_root, "recent.txt", kMaxRecentBytes);
  } catch (const IoError&) {
    return out;  // a convenience: an unreadable list is an empty one
  }
  if (!text) return out;
  size_t pos = 0;
  while (pos < text->size() && out.size() < kRecentStudies) {
    const size_t eol = std::min(text->find('\n', pos), text->size());
    if (eol > pos) out.push_back(text->substr(pos, eol - pos));
    pos = eol + 1;
  }
  return out;
}

std::vector<std::string> with_recent_study(std::vector<std::string> list, const std::string& opened) {
  list.erase(std::remove(list.begin(), list.end(), opened), list.end());
  list.insert(list.begin(), opened);
  if (list.size() > kRecentStudies) list.resize(kRecentStudies);
  return list;
}

std::string save_recent_studies(const std::string& cache_root, const std::vector<std::string>& list,
                                const std::string& cache_problem) {
  const std::string failed = "the recent-studies list was not saved: ";
  if (cache_root.empty()) return failed + (cache_problem.empty() ? "no user cache" : cache_problem);
  std::string text;
  for (const auto& x : list) text += x + "\n";
  try {
    write_file_beneath(cache_root, "recent.txt", text);
    return "";
  } catch (const std::exception& e) {
    return failed + e.what();
  }
}

}  // namespace ipd::studio
