// Safe file access: writing so that a reader (or a killed process) never sees half of a file (temp file,
// fsync, rename, fsync of the directory), reading regular files only, and telling "missing" from "can't tell".
#pragma once

#include <cstddef>
#include <functional>
#include <string>

#include "core/util/errors.h"

namespace ipd {

// Called after each step of an atomic write ("temp written", "renamed", "directory synced"); tests throw
// from it to simulate a crash between steps.
using WriteStepHook = std::function<void(const char* step)>;

// Replaces `path` with `contents` atomically; creates parent directories. A symbolic link is resolved and its
// target replaced (the link stays a link). Throws IoError naming the file.
void write_file_atomically(const std::string& path, const std::string& contents, const WriteStepHook& hook = {});

// Follows symbolic links to the file a write to `path` should replace (a dangling link: its target).
std::string resolve_write_target(const std::string& path);

enum class FileKind { kMissing, kRegular, kDirectory, kOther };
// What is at `path` (following links). kMissing only when there is nothing there at all; a dangling or
// looping link, or a path that can't be examined (no permission), throws IoError naming the path and why.
FileKind file_kind(const std::string& path);

// Reads a whole regular file; throws IoError naming the file and the reason (missing, unreadable, a
// directory, FIFO or device, or larger than `max_bytes`).
constexpr size_t kMaxReadBytes = size_t{1} << 30;
std::string read_file(const std::string& path, size_t max_bytes = kMaxReadBytes);

// Removes `<name>.tmp-<pid>-<n>` files left in `dir` by writers that died (their process is gone): regular
// files only, never through or of a symbolic link (ours are never links); `dir` itself is opened without
// following a link. Returns how many were removed; problems are ignored (this is tidying, not a correctness
// step). Inside a study use remove_stale_temp_files_beneath (contained_file.h).
int remove_stale_temp_files(const std::string& dir);
// The same in the open folder `dir_fd`: listed with fdopendir on a duplicate of it, each name examined with
// fstatat and removed with unlinkat relative to it, so the folder is never looked up by name again.
// `links_too`: a link of such a name is removed as well (itself, never its target): in a cache folder,
// whose every entry is ours to remove.
int remove_stale_temp_files_at(int dir_fd, bool links_too = false);
// True for `<name>.tmp-<pid>-<n>` whose writer process is gone.
bool is_stale_temp_name(const std::string& name);
// The temp name a writer of `name` (a file name, no folder) uses beside it: `<name>.tmp-<pid>-<n>`, the name cut
// to 200 bytes so that any name the file system takes (255 bytes) still has a temp name it takes.
std::string temp_name_for(const std::string& name);

}  // namespace ipd
