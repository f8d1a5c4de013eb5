// `ipd bench bootstrap`: what the scene-bootstrap intervals add to `ipd table` on a large study
// (default 10,000 scenes × 9 cells — the demo's 3 models × 3 domain pairs — × 2,000 resamples).
#include <fmt/format.h>

#include <chrono>
#include <random>
#include <thread>

#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "core/stats/study_statistics.h"

namespace ipd::cli {

Runner add_bench_bootstrap(CLI::App* bench) {
  struct Args {
    int scenes = 10000, cells = 9, resamples = 2000, threads = 0;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = bench->add_subcommand("bootstrap", "Time of the scene-bootstrap intervals of a large cross table");
  cmd->add_option("--scenes", args->scenes, "Scenes per cell")->check(CLI::Range(1, 10000000));
  cmd->add_option("--cells", args->cells, "Cells of the table")->check(CLI::Range(1, 1000));
  cmd->add_option("--resamples", args->resamples, "Bootstrap resamples")->check(CLI::Range(1, 1000000));
  cmd->add_option("--threads", args->threads, "Threads (0: every core)")->check(CLI::NonNegativeNumber);
  return [args]() -> int {
    // Synthetic per-scene sums: 5-30 pairs per scene, |diff| about 0.1 each.
    CrossTable table;
    std::mt19937_64 gen(1);
    std::uniform_int_distribution<int> pairs(5, 30);
    std::uniform_real_distribution<double> diff(0.0, 0.2);
    for (int c = 0; c < args->cells; ++c) {
      TableCell cell;
      cell.model = fmt::format("model{}", c / 3);
      cell.a = "a";
      cell.b = fmt::format("b{}", c);
      for (int s = 0; s < args->scenes; ++s) {
        SceneIpd si;
        si.pairs = pairs(gen);
        si.sum_abs_diff = si.pairs * diff(gen);
        cell.pairs += si.pairs;
        cell.per_scene.push_back(std::move(si));
      }
      cell.scenes = args->scenes;
      table.cells.push_back(std::move(cell));
    }
    BootstrapOptions o;
    o.resamples = args->resamples;
    const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
    const int threads = args->threads > 0 ? args->threads : static_cast<int>(hw);
    double best = 1e300;
    for (int run = 0; run < 3; ++run) {
      const auto t0 = std::chrono::steady_clock::now();
      add_confidence_intervals(&table, o, threads);
      best = std::min(best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
    const double draws = static_cast<double>(args->scenes) * args->cells * args->resamples;
    fmt::print(
        "{} scenes x {} cells x {} resamples ({:.2g} scene draws), {} threads: {:.0f} ms (best of 3), "
        "{:.2f} ns per draw\n",
        args->scenes, args->cells, args->resamples, draws, threads, best, best * 1e6 / draws);
    fmt::print("cell 0: IPD {:.4f} [{:.4f}, {:.4f}]\n",
               table.cells[0].per_scene.empty() ? 0.0 : pooled_mean(scene_sums(table.cells[0])), table.cells[0].ci_low,
               table.cells[0].ci_high);
    return kOk;
  };
}

}  // namespace ipd::cli
