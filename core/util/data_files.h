// Where the programs find their data files (fonts, the pycpd script): beside an installed binary
// (PREFIX/share/ipd-studio, the layout `cmake --install` and the .deb give), else in the source tree the
// binary was built from. One look-up for every data file: the font of the figures, of the studio and of `ipd`.
#pragma once

#include <string>

namespace ipd {

// The path of `relative` (e.g. "fonts/DejaVuSans.ttf") in the installed data directory or in `source_dir`;
// empty when neither has it.
std::string find_data_file(const std::string& relative, const std::string& source_dir);

}  // namespace ipd
