// Helpers for tests: temporary directories, writing files, running the CLI.
#pragma once

#include <string>
#include <vector>

#include "core/geometry/geometry.h"

namespace ipd::test {

// A class-0 box centred at (cx, cy), w x h, in normalised image coordinates.
inline Box box(double cx, double cy, double w, double h, double conf = 1.0) { return Box{0, cx, cy, w, h, conf}; }

// A fresh directory under the system temp dir, removed when the object dies.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  const std::string& path() const { return path_; }
  std::string operator/(const std::string& rel) const { return path_ + "/" + rel; }

 private:
  std::string path_;
};

void write_text(const std::string& path, const std::string& text);

// Seven rocks of distinct sizes spread over the picture, shifted right by `dx`: a registration with one clear
// answer, for the cache tests.
std::vector<Box> seven_rocks(double dx);

// A one-scene study of two rocks listed in the other order in `synth` (automatic pairs (0, 1), (1, 0)), with
// predictions of a model `det` on both sides.
void write_two_rock_study(const TempDir& d);

// Two scenes (s1, s2) of four rocks of different sizes at the same places in `real` and `synth`; s1's hand
// pairs cross rocks 2 and 3 (0-based), which makes [2, 3] and [3, 2] suspect pairs. For the review marks.
void write_review_study(const TempDir& d);

// parse_study_config's message for `yaml` read as "study.yaml", or "no error" when it is accepted.
std::string study_yaml_error(const std::string& yaml);
// open_study(root)'s StudyError message, or "no error" when the study opens.
std::string open_study_error(const std::string& root);

struct CommandResult {
  int exit_code = -1;
  std::string out, err;
};
// Runs the built `ipd` with the given argument string (shell-quoted by the caller).
CommandResult run_ipd(const std::string& args);
// Runs a shell command line (e.g. poppler's pdftotext), capturing its output.
CommandResult run_command(const std::string& command);
// The same, killed after `seconds` (exit code 124): for inputs that could hang.
CommandResult run_ipd_with_timeout(const std::string& args, int seconds);

}  // namespace ipd::test
