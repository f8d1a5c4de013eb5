#include "core/study/unused_hand_files.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "core/util/atomic_file.h"

namespace fs = std::filesystem;

namespace ipd {

namespace {

// A folder's entries, sorted (messages in a stable order); none when it is missing or a link, and a file in its
// place is said (it holds no hand pairs, so none are read).
std::vector<fs::directory_entry> entries(const fs::path& dir, const char* holds, std::vector<Problem>* out) {
  std::error_code ec;
  std::vector<fs::directory_entry> list;
  const fs::file_status st = fs::symlink_status(dir, ec);
  if (fs::exists(st) && !fs::is_symlink(st) && !fs::is_directory(st))
    out->push_back(
        {dir.string(), 0, "", "", "", fmt::format("is a file, expected the folder of {}: none are read", holds)});
  if (fs::is_symlink(st) || !fs::is_directory(st)) return list;
  for (fs::directory_iterator it(dir, ec); !ec && it != fs::directory_iterator(); it.increment(ec)) list.push_back(*it);
  if (ec) out->push_back({dir.string(), 0, "", "", "", "cannot be listed: " + ec.message()});
  std::sort(list.begin(), list.end());
  return list;
}

// "A__B" -> the two domains when both are the study's (and differ); otherwise the reason it is not used.
std::string domain_pair_problem(const Study& s, const std::string& name, const Domain** a, const Domain** b) {
  const size_t cut = name.find("__");
  if (cut == std::string::npos) return "is not named <A>__<B> after two domains";
  *a = s.domain(name.substr(0, cut));
  *b = s.domain(name.substr(cut + 2));
  if (*a && *b && *a != *b) return "";
  return fmt::format("names no domain pair of this study (domains: {})", s.domain_names());
}

void check_pairs_folder(const Study& s, const fs::directory_entry& e, std::vector<Problem>* out) {
  std::error_code ec;
  if (e.is_symlink(ec) || !e.is_directory(ec)) return;  // reading says what a link or a file there is
  const Domain *a = nullptr, *b = nullptr;
  if (const std::string why = domain_pair_problem(s, e.path().filename().string(), &a, &b); !why.empty()) {
    out->push_back({e.path().string(), 0, "", "", "", why + ": its hand pairs are not used"});
    return;
  }
  for (const auto& f : entries(e.path(), "hand pairs", out)) {
    const std::string file = f.path().filename().string();
    if (f.path().extension() != ".json" || is_stale_temp_name(file)) continue;
    const std::string stem = f.path().stem().string();
    if (std::binary_search(a->stems.begin(), a->stems.end(), stem) &&
        std::binary_search(b->stems.begin(), b->stems.end(), stem))
      continue;
    out->push_back(
        {f.path().string(), 0, a->name, b->name, "",
         fmt::format("no scene '{}' in both '{}' and '{}': its hand pairs are not used", stem, a->name, b->name)});
  }
}

}  // namespace

std::vector<Problem> unused_hand_files(const Study& study) {
  std::vector<Problem> out;
  for (const auto& e : entries(fs::path(study.root) / "pairs", "hand pairs", &out)) check_pairs_folder(study, e, &out);
  for (const auto& e : entries(fs::path(study.root) / "review", "review marks", &out)) {
    std::error_code ec;
    if (e.path().extension() != ".json" || e.is_symlink(ec) || e.is_directory(ec)) continue;
    const Domain *a = nullptr, *b = nullptr;
    if (const std::string why = domain_pair_problem(study, e.path().stem().string(), &a, &b); !why.empty())
      out.push_back({e.path().string(), 0, "", "", "", why + ": its review marks are not used"});
  }
  return out;
}

}  // namespace ipd
