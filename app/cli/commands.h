// The subcommands of `ipd`; each adds itself to the CLI11 app and runs when chosen.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <memory>
#include <string>

namespace ipd::cli {

// Each returns the function to run when its subcommand was chosen (returning the exit code).
using Runner = std::function<int()>;
Runner add_table_command(CLI::App& app);
Runner add_register_command(CLI::App& app);
Runner add_demo_command(CLI::App& app);
Runner add_figure_command(CLI::App& app);
// `ipd figure table|compare|distribution|breakdown`, added under `figure`; runs the one `which` names.
Runner add_figure_stats_commands(CLI::App* figure, std::shared_ptr<std::string> which);
// `ipd figure sweep` (cmd_figure_sweep.cpp), added under `figure`; runs when `which` is "sweep".
Runner add_figure_sweep_command(CLI::App* figure, std::shared_ptr<std::string> which);
Runner add_bench_command(CLI::App& app);
Runner add_detect_command(CLI::App& app);
Runner add_import_command(CLI::App& app);
Runner add_compare_command(CLI::App& app);
Runner add_rank_command(CLI::App& app);
Runner add_breakdown_command(CLI::App& app);
Runner add_export_command(CLI::App& app);
Runner add_metrics_command(CLI::App& app);
// `ipd bench edits` (app/bench/bench_edits.cpp), added under `ipd bench`.
Runner add_bench_edits(CLI::App* bench);
// `ipd bench bootstrap` (app/bench/bench_bootstrap.cpp), added under `ipd bench`.
Runner add_bench_bootstrap(CLI::App* bench);
// `ipd bench study` (app/bench/bench_study.cpp), added under `ipd bench`.
Runner add_bench_study(CLI::App* bench);
// `ipd bench budget` (app/bench/bench_budget.cpp), added under `ipd bench`.
Runner add_bench_budget(CLI::App* bench);
// `ipd bench rank` (app/bench/bench_rank.cpp), added under `ipd bench`.
Runner add_bench_rank(CLI::App* bench);

}  // namespace ipd::cli
