// Shared bits of the `ipd` subcommands: exit codes, error reporting, progress.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/ipd/ipd.h"
#include "core/ipd/study_layout.h"

namespace ipd::cli {

constexpr int kOk = 0, kBadInput = 1, kUsage = 2;

// Prints the label errors (`FILE:LINE: ...`, at most kMaxListedErrors per file and a count of the rest) and a
// summary; true when they are fatal: malformed lines unless skipped, and always a file that can't be read.
bool report_label_errors(const std::vector<LabelError>& errors, bool skip_bad_lines);
// Prints to stderr, once each, how label sets' class numbers were mapped by name and which prediction sets look
// class-shifted ("note: ..." / "warning: ...").
void report_class_notes(const StudyLabels& labels);

// Hand pairs that can't be used (a stored box is no longer in its label file): printed as errors (true:
// fatal), or with --skip-bad-lines added to `warnings` (printed and in JSON output like the others; null:
// printed as warnings here) while registration counts for those scenes.
bool report_unusable_pairs(const std::vector<PairsProblem>& problems, bool skip_bad_lines,
                           std::vector<std::string>* warnings);
// Layout problems (study_layout.h) that took most of a number's scenes or rocks: printed as errors (true: fatal,
// nothing is printed from such a study), or with --skip-bad-lines added to `warnings` like every other problem.
bool report_layout_problems(const std::vector<LayoutProblem>& problems, bool skip_bad_lines,
                            std::vector<std::string>* warnings);

// The arguments after the program name, reversed (as CLI::App::parse takes them), with `--ci 0.9` joined
// into `--ci=0.9`: --ci is a flag with an optional level, so a level must be attached to it, and a
// following word that is not a number (the STUDY) stays an argument of its own.
std::vector<std::string> join_optional_values(int argc, char** argv);

// For --seed: parse_seed's range (core/util/number_text.h), the same as study.yaml's registration.seed. CLI11
// reads "-5" into an unsigned seed as 2^64 - 5, and 2^64 into a signed one as 2^63 - 1: a different seed without
// a word; "--seed: must be a whole number from 0 to 18446744073709551615, got -5" instead.
CLI::Validator seed_validator();

// Prints "error: PATH: is one of the study's inputs (...)" and returns true when `out` (an --out) is one of
// the study's inputs (core/util/study_inputs.h): said before the work, not after it. write_output_file refuses
// it again when writing, for every caller.
bool output_is_study_input(const std::string& study, const std::string& out);

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

// Leaves `data` to the end of the process instead of freeing it where the command returns: the command has printed
// its last line, and freeing a 10,000-scene study's 120,000 label files one by one costs a tenth of a second that
// the system's release of the process does at once. It stays reachable until then (no leak is reported).
template <typename T>
void keep_until_exit(T&& data) {
  static auto* const kept = new std::vector<std::shared_ptr<void>>();  // never freed: the process's end does it
  kept->push_back(std::make_shared<std::decay_t<T>>(std::forward<T>(data)));
}

}  // namespace ipd::cli
