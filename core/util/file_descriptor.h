// A file descriptor closed when it goes out of scope, unless it is borrowed (a caller's descriptor walked from,
// never closed here). The received-study file layer (contained_file, cache_file) opens every file and folder
// through one of these, so no error path leaks a descriptor.
#pragma once

#include <unistd.h>

#include <utility>

namespace ipd {

class FileDescriptor {
 public:
  explicit FileDescriptor(int fd = -1) : fd_(fd) {}
  static FileDescriptor borrowed(int fd) {
    FileDescriptor d(fd);
    d.own_ = false;
    return d;
  }
  FileDescriptor(FileDescriptor&& o) noexcept : fd_(std::exchange(o.fd_, -1)), own_(o.own_) {}
  FileDescriptor& operator=(FileDescriptor&& o) noexcept {
    std::swap(fd_, o.fd_);
    std::swap(own_, o.own_);
    return *this;
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  ~FileDescriptor() {
    if (own_ && fd_ >= 0) ::close(fd_);
  }
  int get() const { return fd_; }
  int release() { return std::exchange(fd_, -1); }

 private:
  int fd_;
  bool own_ = true;
};

}  // namespace ipd
