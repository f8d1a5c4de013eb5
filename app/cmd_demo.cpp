// `ipd demo OUT_DIR`: writes the built-in demo study.
#include <fmt/format.h>

#include "cli_common.h"
#include "commands.h"
#include "ipd/demo_study.h"

namespace ipd::cli {

Runner add_demo_command(CLI::App& app) {
  struct Args {
    std::string out;
    std::uint64_t seed = 7;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("demo", "Write the built-in demo study (generated pictures, labels, predictions)");
  cmd->add_option("OUT_DIR", args->out, "Directory to write the study into")->required();
  cmd->add_option("--seed", args->seed, "Generator seed (the same seed gives the same study)");
  return [args]() -> int {
    DemoStudyOptions o;
    o.seed = args->seed;
    write_demo_study(args->out, o);
    fmt::print("wrote the demo study to {}\n", args->out);
    return kOk;
  };
}

}  // namespace ipd::cli
