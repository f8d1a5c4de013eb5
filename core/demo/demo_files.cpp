#include "core/demo/demo_files.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/util/atomic_file.h"
#include "core/util/contained_file.h"
#include "core/util/errors.h"

namespace ipd {

void write_demo_file(const std::string& dir, const std::string& relative, const std::string& contents) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);  // the demo's own folder, named by the user
  write_new_file_beneath(dir, relative, contents);
}

void write_demo_labels(const std::string& dir, const std::string& relative, const std::vector<Box>& boxes,
                       LabelKind kind) {
  write_demo_file(dir, relative, labels_text(boxes, kind));
}

void finish_demo_study(const std::string& dir, const std::string& study_yaml, const std::string& readme) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  const bool synced = fd >= 0 && ::syncfs(fd) == 0;
  const int error = errno;
  if (fd >= 0) ::close(fd);
  if (!synced) throw IoError(dir + ": cannot sync the demo's files: " + std::strerror(error));
  write_file_atomically((std::filesystem::path(dir) / "study.yaml").string(), study_yaml);
  if (!readme.empty()) write_file_atomically((std::filesystem::path(dir) / "README.md").string(), readme);
}

}  // namespace ipd
