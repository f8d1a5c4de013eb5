#include "core/study/file_sets.h"

#include <fmt/format.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>

#include "core/study/study.h"
#include "core/util/contained_file.h"
#include "core/util/number_text.h"

namespace fs = std::filesystem;

namespace ipd {

StagedFolder::StagedFolder(const std::string& target) {
  const fs::path t = fs::absolute(target).lexically_normal();
  const fs::path clean = t.has_filename() ? t : t.parent_path();
  parent_ = clean.parent_path().string();
  name_ = clean.filename().string();
  std::error_code ec;
  if (fs::is_symlink(clean, ec))
    throw StudyError(clean.string() + ": is a symbolic link; the import replaces a folder, never through a link");
  fs::create_directories(parent_, ec);  // the study folder the user named, made when it is new
  if (ec) throw StudyError(fmt::format("{}: cannot create the folder: {}", parent_, ec.message()));
  const std::string base = "." + name_.substr(0, 200) + ".import-" + std::to_string(::getpid()) + "-";
  for (unsigned n = 0;; ++n) {
    temp_ = base + std::to_string(n);
    try {
      make_folder_beneath(parent_, temp_);
      return;
    } catch (const IoError&) {
      if (n >= 100) throw;  // a stale one of that name: the next number
    }
  }
}

StagedFolder::~StagedFolder() {
  try {
    remove_tree_beneath(parent_, temp_);
  } catch (const IoError&) {
  }
}

bool StagedFolder::target_exists() const {
  std::error_code ec;
  return fs::exists(fs::symlink_status(fs::path(parent_) / name_, ec));
}

void StagedFolder::commit() {
  sync_file_system_beneath(parent_, temp_);  // its files were written without a sync each (write_new_file_beneath)
  std::error_code ec;
  const fs::path target = fs::path(parent_) / name_;
  if (!target_exists()) {
    rename_beneath(parent_, temp_, name_);
  } else {
    if (fs::is_symlink(target, ec))
      throw StudyError(target.string() + ": is a symbolic link; the import replaces a folder, never through a link");
    exchange_beneath(parent_, temp_, name_);  // temp_ now names what was there, removed by the destructor
  }
}

void check_domain_folder(const std::string& out_dir, bool replace, const std::string& command) {
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(out_dir, ec);
  if (!fs::exists(st)) return;
  if (fs::is_symlink(st))
    throw StudyError(out_dir + ": is a symbolic link; the import replaces a folder, never through a link");
  if (!fs::is_directory(fs::status(out_dir, ec)))
    throw StudyError(out_dir + ": is not a folder; " + command + " fills a domain folder");
  if (fs::is_empty(out_dir, ec) && !ec) return;
  if (replace) return;
  throw StudyError(out_dir +
                   ": already exists and is not an empty directory; its labels, pictures and predictions would mix "
                   "with the imported ones, so nothing is written (--replace replaces them whole)");
}

std::vector<std::string> label_files_in(const std::string& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(dir, ec))) return out;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (e.is_directory(ec) && !e.is_symlink(ec)) continue;
    if (e.path().extension() == ".txt") out.push_back(e.path().filename().string());
  }
  if (ec) throw StudyError(fmt::format("{}: cannot read the folder: {}", dir, ec.message()));
  std::sort(out.begin(), out.end());
  return out;
}

int remove_files_not_kept(const std::string& root, const std::string& relative, const std::set<std::string>& keep,
                          const std::string& suffix) {
  const fs::path dir = fs::path(root) / relative;
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(dir, ec);
  if (!fs::exists(st)) return 0;
  // A linked folder on the way is refused, never listed through.
  check_beneath(root, (fs::path(relative) / "x").string());
  std::vector<std::string> stale;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if ((e.is_directory(ec) && !e.is_symlink(ec)) || keep.count(name)) continue;
    const bool has_suffix =
        name.size() >= suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
    if (!has_suffix) continue;
    stale.push_back(name);
  }
  if (ec) throw StudyError(fmt::format("{}: cannot read the folder: {}", dir.string(), ec.message()));
  for (const std::string& name : stale) remove_file_beneath(root, (fs::path(relative) / name).string());
  return static_cast<int>(stale.size());
}

std::vector<std::string> read_class_names(const std::string& classes_txt) {
  const fs::path p(classes_txt);
  const auto text = read_file_beneath(p.parent_path().string(), p.filename().string(), 1 << 20);
  std::vector<std::string> names;
  if (!text) return names;
  size_t at = 0;
  while (at < text->size()) {
    size_t end = text->find('\n', at);
    if (end == std::string::npos) end = text->size();
    std::string line = text->substr(at, end - at);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    names.push_back(line);
    at = end + 1;
  }
  return names;
}

std::string class_name_conflict(const std::string& domain_dir, const std::vector<std::string>& classes) {
  const fs::path domain = fs::path(domain_dir).lexically_normal();
  const fs::path mine = domain.filename().empty() ? domain.parent_path() : domain;
  const fs::path study = mine.parent_path().empty() ? fs::path(".") : mine.parent_path();
  std::error_code ec;
  std::vector<fs::path> siblings;
  for (const auto& e : fs::directory_iterator(study, ec))
    if (e.path().filename() != mine.filename() && e.is_directory(ec) && !e.is_symlink(ec)) siblings.push_back(e.path());
  std::sort(siblings.begin(), siblings.end());  // the same answer whatever order the folder lists them in
  for (const fs::path& sibling : siblings) {
    const std::string file = (sibling / "labels" / "classes.txt").string();
    if (fs::symlink_status(sibling / "labels", ec).type() != fs::file_type::directory) continue;
    const std::vector<std::string> theirs = read_class_names(file);
    for (size_t k = 0; k < std::min(theirs.size(), classes.size()); ++k)
      if (!classes[k].empty() && !theirs[k].empty() && classes[k] != theirs[k])
        return fmt::format("class {} is \"{}\" here but \"{}\" in {}", k, quoted_for_message(classes[k]),
                           quoted_for_message(theirs[k]), file);
  }
  return {};
}

}  // namespace ipd
