// Cache files inside an untrusted study, reached without ever following a symbolic link. STUDY/.ipd-cache
// comes with the study (a zip, a shared drive): were `.ipd-cache`, `registration`, an entry or
// `parsed-study.bin` a link, writing the cache would replace a file anywhere the user can write. So every
// component from `.ipd-cache` on is opened with O_NOFOLLOW relative to its parent's descriptor, folders are
// created with mkdirat, and a file is replaced by renameat within the directory descriptor: a link swapped in
// after a check is itself replaced, never written through. A link found is ignored and said once on stderr
// ("PATH: is a symbolic link; not used").
//
// Cache writes are not synced: a cache needs integrity, not durability. A lost or torn entry is caught by its
// signature (cache_signer.h) and recomputed.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace ipd {

// Where the walk without links starts: the part of `dir` before its last `.ipd-cache` component (the study
// root, which the user named), or `dir` itself for any other directory (the user cache directory, or one a
// caller chose). Everything after the anchor is never followed.
std::string cache_anchor(const std::string& dir);

class CacheDir {
 public:
  // The cache directory `dir` (created below its anchor when `create`); nullptr when it is missing, not a
  // directory, or reached through a symbolic link (said once on stderr).
  static std::shared_ptr<const CacheDir> open(const std::string& dir, bool create);
  ~CacheDir();
  CacheDir(const CacheDir&) = delete;
  CacheDir& operator=(const CacheDir&) = delete;

  const std::string& path() const { return path_; }

  // A read-only descriptor of the regular file `rel` ("name" or "sub/name"), or -1 when it is missing, a
  // link (said once), not a regular file, or unreadable. The caller closes it.
  int open_file(const std::string& rel) const;
  // The contents of `rel`, or nullopt as for open_file() or when larger than `max_bytes`.
  std::optional<std::string> read(const std::string& rel, size_t max_bytes) const;
  // Replaces `rel` with `contents` (creating "sub/" without following links); false when it can't, or when
  // `rel` is a symbolic link (said once; the link is left as it is). `hook` is called with "checked" after
  // the name was found not to be a link and before the rename (tests swap a link in there).
  bool write(const std::string& rel, const std::string& contents,
             const std::function<void(const char*)>& hook = {}) const;
  // Removes temp files of writers that were killed (`<name>.tmp-<pid>-<n>`, process gone) in this
  // directory; returns how many.
  int remove_stale_temp_files() const;

 private:
  CacheDir(int fd, std::string path) : fd_(fd), path_(std::move(path)) {}
  int fd_;
  std::string path_;
};

// Says "PATH: is a symbolic link; not used" (or another `why`) on stderr, once per path per process.
void warn_cache_entry_once(const std::string& path, const std::string& why);

}  // namespace ipd
