#include "core/util/contained_file.h"

#include <dirent.h>
#include <fcntl.h>
#include <linux/openat2.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <fmt/format.h>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <utility>
#include <vector>

#include "core/util/file_descriptor.h"
#include "core/util/study_inputs.h"

namespace ipd {

namespace {

// "PATH: is a FIFO, expected a regular file" (or a socket, a device), as read_file says it.
std::string not_regular(const std::string& path, mode_t mode) {
  const char* kind = S_ISFIFO(mode) ? "a FIFO" : S_ISSOCK(mode) ? "a socket" : "a device";
  return path + ": is " + kind + ", expected a regular file";
}

std::string link_refused(const std::string& path, const char* action) {
  return fmt::format("{}: is a symbolic link; {} through it is refused (links inside a study are never followed)", path,
                     action);
}

// The folder names of `relative` and its file name; "." "..", empty parts and NUL bytes are refused, so the
// walk can't climb out of root.
std::vector<std::string> split_relative(const std::string& root, const std::string& relative) {
  std::vector<std::string> parts;
  size_t pos = 0;
  while (pos <= relative.size()) {
    const size_t slash = std::min(relative.find('/', pos), relative.size());
    parts.push_back(relative.substr(pos, slash - pos));
    pos = slash + 1;
  }
  for (const auto& p : parts)
    if (p.empty() || p == "." || p == ".." || p.find('\0') != std::string::npos)
      throw IoError(fmt::format("{}/{}: expected a plain path inside the folder", root, relative));
  return parts;
}

// The folder `relative` below the open folder `dir` in one openat2 call that the kernel keeps beneath `dir`
// with no symbolic link on the way (RESOLVE_BENEATH | RESOLVE_NO_SYMLINKS), or -1 when it did not open: a
// kernel without openat2 (before 5.6, or a sandbox that filters it), or a part that is missing, a link or a
// file. The caller then walks part by part, which opens the same folders and says precisely which part failed.
int open_folder_in_one_call(int dir, const std::string& relative) {
#ifdef SYS_openat2
  open_how how{};
  how.flags = O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC;
  how.resolve = RESOLVE_BENEATH | RESOLVE_NO_SYMLINKS | RESOLVE_NO_MAGICLINKS;
  return static_cast<int>(::syscall(SYS_openat2, dir, relative.c_str(), &how, sizeof how));
#else
  (void)dir, (void)relative;
  return -1;
#endif
}

// Opens the folders of `parts` (all but the last) below root, without following a link. Missing folders
// are created when `create`; otherwise a missing one gives an FileDescriptor of -1. `shown` receives the path so far.
FileDescriptor open_folders(const std::string& root, const std::vector<std::string>& parts, bool create,
                            const char* action, std::string* shown) {
  FileDescriptor dir(::open(root.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (dir.get() < 0) {
    if (errno == ENOENT && !create) return FileDescriptor();
    throw IoError(fmt::format("{}: cannot open the folder: {}", root, std::strerror(errno)));
  }
  *shown = root.size() > 1 && root.back() == '/' ? root.substr(0, root.size() - 1) : root;
  if (parts.size() > 2) {  // two folders or more: one call instead of one per folder
    std::string folders = parts[0];
    for (size_t k = 1; k + 1 < parts.size(); ++k) folders += "/" + parts[k];
    if (const int fd = open_folder_in_one_call(dir.get(), folders); fd >= 0) {
      *shown += "/" + folders + "/" + parts.back();
      return FileDescriptor(fd);
    }
  }
  for (size_t k = 0; k + 1 < parts.size(); ++k) {
    *shown += "/" + parts[k];
    int fd = ::openat(dir.get(), parts[k].c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0 && errno == ENOENT) {
      if (!create) return FileDescriptor();
      if (::mkdirat(dir.get(), parts[k].c_str(), 0755) != 0 && errno != EEXIST)
        throw IoError(fmt::format("{}: cannot create the folder: {}", *shown, std::strerror(errno)));
      fd = ::openat(dir.get(), parts[k].c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    }
    if (fd < 0) {
      const int err = errno;
      struct stat st {};
      if (::fstatat(dir.get(), parts[k].c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0) {
        if (S_ISLNK(st.st_mode)) throw IoError(link_refused(*shown, action));
        if (!S_ISDIR(st.st_mode)) throw IoError(fmt::format("{}: is a file, expected a folder", *shown));
      }
      throw IoError(fmt::format("{}: cannot open the folder: {}", *shown, std::strerror(err)));
    }
    dir = FileDescriptor(fd);
  }
  *shown += "/" + parts.back();
  return dir;
}

// The folder root/relative itself, opened beneath root without following a link; an FileDescriptor of -1 when missing.
FileDescriptor open_folder(const std::string& root, const std::string& relative, const char* action) {
  std::vector<std::string> parts = split_relative(root, relative);
  parts.emplace_back();  // open_folders opens every part but the last
  std::string shown;
  return open_folders(root, parts, false, action, &shown);
}

// What the last part is, examined without following it: 0 when missing, else st_mode's type bits.
mode_t type_at(int dir, const std::string& name, const std::string& shown) {
  struct stat st {};
  if (::fstatat(dir, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0) return st.st_mode & S_IFMT;
  if (errno == ENOENT) return 0;
  throw IoError(fmt::format("{}: cannot examine: {}", shown, std::strerror(errno)));
}

void write_all(int fd, const std::string& contents, const std::string& shown, bool sync = true) {
  size_t done = 0;
  while (done < contents.size()) {
    const ssize_t n = ::write(fd, contents.data() + done, contents.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw IoError(shown + ": cannot write: " + std::strerror(errno));
    }
    done += static_cast<size_t>(n);
  }
  if (sync && ::fsync(fd) != 0) throw IoError(shown + ": cannot write: " + std::strerror(errno));
}

// Reads the open regular file `fd` whole (at most `max_bytes`), named `shown` in errors.
// Reads the open file `fd` to its end, 64 KiB at a time, each piece handed to `chunk`.
void read_open_file_in_chunks(int fd, const std::string& shown, size_t max_bytes,
                              const std::function<void(std::string_view)>& chunk) {
  char buf[65536];
  size_t total = 0;
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw IoError(shown + ": cannot read: " + std::strerror(errno));
    }
    if (n == 0) break;
    total += static_cast<size_t>(n);
    if (total > max_bytes)
      throw IoError(fmt::format("{}: grew beyond the {} MB limit for this kind of file while being read", shown,
                                max_bytes >> 20));
    chunk(std::string_view(buf, static_cast<size_t>(n)));
  }
}

std::string read_open_file(int fd, const std::string& shown, size_t max_bytes) {
  std::string out;
  read_open_file_in_chunks(fd, shown, max_bytes, [&](std::string_view piece) { out.append(piece); });
  return out;
}

// Runs `recheck` with what `name` in the open folder `dir` holds now (nullopt: missing); a link or anything
// but a regular file is not read, and not checked: the rename replaces it, never following it.
void run_recheck(int dir, const std::string& name, const std::string& shown, const Recheck& recheck) {
  const int fd = ::openat(dir, name.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    if (errno == ENOENT) recheck(std::nullopt);
    return;
  }
  const FileDescriptor file(fd);
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) return;
  recheck(read_open_file(fd, shown, kMaxReadBytes));
}

}  // namespace

void write_file_beneath(const std::string& root, const std::string& relative, const std::string& contents,
                        const WriteStepHook& hook, const Recheck& recheck) {
  const std::vector<std::string> parts = split_relative(root, relative);
  std::string shown;
  const FileDescriptor dir = open_folders(root, parts, true, "saving", &shown);
  if (hook) hook("folder opened");
  const std::string& name = parts.back();
  const mode_t type = type_at(dir.get(), name, shown);
  if (type == S_IFLNK) throw IoError(link_refused(shown, "saving"));
  if (type != 0 && type != S_IFREG) throw IoError(shown + ": is not a regular file; not replaced");
  if (hook) hook("checked");
  const std::string tmp = temp_name_for(name);
  // O_EXCL | O_NOFOLLOW: a link planted under the temp name is never written through.
  const int fd = ::openat(dir.get(), tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0) throw IoError(shown + ": cannot write: " + std::strerror(errno));
  try {
    write_all(fd, contents, shown);
  } catch (...) {
    ::close(fd);
    ::unlinkat(dir.get(), tmp.c_str(), 0);
    throw;
  }
  if (::close(fd) != 0) {
    const std::string why = std::strerror(errno);
    ::unlinkat(dir.get(), tmp.c_str(), 0);
    throw IoError(shown + ": cannot write: " + why);
  }
  if (hook) hook("temp written");
  if (recheck) {
    try {
      run_recheck(dir.get(), name, shown, recheck);
    } catch (...) {
      ::unlinkat(dir.get(), tmp.c_str(), 0);
      throw;
    }
  }
  // renameat replaces whatever is at `name` now (even a link swapped in after the check) without following it.
  if (::renameat(dir.get(), tmp.c_str(), dir.get(), name.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    ::unlinkat(dir.get(), tmp.c_str(), 0);
    throw IoError(shown + ": cannot replace: " + why);
  }
  if (hook) hook("renamed");
  ::fsync(dir.get());  // some file systems refuse it; the rename itself is still atomic
  if (hook) hook("directory synced");
}

bool remove_file_beneath(const std::string& root, const std::string& relative, const WriteStepHook& hook,
                         const Recheck& recheck) {
  const std::vector<std::string> parts = split_relative(root, relative);
  std::string shown;
  const FileDescriptor dir = open_folders(root, parts, false, "deleting", &shown);
  if (dir.get() < 0) return false;
  if (hook) hook("folder opened");
  const std::string& name = parts.back();
  const mode_t type = type_at(dir.get(), name, shown);
  if (type == 0) return false;
  if (type == S_IFLNK) throw IoError(link_refused(shown, "deleting"));
  if (type == S_IFDIR) throw IoError(shown + ": is a folder, expected a file; not removed");
  if (hook) hook("checked");
  if (recheck) run_recheck(dir.get(), name, shown, recheck);
  // unlinkat removes a name in this folder; should a link have been swapped in, the link goes, not its target.
  if (::unlinkat(dir.get(), name.c_str(), 0) != 0) {
    if (errno == ENOENT) return false;
    throw IoError(shown + ": cannot remove: " + std::strerror(errno));
  }
  ::fsync(dir.get());  // the removal is durable before the next step depends on it
  return true;
}

void check_beneath(const std::string& root, const std::string& relative) {
  const std::vector<std::string> parts = split_relative(root, relative);
  std::string shown;
  const FileDescriptor dir = open_folders(root, parts, false, "saving", &shown);
  if (dir.get() >= 0 && type_at(dir.get(), parts.back(), shown) == S_IFLNK)
    throw IoError(link_refused(shown, "saving"));
}

namespace {
// Reads the entry `name` of the open folder `dir` (named `shown` in errors), as read_file_beneath says.
// The entry `name` of the open folder `dir` opened for reading, once checked a regular file of at most max_bytes;
// -1 when it is missing.
FileDescriptor open_entry(int dir, const std::string& name, const std::string& shown, size_t max_bytes) {
  // O_NONBLOCK: a FIFO must not make open() hang; O_NOFOLLOW: a link is refused, not followed.
  const int fd = ::openat(dir, name.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    if (errno == ENOENT) return FileDescriptor(-1);
    if (errno == ELOOP) throw IoError(link_refused(shown, "reading"));
    throw IoError(shown + ": cannot read: " + std::strerror(errno));
  }
  FileDescriptor file(fd);
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw IoError(shown + ": cannot read: " + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) throw IoError(shown + ": is a directory, expected a file");
  if (!S_ISREG(st.st_mode)) throw IoError(not_regular(shown, st.st_mode));
  if (static_cast<unsigned long long>(st.st_size) > max_bytes)
    // Rounded up, so a file just over the limit never reads as equal to it (as read_file says it).
    throw IoError(fmt::format("{}: is {:.1f} MB, larger than the {:g} MB limit for this kind of file", shown,
                              std::ceil(st.st_size * 10 / 1048576.0) / 10, max_bytes / 1048576.0));
  return file;
}

std::optional<std::string> read_entry(int dir, const std::string& name, const std::string& shown, size_t max_bytes) {
  const FileDescriptor file = open_entry(dir, name, shown, max_bytes);
  if (file.get() < 0) return std::nullopt;
  return read_open_file(file.get(), shown, max_bytes);
}
}  // namespace

std::optional<std::string> read_file_beneath(const std::string& root, const std::string& relative, size_t max_bytes,
                                             const WriteStepHook& hook) {
  const std::vector<std::string> parts = split_relative(root, relative);
  std::string shown;
  const FileDescriptor dir = open_folders(root, parts, false, "reading", &shown);
  if (dir.get() < 0) return std::nullopt;
  if (hook) hook("folder opened");
  return read_entry(dir.get(), parts.back(), shown, max_bytes);
}

bool read_file_beneath_in_chunks(const std::string& root, const std::string& relative, size_t max_bytes,
                                 const std::function<void(std::string_view)>& chunk) {
  const std::vector<std::string> parts = split_relative(root, relative);
  std::string shown;
  const FileDescriptor dir = open_folders(root, parts, false, "reading", &shown);
  if (dir.get() < 0) return false;
  const FileDescriptor file = open_entry(dir.get(), parts.back(), shown, max_bytes);
  if (file.get() < 0) return false;
  read_open_file_in_chunks(file.get(), shown, max_bytes, chunk);
  return true;
}

std::optional<std::string> OpenFolder::read(const std::string& name, size_t max_bytes) const {
  if (fd_ < 0) return std::nullopt;
  return read_entry(fd_, name, shown_ + name, max_bytes);
}

int remove_stale_temp_files_beneath(const std::string& root, const std::string& relative, const WriteStepHook& hook) {
  try {
    const FileDescriptor dir = open_folder(root, relative, "deleting");
    if (dir.get() < 0) return 0;
    if (hook) hook("folder opened");
    return remove_stale_temp_files_at(dir.get());
  } catch (const IoError&) {
    return 0;  // a link, or a folder that can't be opened: tidying, not a correctness step
  }
}

namespace {

// The entries of the open folder `dir`, sorted by name.
std::vector<FolderEntry> list_entries(int dir, const std::string& shown) {
  std::vector<FolderEntry> out;
  const int fd = ::dup(dir);
  DIR* d = fd < 0 ? nullptr : ::fdopendir(fd);
  if (!d) {
    if (fd >= 0) ::close(fd);
    throw IoError(fmt::format("{}: cannot list the folder: {}", shown, std::strerror(errno)));
  }
  ::rewinddir(d);
  while (const dirent* e = ::readdir(d)) {
    const std::string name = e->d_name;
    if (name == "." || name == "..") continue;
    // The listing's own type when the file system gives one (a link is DT_LNK, never DT_DIR): one fstatat per
    // entry costs more than the listing itself in a folder of 10,000 label files.
    bool folder = e->d_type == DT_DIR;
    if (e->d_type == DT_UNKNOWN) {
      struct stat st {};
      folder = ::fstatat(dir, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISDIR(st.st_mode);
    }
    out.push_back({name, folder});
  }
  ::closedir(d);
  std::sort(out.begin(), out.end(), [](const FolderEntry& x, const FolderEntry& y) { return x.name < y.name; });
  return out;
}

// Removes everything in the open folder `dir`, depth first, never following a link.
void empty_folder(int dir, const std::string& shown) {
  for (const FolderEntry& e : list_entries(dir, shown)) {
    const std::string inner = shown + "/" + e.name;
    if (e.folder) {
      const FileDescriptor sub(::openat(dir, e.name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC));
      if (sub.get() < 0) throw IoError(fmt::format("{}: cannot open the folder: {}", inner, std::strerror(errno)));
      empty_folder(sub.get(), inner);
    }
    if (::unlinkat(dir, e.name.c_str(), e.folder ? AT_REMOVEDIR : 0) != 0 && errno != ENOENT)
      throw IoError(fmt::format("{}: cannot remove: {}", inner, std::strerror(errno)));
  }
}

}  // namespace

std::vector<FolderEntry> entries_beneath(const std::string& root, const std::string& relative) {
  const FileDescriptor dir = open_folder(root, relative, "reading");
  if (dir.get() < 0) return {};
  return list_entries(dir.get(), root + "/" + relative);
}

OpenFolder::OpenFolder(const std::string& root, const std::string& relative) {
  std::vector<std::string> parts = split_relative(root, relative);
  parts.emplace_back();                                                  // open_folders opens every part but the last
  fd_ = open_folders(root, parts, false, "reading", &shown_).release();  // shown_: "ROOT/RELATIVE/"
}

OpenFolder::~OpenFolder() {
  if (fd_ >= 0) ::close(fd_);
}

bool OpenFolder::stat_entry(const std::string& name, struct stat* st) const {
  return fd_ >= 0 && ::fstatat(fd_, name.c_str(), st, AT_SYMLINK_NOFOLLOW) == 0;
}

std::vector<std::string> folders_beneath(const std::string& root, const std::string& relative) {
  std::vector<std::string> out;
  for (const FolderEntry& e : entries_beneath(root, relative))
    if (e.folder) out.push_back(e.name);
  return out;
}

void make_folder_beneath(const std::string& root, const std::string& relative) {
  const std::vector<std::string> parts = split_relative(root, relative);
  std::string shown;
  const FileDescriptor dir = open_folders(root, parts, true, "saving", &shown);
  if (::mkdirat(dir.get(), parts.back().c_str(), 0755) != 0)
    throw IoError(fmt::format("{}: cannot create the folder: {}", shown, std::strerror(errno)));
}

void rename_beneath(const std::string& root, const std::string& from, const std::string& to) {
  const std::vector<std::string> a = split_relative(root, from), b = split_relative(root, to);
  std::string shown_a, shown_b;
  const FileDescriptor dir_a = open_folders(root, a, false, "moving", &shown_a);
  const FileDescriptor dir_b = open_folders(root, b, true, "moving", &shown_b);
  if (dir_a.get() < 0 || ::renameat(dir_a.get(), a.back().c_str(), dir_b.get(), b.back().c_str()) != 0)
    throw IoError(
        fmt::format("{}: cannot move to {}: {}", shown_a, shown_b, std::strerror(dir_a.get() < 0 ? ENOENT : errno)));
}

void exchange_beneath(const std::string& root, const std::string& a, const std::string& b) {
  const std::vector<std::string> pa = split_relative(root, a), pb = split_relative(root, b);
  std::string shown_a, shown_b;
  const FileDescriptor dir_a = open_folders(root, pa, false, "moving", &shown_a);
  const FileDescriptor dir_b = open_folders(root, pb, false, "moving", &shown_b);
  if (dir_a.get() < 0 || dir_b.get() < 0 ||
      ::renameat2(dir_a.get(), pa.back().c_str(), dir_b.get(), pb.back().c_str(), RENAME_EXCHANGE) != 0)
    throw IoError(fmt::format("{}: cannot be swapped with {}: {}", shown_a, shown_b, std::strerror(errno)));
}

void remove_tree_beneath(const std::string& root, const std::string& relative) {
  const std::vector<std::string> parts = split_relative(root, relative);
  std::string shown;
  const FileDescriptor dir = open_folders(root, parts, false, "deleting", &shown);
  if (dir.get() < 0) return;
  const mode_t type = type_at(dir.get(), parts.back(), shown);
  if (type == 0) return;
  if (type == S_IFDIR) {
    const FileDescriptor sub(
        ::openat(dir.get(), parts.back().c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC));
    if (sub.get() < 0) throw IoError(fmt::format("{}: cannot open the folder: {}", shown, std::strerror(errno)));
    empty_folder(sub.get(), shown);
  }
  if (::unlinkat(dir.get(), parts.back().c_str(), type == S_IFDIR ? AT_REMOVEDIR : 0) != 0 && errno != ENOENT)
    throw IoError(fmt::format("{}: cannot remove: {}", shown, std::strerror(errno)));
}

void write_new_file_beneath(const std::string& root, const std::string& relative, const std::string& contents) {
  const std::vector<std::string> parts = split_relative(root, relative);
  std::string shown;
  const FileDescriptor dir = open_folders(root, parts, true, "saving", &shown);
  // O_EXCL | O_NOFOLLOW: a file or link already there is never written through.
  const int fd = ::openat(dir.get(), parts.back().c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0) throw IoError(shown + ": cannot write: " + std::strerror(errno));
  try {
    write_all(fd, contents, shown, false);
  } catch (...) {
    ::close(fd);
    ::unlinkat(dir.get(), parts.back().c_str(), 0);
    throw;
  }
  if (::close(fd) != 0) throw IoError(shown + ": cannot write: " + std::strerror(errno));
}

void sync_file_system_beneath(const std::string& root, const std::string& relative) {
  const FileDescriptor dir = open_folder(root, relative, "saving");
  if (::syncfs(dir.get()) != 0)
    throw IoError((std::filesystem::path(root) / relative).string() + ": cannot sync: " + std::strerror(errno));
}

void link_file_beneath(const std::string& root, const std::string& relative, const std::string& source) {
  const std::vector<std::string> parts = split_relative(root, relative);
  std::string shown;
  const FileDescriptor dir = open_folders(root, parts, true, "saving", &shown);
  if (::linkat(AT_FDCWD, source.c_str(), dir.get(), parts.back().c_str(), 0) == 0) return;
  if (errno != EXDEV && errno != EPERM && errno != EMLINK)
    throw IoError(fmt::format("{}: cannot link {} there: {}", shown, source, std::strerror(errno)));
  write_file_beneath(root, relative, read_file(source));  // another file system: a copy
}

namespace {

// `path` relative to `base` when it is lexically below it (both absolute and normal).
std::optional<std::string> relative_below(const std::filesystem::path& base, const std::filesystem::path& path) {
  const std::filesystem::path rel = path.lexically_relative(base);
  if (rel.empty() || rel == "." || *rel.begin() == "..") return std::nullopt;
  return rel.string();
}

}  // namespace

std::optional<std::string> path_below(const std::string& root, const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path p = fs::absolute(path, ec).lexically_normal();
  if (ec) return std::nullopt;
  if (auto rel = relative_below(fs::absolute(root, ec).lexically_normal(), p)) return rel;
  const fs::path real_root = fs::canonical(root, ec);  // the user named root: its own link may be resolved
  if (ec) return std::nullopt;
  return relative_below(real_root, p);
}

void write_output_file(const std::string& root, const std::string& path, const std::string& contents) {
  if (const std::string input = study_input_problem(root, path); !input.empty()) throw IoError(input);
  if (const auto rel = path_below(root, path)) {
    std::error_code ec;
    write_file_beneath(std::filesystem::canonical(root, ec).string(), *rel, contents);
    return;
  }
  write_file_atomically(path, contents);
}

std::string study_file_problem(const std::string& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0)
    return errno == ENOENT ? "" : path + ": cannot be examined: " + std::strerror(errno);
  if (S_ISLNK(st.st_mode)) return link_refused(path, "reading");
  if (S_ISREG(st.st_mode)) return "";
  if (S_ISDIR(st.st_mode)) return path + ": is a directory, expected a file";
  return not_regular(path, st.st_mode);
}

}  // namespace ipd
