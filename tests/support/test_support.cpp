#include "tests/support/test_support.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

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

}  // namespace ipd::test
