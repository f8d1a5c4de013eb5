#include "tests/support/test_support.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/study/study.h"

namespace fs = std::filesystem;

namespace ipd::test {

TempDir::TempDir() {
  std::string tmpl = (fs::temp_directory_path() / "ipd-test-XXXXXX").string();
  path_ = ::mkdtemp(tmpl.data());
}

TempDir::~TempDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

void write_text(const std::string& path, const std::string& text) {
  fs::create_directories(fs::path(path).parent_path());
  std::ofstream(path) << text;
}

static std::string slurp(const std::string& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

CommandResult run_ipd_with_timeout(const std::string& args, int seconds) {
  return run_command("timeout " + std::to_string(seconds) + " " + std::string(IPD_BINARY) + " " + args);
}

CommandResult run_ipd(const std::string& args) { return run_command(std::string(IPD_BINARY) + " " + args); }

CommandResult run_command(const std::string& command) {
  TempDir io;
  const std::string cmd = command + " >" + io.path() + "/out 2>" + io.path() + "/err";
  const int status = std::system(cmd.c_str());
  CommandResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(io.path() + "/out");
  r.err = slurp(io.path() + "/err");
  return r;
}

std::vector<Box> seven_rocks(double dx) {
  std::vector<Box> out;
  const double xs[] = {0.1, 0.35, 0.6, 0.8, 0.2, 0.5, 0.75};
  const double ys[] = {0.2, 0.15, 0.3, 0.6, 0.7, 0.5, 0.85};
  for (int k = 0; k < 7; ++k) out.push_back(Box{0, xs[k] + dx, ys[k], 0.04 + 0.005 * k, 0.05, 1.0});
  return out;
}

void write_two_rock_study(const TempDir& d) {
  write_text(d / "real/labels/s1.txt", "0 0.2 0.2 0.1 0.1\n0 0.6 0.6 0.1 0.1\n");
  write_text(d / "synth/labels/s1.txt", "0 0.6 0.6 0.1 0.1\n0 0.2 0.2 0.1 0.1\n");
  write_text(d / "real/predictions/det/s1.txt", "0 0.2 0.2 0.1 0.1 0.9\n");
  write_text(d / "synth/predictions/det/s1.txt", "0 0.25 0.2 0.1 0.1 0.8\n");
}

// Two scenes of four rocks of different sizes at the same places in both domains (registration pairs k
// with k). Scene s1's hand pairs cross rocks 2 and 3: two suspect pairs ([2, 3] and [3, 2], no overlap).
std::string study_yaml_error(const std::string& yaml) {
  try {
    parse_study_config(yaml, "study.yaml");
  } catch (const StudyError& e) {
    return e.what();
  }
  return "no error";
}

std::string open_study_error(const std::string& root) {
  try {
    open_study(root);
  } catch (const StudyError& e) {
    return e.what();
  }
  return "no error";
}

void write_review_study(const TempDir& d) {
  const std::string rocks = "0 0.2 0.2 0.1 0.08\n0 0.8 0.25 0.06 0.06\n0 0.3 0.8 0.12 0.1\n0 0.75 0.7 0.08 0.12\n";
  for (const char* stem : {"s1", "s2"})
    for (const char* domain : {"real", "synth"}) {
      write_text(d / (std::string(domain) + "/labels/" + stem + ".txt"), rocks);
      write_text(d / (std::string(domain) + "/predictions/det/" + stem + ".txt"), "0 0.2 0.2 0.1 0.1 0.9\n");
    }
  write_text(d / "pairs/real__synth/s1.json",
             "{\"pairs\": [[0, 0], [1, 1], [2, 3], [3, 2]], \"rocks_a\": [[0, 0.2, 0.2, 0.1, 0.08], [1, 0.8, "
             "0.25, 0.06, 0.06], [2, 0.3, 0.8, 0.12, 0.1], [3, 0.75, 0.7, 0.08, 0.12]], "
             "\"rocks_b\": [[0, 0.2, 0.2, 0.1, 0.08], [1, 0.8, 0.25, 0.06, 0.06], [2, 0.3, 0.8, 0.12, 0.1], [3, "
             "0.75, 0.7, 0.08, 0.12]]}\n");
  write_text(d / "study.yaml", "image_size: [1000, 1000]\n");  // square pictures, said so
}

}  // namespace ipd::test
