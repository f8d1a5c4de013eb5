// `ipd bench study STUDY`: where `ipd table`'s time goes on a study -- parse, register, cache write, IPD,
// bootstrap -- without caches, on the first run that writes them, and on a warm run that reads them back,
// with each run's peak memory. Every run is a child process (fork), so a run's peak resident size is its
// own (wait4's ru_maxrss) and a warm run can't reuse what an earlier run left in memory.
#include <fmt/format.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "core/ipd/study_cache.h"
#include "core/stats/study_statistics.h"

namespace fs = std::filesystem;

namespace ipd::cli {

namespace {

// The stages of one run, in the order they happen; `total` is the whole run.
constexpr std::array<const char*, 6> kStages = {"parse", "register", "IPD", "cache-write", "bootstrap", "total"};
using StageMs = std::array<double, kStages.size()>;

struct StudyBenchOptions {
  std::string study;
  int threads = 0, resamples = 2000;
};

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// One `ipd table`-like run: caches in `cache_dir` (empty: none).
StageMs run_once(const StudyBenchOptions& o, const std::string& cache_dir) {
  StageMs ms{};
  const auto start = std::chrono::steady_clock::now();
  auto t = start;
  const Study study = open_study(o.study);
  StudyCache parsed(cache_dir.empty() ? std::string() : (fs::path(cache_dir) / "parsed-study.bin").string(),
                    study.root);
  const StudyLabels labels = parsed.load_labels(study);
  ms[0] = ms_since(t);
  t = std::chrono::steady_clock::now();
  RegistrationCache registration(cache_dir.empty() ? std::string() : (fs::path(cache_dir) / "registration").string());
  parsed.hand_registrations_to(registration);
  TableOptions opt;
  opt.threads = o.threads;
  opt.registration = study.config.registration;
  opt.cache_dir = registration.dir();
  opt.registration_cache = &registration;
  CrossTable table = compute_cross_table(labels, opt);
  // compute_cross_table times its registrations (cache reads included); the rest of it is the IPD.
  ms[1] = table.registration_ms;
  ms[2] = std::max(0.0, ms_since(t) - table.registration_ms);
  t = std::chrono::steady_clock::now();
  parsed.save(labels, registration);
  ms[3] = ms_since(t);
  t = std::chrono::steady_clock::now();
  BootstrapOptions bo;
  bo.resamples = o.resamples;
  bo.seed = opt.registration.seed;
  if (bo.resamples > 0) add_confidence_intervals(&table, bo, o.threads);
  ms[4] = ms_since(t);
  ms[5] = ms_since(start);
  return ms;
}

struct ChildRun {
  StageMs ms{};
  long peak_kib = 0;
};

// run_once in a child process: its stage times come back through a pipe, its peak memory from wait4.
ChildRun run_in_child(const StudyBenchOptions& o, const std::string& cache_dir) {
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error("bench study: pipe failed");
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("bench study: fork failed");
  if (pid == 0) {
    close(fds[0]);
    int status = 0;
    try {
      const StageMs ms = run_once(o, cache_dir);
      if (write(fds[1], ms.data(), sizeof ms) != static_cast<ssize_t>(sizeof ms)) status = 2;
    } catch (const std::exception& e) {
      fmt::print(stderr, "error: {}\n", e.what());
      status = 1;
    }
    std::fflush(stderr);
    _exit(status);
  }
  close(fds[1]);
  ChildRun r;
  const ssize_t got = read(fds[0], r.ms.data(), sizeof r.ms);
  close(fds[0]);
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  if (got != static_cast<ssize_t>(sizeof r.ms) || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw StudyError(o.study + ": a benchmark run failed (see the error above)");
  r.peak_kib = usage.ru_maxrss;  // KiB on Linux
  return r;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

// The median of each stage over the runs, and the largest peak memory.
ChildRun summarise(const std::vector<ChildRun>& runs) {
  ChildRun out;
  for (size_t s = 0; s < kStages.size(); ++s) {
    std::vector<double> v;
    for (const ChildRun& r : runs) v.push_back(r.ms[s]);
    out.ms[s] = median(v);
  }
  for (const ChildRun& r : runs) out.peak_kib = std::max(out.peak_kib, r.peak_kib);
  return out;
}

void print_row(const char* mode, const ChildRun& r) {
  fmt::print("{:<9}", mode);
  for (double x : r.ms) fmt::print(" {:>11.1f}", x);
  fmt::print(" {:>9.0f}\n", static_cast<double>(r.peak_kib) / 1024.0);
}

}  // namespace

Runner add_bench_study(CLI::App* bench) {
  struct Args {
    StudyBenchOptions options;
    int runs = 3;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd =
      bench->add_subcommand("study", "Time of each stage of `ipd table` on a study: no cache, first run, warm run");
  cmd->add_option("STUDY", args->options.study, "Study directory")->required();
  cmd->add_option("--runs", args->runs, "Runs of each kind (the median is printed)")->check(CLI::Range(1, 1000));
  cmd->add_option("--threads", args->options.threads, "Threads (0: every core)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--bootstrap", args->options.resamples, "Bootstrap resamples (0: none)")
      ->check(CLI::Range(0, 1000000));
  return [args]() -> int {
    const StudyBenchOptions& o = args->options;
    const Study study = open_study(o.study);  // a bad study fails here, before any child runs
    // The caches go to a fresh folder of their own: the study's and the user's caches stay untouched. mkdtemp
    // makes it with a name nobody can guess or have made first (a fixed name could be a link planted there).
    std::string pattern = (fs::temp_directory_path() / "ipd-bench-study-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr)
      throw StudyError(fmt::format("{}: cannot make a scratch folder: {}", pattern, std::strerror(errno)));
    const fs::path scratch = pattern;
    fmt::print(
        "{}: {} domains, {} models; {} run(s) of each kind, median ms per stage; peak = largest resident "
        "size of a run (MiB)\n",
        study.root, study.domains.size(), study.models.size(), args->runs);
    fmt::print("{:<9}", "run");
    for (const char* s : kStages) fmt::print(" {:>11}", s);
    fmt::print(" {:>9}\n", "peak MiB");
    std::vector<ChildRun> none, first, warm;
    std::string last_cache;
    try {
      for (int i = 0; i < args->runs; ++i) none.push_back(run_in_child(o, {}));
      print_row("no-cache", summarise(none));
      for (int i = 0; i < args->runs; ++i) {
        last_cache = (scratch / fmt::format("first-{}", i)).string();
        fs::create_directories(last_cache);
        first.push_back(run_in_child(o, last_cache));
      }
      print_row("first", summarise(first));
      for (int i = 0; i < args->runs; ++i) warm.push_back(run_in_child(o, last_cache));
      print_row("warm", summarise(warm));
    } catch (...) {
      fs::remove_all(scratch);
      throw;
    }
    fs::remove_all(scratch);
    fmt::print("first / no-cache: {:.2f}x; warm / no-cache: {:.2f}x (total)\n",
               summarise(first).ms[5] / summarise(none).ms[5], summarise(warm).ms[5] / summarise(none).ms[5]);
    return kOk;
  };
}

}  // namespace ipd::cli
