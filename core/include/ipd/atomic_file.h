// Writing files so that a reader (or a killed process) never sees half of one: temp file, fsync, rename.
#pragma once

#include <stdexcept>
#include <string>

namespace ipd {

struct IoError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Replaces `path` with `contents` atomically; creates parent directories. Throws IoError naming the file.
void write_file_atomically(const std::string& path, const std::string& contents);

// Reads a whole file; throws IoError naming the file and the reason.
std::string read_file(const std::string& path);

}  // namespace ipd
