#include "core/session/study_lock.h"

#include <fcntl.h>
#include <pwd.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>
#include <algorithm>
#include <cerrno>
#include <cstring>

namespace ipd {

namespace {

// The lock file's folder, opened without following a link (a study is untrusted: .ipd-cache -> /x must not
// make the lock file appear in /x).
int open_cache_folder(const std::string& root, std::string* why) {
  const int dir = ::open(root.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir < 0) {
    *why = fmt::format("{}: cannot open the study folder: {}", root, std::strerror(errno));
    return -1;
  }
  if (::mkdirat(dir, ".ipd-cache", 0755) != 0 && errno != EEXIST) {
    *why = fmt::format("{}/.ipd-cache: cannot create the folder: {}", root, std::strerror(errno));
    ::close(dir);
    return -1;
  }
  const int cache = ::openat(dir, ".ipd-cache", O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  const int err = errno;
  ::close(dir);
  if (cache < 0)
    *why = err == ELOOP || err == ENOTDIR
               ? fmt::format("{}/.ipd-cache: is a symbolic link or not a folder; no lock is taken through it", root)
               : fmt::format("{}/.ipd-cache: cannot open the folder: {}", root, std::strerror(err));
  return cache;
}

std::string holder_of(int fd) {
  char buf[256] = {};
  const ssize_t n = ::pread(fd, buf, sizeof buf - 1, 0);
  std::string text = n > 0 ? std::string(buf, static_cast<size_t>(n)) : std::string();
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  // Only what a holder writes is shown: anything else (a forged or torn file) is not repeated.
  const bool plain = text.rfind("pid ", 0) == 0 &&
                     std::all_of(text.begin(), text.end(), [](unsigned char c) { return c >= 0x20 && c < 0x7f; });
  return plain ? text : "another program";
}

}  // namespace

std::unique_ptr<StudyLock> StudyLock::try_acquire(const std::string& root, std::string* held_by) {
  std::string why;
  const int cache = open_cache_folder(root, &why);
  if (cache < 0) {
    *held_by = why;
    return nullptr;
  }
  // The study folder's own lock: a window whose .ipd-cache was deleted still holds it.
  const int folder = ::open(root.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (folder < 0 || ::flock(folder, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    const int note = ::openat(cache, "lock", O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    *held_by = folder < 0  ? fmt::format("{}: cannot open the study folder: {}", root, std::strerror(err))
               : note >= 0 ? holder_of(note)
                           : std::string("another window");
    if (note >= 0) ::close(note);
    if (folder >= 0) ::close(folder);
    ::close(cache);
    return nullptr;
  }
  int fd = ::openat(cache, "lock", O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644);
  int err = errno;
  bool note_writable = true;
  if (fd < 0 && err == EACCES) {
    // Another user's lock file: locked read-only (flock needs no write access), its note left as it is.
    fd = ::openat(cache, "lock", O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    err = errno;
    note_writable = false;
  }
  ::close(cache);
  const auto refuse = [&](std::string message) {
    *held_by = std::move(message);
    if (fd >= 0) ::close(fd);
    ::close(folder);  // releases the folder's lock
    return nullptr;
  };
  if (fd < 0)
    return refuse(err == ELOOP
                      ? fmt::format("{}/.ipd-cache/lock: is a symbolic link; no lock is taken through it", root)
                      : fmt::format("{}/.ipd-cache/lock: cannot open: {}", root, std::strerror(err)));
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode))
    return refuse(fmt::format("{}/.ipd-cache/lock: is not a regular file", root));
  // The holder's note is written into the lock file: were it a hard link to a file elsewhere (a study is
  // untrusted), that file would lose its contents. Ours has one name.
  if (st.st_nlink > 1)
    return refuse(fmt::format(
        "{}/.ipd-cache/lock: has {} names (a hard link to another file); no lock is taken through it (delete "
        "it: the study's .ipd-cache may be deleted)",
        root, static_cast<unsigned long long>(st.st_nlink)));
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    if (errno != EWOULDBLOCK)
      return refuse(fmt::format("{}/.ipd-cache/lock: cannot lock: {}", root, std::strerror(errno)));
    std::string holder = holder_of(fd);
    if (st.st_uid != ::geteuid()) {
      const passwd* pw = ::getpwuid(st.st_uid);
      holder += fmt::format(" (user {})", pw ? pw->pw_name : std::to_string(st.st_uid));
    }
    return refuse(holder);
  }
  if (note_writable) {
    char host[256] = {};
    if (::gethostname(host, sizeof host - 1) != 0) std::strcpy(host, "this machine");
    const std::string text = fmt::format("pid {} on {}\n", ::getpid(), host);
    // Only for the message another window shows: a failure here leaves the lock held all the same.
    const bool noted =
        ::ftruncate(fd, 0) == 0 && ::pwrite(fd, text.data(), text.size(), 0) == static_cast<ssize_t>(text.size());
    (void)noted;
  }
  return std::unique_ptr<StudyLock>(new StudyLock(fd, folder));
}

StudyLock::~StudyLock() {
  ::flock(fd_, LOCK_UN);
  ::close(fd_);
  ::flock(folder_fd_, LOCK_UN);
  ::close(folder_fd_);
}

}  // namespace ipd
