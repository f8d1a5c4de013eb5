// `ipd bench rank`: what a ranking of many renderer settings costs against one domain pair's table. On a
// generated variants study (core/demo/variant_study.h; default 1 reference + 24 variants x 1,000 scenes x 30
// rocks) it times, each as a child `ipd` process of its own: `ipd table` of one (reference, variant) pair with
// empty caches; the first `ipd rank` over every variant with empty caches; and `ipd rank` again after a 25th
// variant is added (the caches of the first run in place), which registers only the new one. One pair's table is
// timed in a study of that pair alone and in the variants study (where it parses every domain's label files).
#include <fmt/format.h>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "core/demo/variant_study.h"
#include "core/util/atomic_file.h"

namespace fs = std::filesystem;

namespace ipd::cli {

namespace {

struct RankBenchOptions {
  int variants = 24, scenes = 1000, rocks = 30, threads = 0;
};

// Runs this program with `args` (stdout to /dev/null); returns the wall time in ms. Throws when it fails.
double time_child(const std::vector<std::string>& args) {
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("bench rank: fork failed");
  if (pid == 0) {
    // Quiet: the ranking's notes go to stderr too; a failure is said below with its command.
    const int null = ::open("/dev/null", O_WRONLY);
    if (null >= 0) ::dup2(null, 1), ::dup2(null, 2);
    std::vector<char*> argv;
    static std::string self = "/proc/self/exe";
    argv.push_back(self.data());
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv("/proc/self/exe", argv.data());
    ::_exit(127);
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw std::runtime_error("bench rank: waitpid failed");
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::string line;
    for (const auto& a : args) line += " " + a;
    throw std::runtime_error("bench rank: `ipd" + line + "` failed");
  }
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

int run_rank_bench(const RankBenchOptions& o) {
  std::string pattern = (fs::temp_directory_path() / "ipd-bench-rank-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("bench rank: mkdtemp failed");
  const fs::path scratch = pattern, study = scratch / "study", held = scratch / "held";
  struct Cleanup {
    fs::path p;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(p, ec);
    }
  } cleanup{scratch};
  VariantStudyOptions v;
  v.variants = o.variants + 1;
  v.scenes = o.scenes;
  v.min_rocks = v.max_rocks = o.rocks;
  fmt::print("writing 1 reference + {} variants x {} scenes x {} rocks ...\n", v.variants, o.scenes, o.rocks);
  std::fflush(stdout);
  write_variant_study(study.string(), v);
  // The last variant waits outside the study until the re-run.
  const std::string added = variant_domain(v, v.variants - 1);
  fs::create_directories(held);
  fs::rename(study / added, held / added);
  write_file_atomically((study / "study.yaml").string(), variant_study_yaml(v, o.variants));
  const std::string threads = std::to_string(o.threads);
  const std::string first = variant_domain(v, 0);
  // One pair's table twice: in a study of that pair alone, and in the variants study (which parses every
  // domain's label files, whatever --domains chooses).
  const fs::path pair = scratch / "pair";
  fs::create_directories(pair);
  for (const std::string& d : {std::string("real"), first}) fs::copy(study / d, pair / d, fs::copy_options::recursive);
  write_file_atomically((pair / "study.yaml").string(), variant_study_yaml(v, 1));
  const double pair_ms =
      time_child({"table", pair.string(), "--model", "det-real", "--domains", "real," + first, "--threads", threads});
  const double table_ms =
      time_child({"table", study.string(), "--model", "det-real", "--domains", "real," + first, "--threads", threads});
  fs::remove_all(study / ".ipd-cache");  // the ranking starts from empty caches too
  const std::vector<std::string> rank = {"rank",     study.string(), "--ref", "real",      "--model",
                                         "det-real", "--format",     "json",  "--threads", threads};
  const double first_ms = time_child(rank);
  fs::rename(held / added, study / added);
  write_file_atomically((study / "study.yaml").string(), variant_study_yaml(v, v.variants));
  const double rerun_ms = time_child(rank);
  fmt::print("{:<64} {:>9} {:>13} {:>13}\n", "run", "ms", "x pair alone", "x pair in it");
  auto row = [&](const std::string& what, double ms) {
    fmt::print("{:<64} {:>9.0f} {:>13.2f} {:>13.2f}\n", what, ms, ms / pair_ms, ms / table_ms);
  };
  row(fmt::format("ipd table (real, {}), a study of that pair alone, empty caches", first), pair_ms);
  row(fmt::format("ipd table (real, {}) in the variants study, empty caches", first), table_ms);
  row(fmt::format("ipd rank, first, {} variants, empty caches", o.variants), first_ms);
  row(fmt::format("ipd rank, re-run after adding {}", added), rerun_ms);
  fmt::print("(targets: first rank <= 25x one pair, re-run <= 2x; threads {}, wall time of each child process)\n",
             o.threads == 0 ? std::string("every core") : threads);
  return kOk;
}

}  // namespace

Runner add_bench_rank(CLI::App* bench) {
  auto o = std::make_shared<RankBenchOptions>();
  CLI::App* cmd = bench->add_subcommand(
      "rank", "A ranking of many variants against one pair's table: first run, and re-run after adding one");
  cmd->add_option("--variants", o->variants, "Variants in the first ranking (one more is added)")
      ->check(CLI::Range(1, 97));
  cmd->add_option("--scenes", o->scenes, "Scenes per domain")->check(CLI::Range(1, 10000));
  cmd->add_option("--rocks", o->rocks, "Rocks per scene")->check(CLI::Range(1, 500));
  cmd->add_option("--threads", o->threads, "Worker threads of each run (0: every core)")->check(CLI::NonNegativeNumber);
  return [o]() -> int { return run_rank_bench(*o); };
}

}  // namespace ipd::cli
