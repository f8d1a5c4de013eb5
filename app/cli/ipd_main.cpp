// `ipd`: the command-line face of IPD Studio. Thin: parsing and printing; the work is in core/.
#include <fmt/format.h>

#include <exception>
#include <vector>

#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "core/util/version.h"

namespace {

// A command (or a figure's kind) that is not one is named, with the ones there are: CLI11 only said "A
// subcommand is required", or took a later word for the command ("ipd tabel demo" ran `ipd demo`). Only the
// words before the first option are looked at.
bool unknown_command(const CLI::App& app, int argc, char** argv) {
  const CLI::App* at = &app;
  for (int k = 1; k < argc && argv[k][0] != '-' && at->get_require_subcommand_min() > 0; ++k) {
    const CLI::App* next = nullptr;
    std::string names;
    for (const CLI::App* sub : at->get_subcommands([](const CLI::App*) { return true; })) {
      if (sub->check_name(argv[k])) next = sub;
      names += (names.empty() ? "" : ", ") + sub->get_name();
    }
    if (!next) {
      fmt::print(stderr, "error: '{}' is not a command of {}; expected one of: {}\n", argv[k],
                 at == &app ? std::string("ipd") : "ipd " + at->get_name(), names);
      return true;
    }
    at = next;
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"ipd: Instance Performance Difference of real vs synthetic camera images"};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "Show help for every subcommand");
  app.set_version_flag("--version", std::string("ipd ") + ipd::version(), "Print the version and exit");
  std::vector<std::pair<CLI::App*, ipd::cli::Runner>> runners;
  auto add = [&](ipd::cli::Runner (*adder)(CLI::App&)) {
    const size_t before = app.get_subcommands({}).size();
    auto run = adder(app);
    runners.emplace_back(app.get_subcommands({})[before], std::move(run));
  };
  add(ipd::cli::add_table_command);
  add(ipd::cli::add_register_command);
  add(ipd::cli::add_demo_command);
  add(ipd::cli::add_figure_command);
  add(ipd::cli::add_bench_command);
  add(ipd::cli::add_detect_command);
  add(ipd::cli::add_import_command);
  add(ipd::cli::add_compare_command);
  add(ipd::cli::add_rank_command);
  add(ipd::cli::add_breakdown_command);
  add(ipd::cli::add_export_command);
  add(ipd::cli::add_metrics_command);
  if (unknown_command(app, argc, argv)) return ipd::cli::kUsage;
  try {
    if (argc > 0) app.name(argv[0]);
    std::vector<std::string> args = ipd::cli::join_optional_values(argc, argv);
    app.parse(args);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return ipd::cli::kUsage;
  }
  try {
    for (auto& [sub, run] : runners)
      if (sub->parsed()) return run();
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return ipd::cli::kUsage;
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return ipd::cli::kBadInput;
  }
  return ipd::cli::kUsage;
}
