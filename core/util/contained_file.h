// Files below a folder the user chose (a study), reached without ever following a symbolic link below it.
//
// A study is untrusted input: a link inside it (`pairs -> /x`, `pairs/B__A -> /victim`) must not make the
// tool write, delete or read outside it. Every folder on the way is opened with O_NOFOLLOW from the one
// above it, and the file is then written, removed or read relative to that open folder, so a link swapped
// in after a check is never followed either. The root itself may be a link: the user named it.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "core/util/atomic_file.h"

namespace ipd {

// Replaces root/relative with `contents` atomically (temp file, fsync, rename, fsync of the folder),
// creating missing folders. Refuses with IoError "PATH: is a symbolic link; ..." when a folder below root
// or the file itself is one. `hook` steps: "folder opened", "checked", "temp written", "renamed",
// "directory synced".
void write_file_beneath(const std::string& root, const std::string& relative, const std::string& contents,
                        const WriteStepHook& hook = {});

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
// symbolic link, whether the file or a folder on the way. `hook` steps: "folder opened", "checked".
bool remove_file_beneath(const std::string& root, const std::string& relative, const WriteStepHook& hook = {});

// Checks that the folders of root/relative are real folders (or missing) and the file is not a link,
// without changing anything ("saving through it is refused"): a save checks every file it will write or
// remove before it changes the first one.
void check_beneath(const std::string& root, const std::string& relative);

// What keeps `path`, a file a study names (a picture, say), from being read where it is: "PATH: is a symbolic
// link; ..." (a link is never followed out of a study) or "PATH: is a FIFO, expected a regular file" (which
// would block the reader forever); "" for a regular file or nothing there. The path is examined, not followed.
std::string study_file_problem(const std::string& path);

// Reads root/relative (a regular file of at most `max_bytes`); nullopt when it or a folder on the way is
// missing. Throws IoError naming the path for a symbolic link, a non-regular file, or a read error.
std::optional<std::string> read_file_beneath(const std::string& root, const std::string& relative,
                                             size_t max_bytes = kMaxReadBytes);

}  // namespace ipd
