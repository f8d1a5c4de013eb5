// Shared bits of the `ipd` subcommands: exit codes, error reporting, progress.
#pragma once

#include <string>
#include <vector>

#include "ipd/ipd.h"

namespace ipd::cli {

constexpr int kOk = 0, kBadInput = 1, kUsage = 2;

// Prints the label errors (`FILE:LINE: ...`, at most kMaxListedErrors per file and a count of the rest) and a
// summary; true when they are fatal: malformed lines unless skipped, and always a file that can't be read.
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
