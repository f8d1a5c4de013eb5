// `ipd demo OUT_DIR`: writes the built-in demo study.
#include <fmt/format.h>

#include <filesystem>
#include <system_error>

#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "core/demo/demo_study.h"

namespace fs = std::filesystem;

namespace ipd::cli {

Runner add_demo_command(CLI::App& app) {
  struct Args {
    std::string out;
    std::uint64_t seed = 7;
    DemoStudyOptions options;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("demo", "Write the built-in demo study (generated pictures, labels, predictions)");
  cmd->add_option("OUT_DIR", args->out, "Directory to write the study into")->required();
  cmd->add_option("--seed", args->seed, "Generator seed (the same seed gives the same study)")->check(seed_validator());
  cmd->add_option("--scenes", args->options.scenes, "Scenes per domain")->check(CLI::Range(1, 10000));
  cmd->add_option("--width", args->options.width, "Picture width")->check(CLI::Range(64, 10000));
  cmd->add_option("--height", args->options.height, "Picture height")->check(CLI::Range(64, 10000));
  cmd->add_option("--rocks", args->options.max_rocks, "Most rocks per scene (a benchmark setting)")
      ->check(CLI::Range(3, 500));
  cmd->add_flag("--labels-only", args->options.labels_only,
                "No pictures: GT from the scene geometry and synthetic predictions (fast; for 10,000-scene studies)");
  return [args]() -> int {
    // A new study only: written over an existing one, its hand pairs and review marks would stay and mix with the
    // new labels (and the tour's numbers would not be the demo's).
    std::error_code ec;
    const bool exists = fs::exists(args->out, ec);
    if (ec || (exists && (!fs::is_directory(args->out, ec) || !fs::is_empty(args->out, ec) || ec))) {
      fmt::print(stderr, "error: {}: {}; ipd demo writes a new study into an empty or new directory\n", args->out,
                 ec ? "cannot be read (" + ec.message() + ")" : "already exists and is not an empty directory");
      return kBadInput;
    }
    DemoStudyOptions o = args->options;
    o.seed = args->seed;
    o.min_rocks = std::min(o.min_rocks, o.max_rocks);
    if (o.max_rocks > 18) o.min_rocks = o.max_rocks;
    write_demo_study(args->out, o);
    fmt::print("wrote the demo study to {}\n", args->out);
    return kOk;
  };
}

}  // namespace ipd::cli
