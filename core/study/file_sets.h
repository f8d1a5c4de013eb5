// Sets of files a command writes whole: the domain `ipd import coco` fills, the prediction folder `ipd detect`
// fills. Written over an earlier set they mixed with it: an import replaced the labels and pictures of its own
// scenes and left the others, a second detector run left the first run's files of pictures it did not see, and
// the next table counted both. So a folder that already holds such a set is refused unless the user asks to
// replace it, and replacing removes what the new set did not write (`ipd demo` likewise refuses a non-empty
// folder).
#pragma once

#include <set>
#include <string>
#include <vector>

namespace ipd {

// A folder written whole beside its target (`.<name>.import-<pid>-<n>` in the same parent) and renamed in, so
// the target is never written into and a link in it (`labels -> /x`) never written through: ipd import fills
// it through contained_file.h's writers (parent() as the root, inside() the names; write_new_file_beneath needs
// no sync a file: commit() syncs the file system once before the swap), then commit() swaps it
// with the target in one step (renameat2 RENAME_EXCHANGE; a plain rename when there is none) and removes
// what was there through descriptors. Not committed, it is removed when it goes out of scope.
class StagedFolder {
 public:
  // Refuses (StudyError) a target that is a symbolic link: the import replaces a folder, never through one.
  explicit StagedFolder(const std::string& target);
  ~StagedFolder();
  StagedFolder(const StagedFolder&) = delete;
  StagedFolder& operator=(const StagedFolder&) = delete;
  const std::string& parent() const { return parent_; }
  // `inside` (a path below the new folder, "labels/s1.txt") as written beneath parent(); and the target's.
  std::string inside(const std::string& rel) const { return temp_ + "/" + rel; }
  std::string target_inside(const std::string& rel) const { return name_ + "/" + rel; }
  const std::string& target_name() const { return name_; }
  bool target_exists() const;
  void commit();

 private:
  std::string parent_, name_, temp_;
};

// A domain folder an import fills takes a new set only when the user asked to replace it: a folder that holds
// files is refused (StudyError, nothing written) unless `replace`; a link or a file there always is. `command`
// names the import in the message ("ipd import coco").
void check_domain_folder(const std::string& out_dir, bool replace, const std::string& command);

// The label files (`*.txt`, regular files or links) directly in `dir`, sorted; none when `dir` is missing.
// Throws StudyError when `dir` exists but can't be listed.
std::vector<std::string> label_files_in(const std::string& dir);

// Removes the entries of root/relative (a folder) that are not folders, are not named in `keep` and, when
// `suffix` is not empty, end with it; durably, never through a link (remove_file_beneath). Returns how many.
int remove_files_not_kept(const std::string& root, const std::string& relative, const std::set<std::string>& keep,
                          const std::string& suffix);

// The class names a domain's labels/classes.txt lists (one a line, "" for an unused number); none when the
// file is missing. Throws for a link or an unreadable file, as every study file.
std::vector<std::string> read_class_names(const std::string& classes_txt);

// The first class number `classes` names differently from a sibling domain of `domain_dir` (another folder of
// its study with labels/classes.txt), as "class K is \"A\" here but \"B\" in FILE"; "" when every number both
// name is the same category.
std::string class_name_conflict(const std::string& domain_dir, const std::vector<std::string>& classes);

}  // namespace ipd
