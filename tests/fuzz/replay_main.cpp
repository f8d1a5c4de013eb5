// Runs a fuzzer's entry point over files and directories without libFuzzer: the regular and the sanitizer
// builds replay the committed corpus as a ctest test (FuzzCorpus.<fuzzer>).
//   <fuzzer>_replay [--known-failure=NAME]... FILE_OR_DIR...
// A known failure (FUZZER/FILE, a corpus file that still crashes, waiting for its fix) runs in a child process and is
// reported, not counted; when it passes, the replay says so, so that it can be taken off the list.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

std::string read_all(const std::filesystem::path& f) {
  std::ifstream in(f, std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "%s: can't read\n", f.c_str());
    std::exit(1);
  }
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void run(const std::string& bytes) {
  LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
}

}  // namespace

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  std::vector<fs::path> files;
  std::set<std::string> known;
  const std::string known_flag = "--known-failure=";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind(known_flag, 0) == 0) {
      known.insert(arg.substr(known_flag.size()));
    } else if (fs::is_directory(arg)) {
      for (const auto& e : fs::directory_iterator(arg))
        if (e.is_regular_file()) files.push_back(e.path());
    } else {
      files.emplace_back(arg);
    }
  }
  std::sort(files.begin(), files.end());
  size_t replayed = 0, still_failing = 0;
  for (const fs::path& f : files) {
    const std::string bytes = read_all(f);
    if (known.count((f.parent_path().filename() / f.filename()).string())) {
      std::fflush(nullptr);
      const pid_t child = fork();
      if (child == 0) {
        run(bytes);
        std::_Exit(0);
      }
      int status = 0;
      waitpid(child, &status, 0);
      const bool passes = WIFEXITED(status) && WEXITSTATUS(status) == 0;
      std::printf("%s: known failure %s\n", f.c_str(),
                  passes ? "NOW PASSES: take it off tests/fuzz/known_failures.txt" : "still fails (not counted)");
      still_failing += !passes;
      continue;
    }
    std::fprintf(stderr, "%s (%zu bytes)\n", f.c_str(), bytes.size());
    run(bytes);
    ++replayed;
  }
  std::printf("replayed %zu inputs, %zu known failures still failing\n", replayed, still_failing);
  return replayed == 0 ? 1 : 0;
}
