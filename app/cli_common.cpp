#include "cli_common.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fmt/format.h>

namespace ipd::cli {

bool report_label_errors(const std::vector<LabelError>& errors, bool skip_bad_lines) {
  if (errors.empty()) return false;
  for (const auto& e : errors) fmt::print(stderr, "{}{}\n", skip_bad_lines ? "warning: " : "", e.to_string());
  const auto lines = std::count_if(errors.begin(), errors.end(), [](const LabelError& e) { return e.line > 0; });
  if (lines == 0) return !skip_bad_lines;  // whole-file problems speak for themselves
  if (skip_bad_lines) {
    fmt::print(stderr, "warning: {} malformed line(s) skipped (--skip-bad-lines)\n", lines);
    return false;
  }
  fmt::print(stderr, "error: {} malformed line(s); fix them, or pass --skip-bad-lines to skip them\n", lines);
  return true;
}

Progress::Progress(std::string what) : what_(std::move(what)), tty_(::isatty(2) == 1) {}

void Progress::update(int done, int total) {
  if (!tty_ || total <= 0) return;
  fmt::print(stderr, "\r{} {}/{} ({:.0f}%)", what_, done, total, 100.0 * done / total);
  std::fflush(stderr);
  shown_ = true;
}

Progress::~Progress() {
  if (shown_) fmt::print(stderr, "\n");
}

}  // namespace ipd::cli
