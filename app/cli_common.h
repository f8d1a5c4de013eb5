// Shared bits of the `ipd` subcommands: exit codes, error reporting, progress.
#pragma once

#include <string>
#include <vector>

#include "ipd/ipd.h"

namespace ipd::cli {

constexpr int kOk = 0, kBadInput = 1, kUsage = 2;

// Prints every label error (all of them, `FILE:LINE: ...`) and a summary; true when there were any and
// they are fatal (not skipped).
bool report_label_errors(const std::vector<LabelError>& errors, bool skip_bad_lines);

// A one-line progress indicator on stderr, only when stderr is a terminal.
class Progress {
 public:
  explicit Progress(std::string what);
  void update(int done, int total);
  ~Progress();

 private:
  std::string what_;
  bool tty_;
  bool shown_ = false;
};

}  // namespace ipd::cli
