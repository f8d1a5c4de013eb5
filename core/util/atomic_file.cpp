#include "core/util/atomic_file.h"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>
#include <vector>

namespace fs = std::filesystem;

namespace ipd {

namespace {

std::string errno_text(int err) { return std::strerror(err); }

const char* kind_name(fs::file_type t) {
  switch (t) {
    case fs::file_type::fifo:
      return "a FIFO";
    case fs::file_type::socket:
      return "a socket";
    case fs::file_type::character:
      return "a character device";
    case fs::file_type::block:
      return "a block device";
    case fs::file_type::directory:
      return "a directory";
    default:
      return "not a regular file";
  }
}

// Makes the rename durable: a crash after this keeps the new name.
void sync_directory(const fs::path& dir) {
  const std::string d = dir.empty() ? std::string(".") : dir.string();
  const int fd = ::open(d.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;  // some file systems don't allow it; the rename itself is still atomic
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

std::string resolve_write_target(const std::string& path) {
  fs::path p(path);
  for (int hops = 0; hops < 40; ++hops) {
    std::error_code ec;
    const fs::file_status st = fs::symlink_status(p, ec);
    if (st.type() == fs::file_type::not_found) return p.string();
    if (ec) throw IoError(fmt::format("{}: cannot examine: {}", path, ec.message()));
    if (st.type() != fs::file_type::symlink) return p.string();
    const fs::path target = fs::read_symlink(p, ec);
    if (ec) throw IoError(fmt::format("{}: cannot read the symbolic link: {}", path, ec.message()));
    p = target.is_absolute() ? target : p.parent_path() / target;
  }
  throw IoError(path + ": too many levels of symbolic links");
}

void write_file_atomically(const std::string& path, const std::string& contents, const WriteStepHook& hook) {
  const fs::path target(resolve_write_target(path));
  std::error_code ec;
  if (target.has_parent_path()) {
    fs::create_directories(target.parent_path(), ec);
    if (ec) throw IoError(path + ": cannot create directory " + target.parent_path().string() + ": " + ec.message());
  }
  const std::string tmp = (target.parent_path() / temp_name_for(target.filename().string())).string();
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw IoError(path + ": cannot write: " + errno_text(errno));
  size_t done = 0;
  while (done < contents.size()) {
    const ssize_t n = ::write(fd, contents.data() + done, contents.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      const std::string why = errno_text(errno);
      ::close(fd);
      ::unlink(tmp.c_str());
      throw IoError(path + ": cannot write: " + why);
    }
    done += static_cast<size_t>(n);
  }
  if (::fsync(fd) != 0) {
    const std::string why = errno_text(errno);
    ::close(fd);
    ::unlink(tmp.c_str());
    throw IoError(path + ": cannot write: " + why);
  }
  if (::close(fd) != 0) {
    const std::string why = errno_text(errno);
    ::unlink(tmp.c_str());
    throw IoError(path + ": cannot write: " + why);
  }
  if (hook) hook("temp written");
  if (::rename(tmp.c_str(), target.c_str()) != 0) {
    const std::string why = errno_text(errno);
    ::unlink(tmp.c_str());
    throw IoError(path + ": cannot replace: " + why);
  }
  if (hook) hook("renamed");
  sync_directory(target.parent_path());
  if (hook) hook("directory synced");
}

FileKind file_kind(const std::string& path) {
  std::error_code ec;
  const fs::file_status link = fs::symlink_status(path, ec);
  if (link.type() == fs::file_type::not_found) return FileKind::kMissing;
  if (ec) throw IoError(fmt::format("{}: cannot examine: {}", path, ec.message()));
  const fs::file_status st = fs::status(path, ec);
  if (st.type() == fs::file_type::not_found) {
    std::error_code ignored;
    throw IoError(
        fmt::format("{}: is a dangling symbolic link (to {})", path, fs::read_symlink(path, ignored).string()));
  }
  if (ec) throw IoError(fmt::format("{}: cannot examine: {}", path, ec.message()));
  if (st.type() == fs::file_type::regular) return FileKind::kRegular;
  if (st.type() == fs::file_type::directory) return FileKind::kDirectory;
  return FileKind::kOther;
}

std::string read_file(const std::string& path, size_t max_bytes) {
  switch (file_kind(path)) {
    case FileKind::kMissing:
      throw IoError(path + ": no such file");
    case FileKind::kDirectory:
      throw IoError(path + ": is a directory, expected a file");
    case FileKind::kOther: {
      std::error_code ec;
      throw IoError(fmt::format("{}: is {}, expected a regular file", path, kind_name(fs::status(path, ec).type())));
    }
    case FileKind::kRegular:
      break;
  }
  // O_NONBLOCK: should the file be swapped for a FIFO after the check, open() must not hang on it.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw IoError(path + ": cannot read: " + errno_text(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw IoError(path + ": expected a regular file");
  }
  if (static_cast<unsigned long long>(st.st_size) > max_bytes) {
    ::close(fd);
    // Rounded up, so a file just over the limit never reads as equal to it.
    throw IoError(fmt::format("{}: is {:.1f} MB, larger than the {:g} MB limit for this kind of file", path,
                              std::ceil(st.st_size * 10 / 1048576.0) / 10, max_bytes / 1048576.0));
  }
  std::string out;
  out.resize(static_cast<size_t>(st.st_size));
  size_t done = 0;
  for (;;) {
    if (done == out.size()) {
      if (out.size() >= max_bytes) break;
      out.resize(std::min(max_bytes, std::max<size_t>(4096, out.size() * 2)));  // the file grew meanwhile
    }
    const ssize_t n = ::read(fd, out.data() + done, out.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      const std::string why = errno_text(errno);
      ::close(fd);
      throw IoError(path + ": cannot read: " + why);
    }
    if (n == 0) break;
    done += static_cast<size_t>(n);
  }
  ::close(fd);
  out.resize(done);
  return out;
}

std::string temp_name_for(const std::string& name) {
  std::random_device rd;
  return name.substr(0, 200) + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(rd() & 0xffff);
}

bool is_stale_temp_name(const std::string& name) {
  const size_t at = name.rfind(".tmp-");
  if (at == std::string::npos) return false;
  const std::string rest = name.substr(at + 5);  // <pid>-<n>
  const size_t dash = rest.find('-');
  if (dash == std::string::npos || dash == 0 || rest.find_first_not_of("0123456789-") != std::string::npos)
    return false;
  const long pid = std::strtol(rest.substr(0, dash).c_str(), nullptr, 10);
  return pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;  // the writer is gone
}

int remove_stale_temp_files_at(int dir_fd, bool links_too) {
  const int fd = ::dup(dir_fd);
  if (fd < 0) return 0;
  DIR* d = ::fdopendir(fd);
  if (!d) {
    ::close(fd);
    return 0;
  }
  ::rewinddir(d);  // the duplicate shares its position with dir_fd, which an earlier listing may have moved
  std::vector<std::string> stale;
  while (const dirent* e = ::readdir(d))
    if (is_stale_temp_name(e->d_name)) stale.emplace_back(e->d_name);
  ::closedir(d);
  int removed = 0;
  for (const auto& name : stale) {
    // Our writers make regular files: a link (or anything else) of that name is not ours, and stays.
    struct stat st {};
    if (::fstatat(dir_fd, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0 ||
        !(S_ISREG(st.st_mode) || (links_too && S_ISLNK(st.st_mode))))
      continue;
    if (::unlinkat(dir_fd, name.c_str(), 0) == 0) ++removed;  // a link swapped in meanwhile goes, never its target
  }
  return removed;
}

int remove_stale_temp_files(const std::string& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return 0;
  const int removed = remove_stale_temp_files_at(fd);
  ::close(fd);
  return removed;
}

}  // namespace ipd
