// `ipd demo OUT_DIR`: writes the built-in demo study.
#include <fmt/format.h>

#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "core/demo/demo_study.h"

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
