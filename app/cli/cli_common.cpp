#include "app/cli/cli_common.h"

#include <unistd.h>

#include <fmt/format.h>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <set>

#include <cstdlib>

#include "core/util/number_text.h"
#include "core/util/study_inputs.h"

namespace ipd::cli {

std::vector<std::string> join_optional_values(int argc, char** argv) {
  std::vector<std::string> args;
  for (int k = 1; k < argc; ++k) {
    std::string a = argv[k];
    if (a == "--ci" && k + 1 < argc) {
      const std::string next = argv[k + 1];
      char* end = nullptr;
      std::strtod(next.c_str(), &end);
      if (!next.empty() && end == next.c_str() + next.size()) a += "=" + next, ++k;
    }
    args.push_back(std::move(a));
  }
  return {args.rbegin(), args.rend()};
}

CLI::Validator seed_validator() {
  return CLI::Validator(
      [](std::string& s) {
        std::uint64_t seed = 0;
        return parse_seed(s, &seed) ? std::string() : std::string("must be ") + kSeedRange + ", got " + s;
      },
      "SEED in [0, 2^64 - 1]", "seed");
}

bool output_is_study_input(const std::string& study, const std::string& out) {
  if (out.empty()) return false;
  const std::string problem = study_input_problem(study, out);
  if (!problem.empty()) fmt::print(stderr, "error: {}\n", problem);
  return !problem.empty();
}

void report_class_notes(const StudyLabels& labels) {
  for (const std::string& n : labels.study.classes.notes) fmt::print(stderr, "note: {}\n", n);
  for (const std::string& w : labels.class_warnings) fmt::print(stderr, "warning: {}\n", w);
  if (!labels.task_note.empty()) fmt::print(stderr, "note: {}\n", labels.task_note);
}

bool report_label_errors(const std::vector<LabelError>& errors, bool skip_bad_lines) {
  if (errors.empty()) return false;
  // A file that can't be read (dangling link, no permission, a FIFO) is never skipped: its rocks would
  // silently count as none.
  const bool file_problems =
      std::any_of(errors.begin(), errors.end(), [](const LabelError& e) { return e.unusable_file(); });
  long lines = 0;
  for (const auto& e : errors) {
    lines += e.malformed_lines();
    const bool warn = skip_bad_lines && e.malformed_lines() > 0;
    fmt::print(stderr, "{}{}\n", warn ? "warning: " : "", e.to_string());
  }
  // A run saved without confidences fails every line the same way: said once per folder, with the way out.
  std::set<std::string> runs_without_conf;
  for (const auto& e : errors)
    if (e.message.rfind("expected 6 columns (class cx cy w h conf), found 5", 0) == 0 &&
        runs_without_conf.insert(std::filesystem::path(e.file).parent_path().string()).second)
      fmt::print(stderr,
                 "{}/: its lines have no confidence column, as a YOLO run saved without it; run the detector again "
                 "with it (yolov5 detect.py --save-txt --save-conf, yolo predict save_txt=True save_conf=True), or "
                 "bring the run in with ipd import predictions RUN --out STUDY/<domain> --model M --no-conf "
                 "(docs/import.md)\n",
                 std::filesystem::path(e.file).parent_path().string());
  if (file_problems) return true;
  if (skip_bad_lines) {
    fmt::print(stderr, "warning: {} malformed line(s) skipped (--skip-bad-lines)\n", lines);
    return false;
  }
  fmt::print(stderr, "error: {} malformed line(s); fix them, or pass --skip-bad-lines to skip them\n", lines);
  return true;
}

bool report_unusable_pairs(const std::vector<PairsProblem>& problems, bool skip_bad_lines,
                           std::vector<std::string>* warnings) {
  int unusable = 0;
  for (const auto& p : problems) {
    if (!p.unusable) continue;
    ++unusable;
    if (!skip_bad_lines)
      fmt::print(stderr, "{}\n", p.to_string());
    else if (warnings)
      warnings->push_back(p.to_string());
    else
      fmt::print(stderr, "warning: {}\n", p.to_string());
  }
  if (unusable == 0 || skip_bad_lines) return false;
  fmt::print(stderr,
             "error: the hand pairs of {} scene(s) can't be used; pair those scenes again, or pass --skip-bad-lines "
             "to use registration for them\n",
             unusable);
  return true;
}

bool report_layout_problems(const std::vector<LayoutProblem>& problems, bool skip_bad_lines,
                            std::vector<std::string>* warnings) {
  bool stop = false;
  for (const LayoutProblem& p : problems) {
    if (p.removes_most && !skip_bad_lines) {
      fmt::print(stderr, "error: {}\n", p.message);
      stop = true;
    } else {
      warnings->push_back(p.message);
    }
  }
  if (stop)
    fmt::print(stderr,
               "error: the numbers would leave out most of the study's scenes or rocks; fix the layout, or pass "
               "--skip-bad-lines to print them anyway\n");
  return stop;
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
