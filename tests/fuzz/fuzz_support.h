// Shared by the fuzzers: a scratch directory, and what counts as a bug besides a crash, a sanitizer report,
// a hang or an exception that escapes (libFuzzer reports all of those): an error message that doesn't name
// its file, or that grows with the input (a 10 MB token must not become a 10 MB message).
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace ipd_fuzz {

// Longest acceptable message beyond the file names it quotes.
constexpr size_t kMaxMessage = 1000;

[[noreturn]] inline void fail(const char* what, const std::string& message) {
  std::fprintf(stderr, "fuzz invariant broken: %s: %.400s%s\n", what, message.c_str(),
               message.size() > 400 ? "..." : "");
  std::abort();
}

// Checks an error message: names `file`, and stays short.
inline void check_message(const std::string& message, const std::string& file) {
  if (message.find(file) == std::string::npos) fail("the error does not name the file", message);
  if (message.size() > kMaxMessage + 2 * file.size()) fail("the error message grows with the input", message);
}

// A per-process scratch directory, removed at exit.
inline const std::filesystem::path& scratch_dir() {
  static const std::filesystem::path dir = [] {
    const char* tmp = std::getenv("TMPDIR");
    std::filesystem::path d =
        std::filesystem::path(tmp && *tmp ? tmp : "/tmp") / ("ipd-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(scratch_dir(), ec);
    });
    return d;
  }();
  return dir;
}

inline void write_bytes(const std::filesystem::path& path, const uint8_t* data, size_t size) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out) fail("can't write the scratch file", path.string());
}

}  // namespace ipd_fuzz
