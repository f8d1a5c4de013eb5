// `ipd demo OUT_DIR`: writes the built-in demo study.
#include <fmt/format.h>

#include <filesystem>
#include <system_error>

#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "core/demo/demo_study.h"
#include "core/demo/variant_study.h"

namespace fs = std::filesystem;

namespace ipd::cli {

Runner add_demo_command(CLI::App& app) {
  struct Args {
    std::string out;
    std::uint64_t seed = 7;
    DemoStudyOptions options;
    int variants = 0;
    std::string task = "detect";
    CLI::Option* scenes = nullptr;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("demo", "Write the built-in demo study (generated pictures, labels, predictions)");
  cmd->add_option("OUT_DIR", args->out, "Directory to write the study into")->required();
  cmd->add_option("--seed", args->seed, "Generator seed (the same seed gives the same study)")->check(seed_validator());
  args->scenes = cmd->add_option("--scenes", args->options.scenes, "Scenes per domain (default 6; 40 with --variants)")
                     ->check(CLI::Range(1, 10000));
  cmd->add_option("--width", args->options.width, "Picture width")->check(CLI::Range(64, 10000));
  cmd->add_option("--height", args->options.height, "Picture height")->check(CLI::Range(64, 10000));
  cmd->add_option("--rocks", args->options.max_rocks, "Most rocks per scene (a benchmark setting)")
      ->check(CLI::Range(3, 500));
  cmd->add_flag("--labels-only", args->options.labels_only,
                "No pictures: GT from the scene geometry and synthetic predictions (fast; for 10,000-scene studies)");
  cmd->add_option("--variants", args->variants,
                  "Write the variants demo instead: the reference 'real' and N renderings along the shading's ambient "
                  "term, whose true best is known (labels only; for ipd rank and ipd figure sweep)")
      ->check(CLI::Range(2, 98));
  cmd->add_option("--task", args->task,
                  "detect (boxes) or segment: outlines as GT (the drawn rocks) and predictions (the detector's "
                  "contours), task: segment in study.yaml")
      ->check(CLI::IsMember({"detect", "segment"}));
  return [args]() -> int {
    if (args->task == "segment" && (args->options.labels_only || args->variants > 0)) {
      fmt::print(stderr,
                 "error: --task segment writes the pictured demo (its predictions are the detector's "
                 "contours): not with --labels-only or --variants\n");
      return kBadInput;
    }
    args->options.segment = args->task == "segment";
    // A new study only: written over an existing one, its hand pairs and review marks would stay and mix with the
    // new labels (and the tour's numbers would not be the demo's).
    std::error_code ec;
    const bool exists = fs::exists(args->out, ec);
    if (ec || (exists && (!fs::is_directory(args->out, ec) || !fs::is_empty(args->out, ec) || ec))) {
      fmt::print(stderr, "error: {}: {}; ipd demo writes a new study into an empty or new directory\n", args->out,
                 ec ? "cannot be read (" + ec.message() + ")" : "already exists and is not an empty directory");
      return kBadInput;
    }
    if (args->variants > 0) {
      VariantStudyOptions v;
      v.variants = args->variants;
      if (args->scenes->count() > 0) v.scenes = args->options.scenes;
      v.seed = args->seed;
      v.width = args->options.width;
      v.height = args->options.height;
      v.max_rocks = args->options.max_rocks;
      v.min_rocks = std::min(v.min_rocks, v.max_rocks);
      write_variant_study(args->out, v);
      fmt::print("wrote the variants demo to {}: real and {} settings of the ambient term; the true best is {}\n",
                 args->out, v.variants, variant_domain(v, true_best_variant(v)));
      return kOk;
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
