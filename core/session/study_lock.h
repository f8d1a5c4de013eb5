// One writer per study: ipd-studio holds an advisory lock (flock) on STUDY/.ipd-cache/lock while it may
// save hand pairs, so a second window on the same study opens read-only and says who holds it, instead of
// the two overwriting each other's edits. The file holds "pid <pid> on <host>" of the holder (for that
// message only: the kernel's lock, released when the holder exits or crashes, is what counts).
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
  explicit StudyLock(int fd) : fd_(fd) {}
  int fd_;
};

}  // namespace ipd
