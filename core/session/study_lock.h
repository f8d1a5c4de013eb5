// One writer per study: ipd-studio holds an advisory lock (flock) on the study folder itself and on
// STUDY/.ipd-cache/lock while it may save hand pairs, so a second window on the same study opens read-only and
// says who holds it, instead of the two overwriting each other's edits. The folder's lock is what a deleted
// .ipd-cache (which may be deleted at any time) can't take away; the file holds "pid <pid> on <host>" of the
// holder (for the message only: the kernel's locks, released when the holder exits or crashes, are what
// count). A lock file another user created is taken read-only when its holder is gone: a stale lock is stale
// whoever made it.
// `ipd table` never writes pairs and takes no lock.
#pragma once

#include <memory>
#include <string>

namespace ipd {

class StudyLock {
 public:
  // Takes the lock of the study at `root` without waiting. Null when another process holds it
  // (`*held_by`: "pid 123 on host-a", or "another program" when it can't tell) or when the lock file
  // can't be made (`*held_by`: why; e.g. .ipd-cache is a symbolic link or the study is not writable).
  static std::unique_ptr<StudyLock> try_acquire(const std::string& root, std::string* held_by);
  ~StudyLock();  // releases the lock
  StudyLock(const StudyLock&) = delete;
  StudyLock& operator=(const StudyLock&) = delete;

 private:
  StudyLock(int fd, int folder_fd) : fd_(fd), folder_fd_(folder_fd) {}
  int fd_, folder_fd_;
};

}  // namespace ipd
