// Files below a folder the user chose (a study), reached without ever following a symbolic link below it.
//
// A study is untrusted input: a link inside it (`pairs -> /x`, `pairs/B__A -> /victim`) must not make the
// tool write, delete or read outside it. Every folder on the way is opened with O_NOFOLLOW from the one
// above it, and the file is then written, removed or read relative to that open folder, so a link swapped
// in after a check is never followed either. The root itself may be a link: the user named it.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/util/atomic_file.h"

struct stat;

namespace ipd {

// Replaces root/relative with `contents` atomically (temp file, fsync, rename, fsync of the folder),
// creating missing folders. Refuses with IoError "PATH: is a symbolic link; ..." when a folder below root
// or the file itself is one. `hook` steps: "folder opened", "checked", "temp written", "renamed",
// "directory synced". `recheck`, when given, runs after the temp file is written and right before the
// rename with what the file holds now, read through the folder already opened (nullopt: missing): it throws to
// refuse the replacement (the temp file is removed, the file left as it is), so a check of what the file holds
// is made as late as it can be, not before a slow write. A link or other non-file found there is not read: it
// is replaced, never followed.
using Recheck = std::function<void(const std::optional<std::string>& now)>;
void write_file_beneath(const std::string& root, const std::string& relative, const std::string& contents,
                        const WriteStepHook& hook = {}, const Recheck& recheck = {});

// Where `path` lies below `root`: its path relative to root when it is below root (written as given, or below
// root's real path when root is itself a link), nullopt when it is elsewhere. Lexical: links below root are
// not resolved, which is the point (a link there must not say where a file goes).
std::optional<std::string> path_below(const std::string& root, const std::string& path);

// Writes `path` atomically, refusing (IoError, nothing written) a path that is one of the study's inputs
// (study_input_problem, core/util/study_inputs.h): below `root` (a study) as write_file_beneath writes, so a link the
// study holds
// (`figures -> /elsewhere`) is refused, never written through; anywhere else it is the user's own path
// (write_file_atomically: a link the user made there is resolved).
void write_output_file(const std::string& root, const std::string& path, const std::string& contents);

// Removes root/relative durably (fsync of its folder); false when it was not there. Refuses (IoError) a
// symbolic link, whether the file or a folder on the way. `hook` steps: "folder opened", "checked";
// `recheck` as write_file_beneath's, right before the removal.
bool remove_file_beneath(const std::string& root, const std::string& relative, const WriteStepHook& hook = {},
                         const Recheck& recheck = {});

// Checks that the folders of root/relative are real folders (or missing) and the file is not a link,
// without changing anything ("saving through it is refused"): a save checks every file it will write or
// remove before it changes the first one.
void check_beneath(const std::string& root, const std::string& relative);

// Removes the temp files of dead writers (remove_stale_temp_files_at) in the folder root/relative, opened
// beneath root without following a link (a folder that is one, or is swapped for one after a check, is never
// listed or deleted in). Returns how many were removed; 0 when the folder is missing, a link or unreadable.
// `hook` step: "folder opened" (tests swap the folder there).
int remove_stale_temp_files_beneath(const std::string& root, const std::string& relative,
                                    const WriteStepHook& hook = {});

// The entries of the folder root/relative (opened beneath root, listed with fdopendir, each examined with
// fstatat without following it), sorted by name; empty when it is missing. Throws IoError for a link on the
// way or at root/relative itself, as read_file_beneath.
struct FolderEntry {
  std::string name;
  bool folder = false;  // a real folder; a link to one is not
  bool operator==(const FolderEntry& o) const { return name == o.name && folder == o.folder; }
};
std::vector<FolderEntry> entries_beneath(const std::string& root, const std::string& relative);
// The names of the real folders among them.
std::vector<std::string> folders_beneath(const std::string& root, const std::string& relative);

// The folder root/relative, opened once beneath root without following a link (as entries_beneath opens it), for
// looking at many of its entries by name without resolving the path again for each: a 10,000-scene study's
// freshness check examines its label files this way, one fstatat each. Not open (fd() -1) when the folder is
// missing; throws IoError for a link on the way or at root/relative itself.
class OpenFolder {
 public:
  OpenFolder(const std::string& root, const std::string& relative);
  ~OpenFolder();
  OpenFolder(const OpenFolder&) = delete;
  OpenFolder& operator=(const OpenFolder&) = delete;
  int fd() const { return fd_; }
  // fstatat of the entry `name` without following it; false when it is missing or the folder is not open.
  bool stat_entry(const std::string& name, struct stat* st) const;
  // read_file_beneath(root, relative + "/" + name, max_bytes) through this folder's descriptor.
  std::optional<std::string> read(const std::string& name, size_t max_bytes = kMaxReadBytes) const;

 private:
  int fd_ = -1;
  std::string shown_;  // "ROOT/RELATIVE/", naming an entry in errors
};

// Creates the folder root/relative, which must not exist (its parents are created; none may be a link).
void make_folder_beneath(const std::string& root, const std::string& relative);
// Moves root/from to root/to (renameat between the two folders' descriptors; to's folders are created): the
// entry itself moves, a link as a link. Throws IoError naming both.
void rename_beneath(const std::string& root, const std::string& from, const std::string& to);
// Swaps root/a and root/b in one step (renameat2 RENAME_EXCHANGE): a reader sees one or the other, whole.
void exchange_beneath(const std::string& root, const std::string& a, const std::string& b);
// Removes root/relative and everything in it, through descriptors: a link inside is removed itself, its
// target never listed or touched. Nothing there: nothing done.
void remove_tree_beneath(const std::string& root, const std::string& relative);
// Writes root/relative, which must not exist (its folders are created; none may be a link), without a temp file
// or fsync: for a folder being filled that nobody reads until it is synced (sync_file_system_beneath) and renamed
// in whole (StagedFolder), where a sync per file cost 8 ms a file (16 s for 2,000 label files).
void write_new_file_beneath(const std::string& root, const std::string& relative, const std::string& contents);
// Makes everything written on the file system of root/relative durable (syncfs), once, before a rename publishes it.
void sync_file_system_beneath(const std::string& root, const std::string& relative);
// Puts the file `source` (a path the user named) at root/relative: a hard link, or a copy through the
// descriptor layer when it is on another file system.
void link_file_beneath(const std::string& root, const std::string& relative, const std::string& source);

// What keeps `path`, a file a study names (a picture, say), from being read where it is: "PATH: is a symbolic
// link; ..." (a link is never followed out of a study) or "PATH: is a FIFO, expected a regular file" (which
// would block the reader forever); "" for a regular file or nothing there. The path is examined, not followed.
std::string study_file_problem(const std::string& path);

// Reads root/relative (a regular file of at most `max_bytes`); nullopt when it or a folder on the way is
// missing. Throws IoError naming the path for a symbolic link, a non-regular file, or a read error. The file is
// opened once (O_NOFOLLOW|O_NONBLOCK: a FIFO never blocks), checked with fstat and read through that
// descriptor. `hook` step: "folder opened" (before the file is opened; tests swap the file there).
std::optional<std::string> read_file_beneath(const std::string& root, const std::string& relative,
                                             size_t max_bytes = kMaxReadBytes, const WriteStepHook& hook = {});
// The same, handing the file to `chunk` as it is read, a piece of at most 64 KiB at a time, instead of holding it
// whole: a parser that reads line by line needs no more memory than a line. False when it or a folder on the way is
// missing; the same errors.
bool read_file_beneath_in_chunks(const std::string& root, const std::string& relative, size_t max_bytes,
                                 const std::function<void(std::string_view)>& chunk);

}  // namespace ipd
