#include "core/util/data_files.h"

#include <filesystem>
#include <system_error>

namespace ipd {

std::string find_data_file(const std::string& relative, const std::string& source_dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  for (const fs::path& dir : {ec ? fs::path() : exe.parent_path() / IPD_DATA_FROM_BIN, fs::path(source_dir)}) {
    if (dir.empty()) continue;
    const fs::path p = dir / relative;
    if (fs::is_regular_file(p, ec)) return p.lexically_normal().string();
  }
  return {};
}

}  // namespace ipd
