#include "core/util/cache_file.h"

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <set>
#include <vector>

#include "core/util/atomic_file.h"
#include "core/util/file_descriptor.h"

namespace fs = std::filesystem;

namespace ipd {

namespace {

std::vector<std::string> components(const std::string& rel) {
  std::vector<std::string> out;
  for (const auto& c : fs::path(rel)) {
    const std::string s = c.string();
    if (!s.empty() && s != "/") out.push_back(s);
  }
  return out;
}

// Says why `name` in `dir_fd` is not used (a link, not a directory, ...), once.
void refuse(int dir_fd, const std::string& shown, const std::string& name, int err) {
  struct stat st {};
  if (::fstatat(dir_fd, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISLNK(st.st_mode))
    warn_cache_entry_once(shown, "is a symbolic link; not used");
  else if (err == ENOTDIR)
    warn_cache_entry_once(shown, "is not a directory; not used");
  else if (err != ENOENT)
    warn_cache_entry_once(shown, fmt::format("cannot open: {}; not used", std::strerror(err)));
}

// Opens the folder `name` in `dir_fd` without following a link, creating it when asked.
int open_subdir(int dir_fd, const std::string& shown, const std::string& name, bool create) {
  if (name == "." || name == "..") return -1;
  int fd = ::openat(dir_fd, name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0 && errno == ENOENT && create) {
    if (::mkdirat(dir_fd, name.c_str(), 0755) != 0 && errno != EEXIST) return -1;
    fd = ::openat(dir_fd, name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  }
  if (fd < 0) refuse(dir_fd, shown, name, errno);
  return fd;
}

// The folder holding `rel`'s last component, and that component's name.
FileDescriptor parent_of(int root_fd, const std::string& root_path, const std::string& rel, bool create,
                         std::string* name) {
  const std::vector<std::string> parts = components(rel);
  if (parts.empty() || parts.back() == "." || parts.back() == "..") return FileDescriptor();
  *name = parts.back();
  FileDescriptor dir = FileDescriptor::borrowed(root_fd);
  fs::path shown(root_path);
  for (size_t k = 0; k + 1 < parts.size(); ++k) {
    shown /= parts[k];
    FileDescriptor next(open_subdir(dir.get(), shown.string(), parts[k], create));
    if (next.get() < 0) return FileDescriptor();
    dir = std::move(next);
  }
  return dir;
}

std::atomic<unsigned> temp_counter{0};

}  // namespace

void warn_cache_entry_once(const std::string& path, const std::string& why) {
  static std::mutex mu;
  static std::set<std::string> said;
  std::lock_guard<std::mutex> l(mu);
  if (said.insert(path).second) std::fprintf(stderr, "%s: %s\n", path.c_str(), why.c_str());
}

std::string cache_anchor(const std::string& dir) {
  const fs::path p(dir);
  fs::path anchor, last_anchor;
  bool found = false;
  for (const auto& c : p) {
    if (c == ".ipd-cache") {
      last_anchor = anchor;
      found = true;
    }
    anchor /= c;
  }
  if (!found) return dir;
  return last_anchor.empty() ? std::string(".") : last_anchor.string();
}

std::shared_ptr<const CacheDir> CacheDir::open(const std::string& dir, bool create) {
  const std::string anchor = cache_anchor(dir);
  const std::string rel = fs::path(dir).lexically_relative(anchor).string();
  std::error_code ec;
  // The anchor is followed as given: the study root the user named, or the user's own cache directory.
  if (create && (rel.empty() || rel == ".")) fs::create_directories(anchor, ec);
  int fd = ::open(anchor.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return nullptr;
  fs::path shown(anchor);
  for (const std::string& part : (rel == "." ? std::vector<std::string>{} : components(rel))) {
    shown /= part;
    const int next = open_subdir(fd, shown.string(), part, create);
    ::close(fd);
    if (next < 0) return nullptr;
    fd = next;
  }
  return std::shared_ptr<const CacheDir>(new CacheDir(fd, dir));
}

CacheDir::~CacheDir() {
  if (fd_ >= 0) ::close(fd_);
}

int CacheDir::open_file(const std::string& rel) const {
  std::string name;
  const FileDescriptor dir = parent_of(fd_, path_, rel, false, &name);
  if (dir.get() < 0) return -1;
  const std::string shown = (fs::path(path_) / rel).string();
  // O_NONBLOCK: a FIFO put there must not make the open hang.
  const int fd = ::openat(dir.get(), name.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    refuse(dir.get(), shown, name, errno);
    return -1;
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    warn_cache_entry_once(shown, "is not a regular file; not used");
    return -1;
  }
  return fd;
}

std::optional<std::string> CacheDir::read(const std::string& rel, size_t max_bytes) const {
  const int fd = open_file(rel);
  if (fd < 0) return std::nullopt;
  struct stat st {};
  if (::fstat(fd, &st) != 0 || static_cast<unsigned long long>(st.st_size) > max_bytes) {
    ::close(fd);
    return std::nullopt;
  }
  std::string out(static_cast<size_t>(st.st_size), '\0');
  size_t done = 0;
  while (done < out.size()) {
    const ssize_t n = ::read(fd, out.data() + done, out.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += static_cast<size_t>(n);
  }
  ::close(fd);
  if (done != out.size()) return std::nullopt;  // shrank meanwhile: not what was signed
  return out;
}

bool CacheDir::write(const std::string& rel, const std::string& contents,
                     const std::function<void(const char*)>& hook) const {
  std::string name;
  const FileDescriptor dir = parent_of(fd_, path_, rel, true, &name);
  if (dir.get() < 0) return false;
  const std::string shown = (fs::path(path_) / rel).string();
  struct stat st {};
  if (::fstatat(dir.get(), name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && !S_ISREG(st.st_mode)) {
    warn_cache_entry_once(shown,
                          S_ISLNK(st.st_mode) ? "is a symbolic link; not used" : "is not a regular file; not used");
    return false;
  }
  const std::string tmp = fmt::format("{}.tmp-{}-{}", name, ::getpid(), temp_counter++);
  const int fd = ::openat(dir.get(), tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0) return false;
  size_t done = 0;
  bool ok = true;
  while (ok && done < contents.size()) {
    const ssize_t n = ::write(fd, contents.data() + done, contents.size() - done);
    if (n < 0 && errno == EINTR) continue;
    ok = n > 0;
    if (ok) done += static_cast<size_t>(n);
  }
  ok = ::close(fd) == 0 && ok;
  if (ok && hook) hook("checked");
  // renameat replaces the directory entry: were a link swapped in since the check, the link itself is
  // replaced and its target left alone.
  if (!ok || ::renameat(dir.get(), tmp.c_str(), dir.get(), name.c_str()) != 0) {
    ::unlinkat(dir.get(), tmp.c_str(), 0);
    return false;
  }
  return true;
}

int CacheDir::remove_stale_temp_files() const { return remove_stale_temp_files_at(fd_, true); }

}  // namespace ipd
