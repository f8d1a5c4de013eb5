// The product's version: CMake's project(VERSION), the version of the .deb. `ipd --version` and
// `ipd-studio --version` print it, and caches key on it so that a new release never serves an old one's answers.
#pragma once

namespace ipd {

// "MAJOR.MINOR.PATCH", e.g. "0.1.0".
const char* version();

}  // namespace ipd
