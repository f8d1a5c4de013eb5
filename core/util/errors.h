// The project's error types, in one place. Each message is one sentence that names the file (and line
// when known) and says what was expected; the CLI prints it after "error: " and exits 1.
#pragma once

#include <stdexcept>
#include <string>

namespace ipd {

// A file that can't be read, written, replaced or removed (or isn't a regular file).
struct IoError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A study that can't be used: bad study.yaml, bad pairs file, unreadable directory.
struct StudyError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A detector model (ONNX) that can't be loaded or has an unexpected layout.
struct ModelError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace ipd
