// Where the programs find their data files (fonts, the pycpd script): beside an installed binary
// (PREFIX/share/ipd-studio, the layout `cmake --install` and the .deb give), else in the source tree the
// binary was built from.
#pragma once

#include <filesystem>
#include <string>
#include <system_error>

namespace ipd {

// The path of `relative` (e.g. "fonts/DejaVuSans.ttf") in the installed data directory or in `source_dir`;
// empty when neither has it.
inline std::string find_data_file(const std::string& relative, const std::string& source_dir) {
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
