#include "app/studio/study_folder.h"

#include <cstdlib>
#include <filesystem>

namespace fs = std::filesystem;

namespace ipd::studio {

std::string expand_typed_path(const std::string& typed) {
  const size_t first = typed.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  std::string p = typed.substr(first, typed.find_last_not_of(" \t\r\n") - first + 1);
  if (p.size() >= 2 && (p.front() == '\'' || p.front() == '"') && p.back() == p.front()) p = p.substr(1, p.size() - 2);
  const char* home = std::getenv("HOME");
  if (home && *home && (p == "~" || p.rfind("~/", 0) == 0)) p = home + p.substr(1);
  return p;
}

bool looks_like_study(const std::string& dir) {
  std::error_code ec;
  if (fs::is_regular_file(fs::path(dir) / "study.yaml", ec)) return true;
  for (fs::directory_iterator d(dir, fs::directory_options::skip_permission_denied, ec);
       !ec && d != fs::directory_iterator(); d.increment(ec)) {
    std::error_code e2;
    if (d->is_directory(e2) && fs::is_directory(d->path() / "labels", e2)) return true;
  }
  return false;
}

std::string open_path_problem(const std::string& dir) {
  if (dir.empty()) return "type or paste the path of a study folder";
  std::error_code ec;
  const fs::file_status st = fs::status(dir, ec);
  if (!fs::exists(st)) return dir + ": no such folder";
  if (!fs::is_directory(st)) return dir + ": is a file, not a folder";
  if (!looks_like_study(dir)) return dir + ": not a study (no study.yaml or <domain>/labels/ in it)";
  return "";
}

}  // namespace ipd::studio
