// Shared modules of ours that a program opens (dlopen) on first use instead of linking the libraries behind
// them: OpenCV's picture codecs pull in GDAL and about 140 libraries, which every `ipd` run would otherwise
// map and relocate at start-up, whether or not it reads a picture.
#pragma once

#include <string>

namespace ipd {

// Opens the module `file_name` (e.g. "ipd_picture_codecs.so") once and returns its handle. It is looked for
// where an installed program has it (PREFIX/lib/ipd-studio, found from the executable's directory), next to
// the executable (the build tree's app/), then in the build tree the program was built from (the tests run
// from build/tests/). Throws std::runtime_error naming the module, the places looked at and the loader's
// reason when none can be opened.
void* open_module(const std::string& file_name);

// The address of `symbol` in a module open_module() returned; throws std::runtime_error when it has none.
void* module_symbol(void* module, const std::string& file_name, const char* symbol);

}  // namespace ipd
