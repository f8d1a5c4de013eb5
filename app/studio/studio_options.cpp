#include "app/studio/studio_options.h"

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "core/util/version.h"

namespace ipd::studio {

std::string StudioOptions::validate() const {
  if (frames < 1) return fmt::format("frames must be at least 1, got {}", frames);
  if (cycle_step < 1) return fmt::format("cycle_step must be at least 1, got {}", cycle_step);
  if (texture_budget_mb < 16) return fmt::format("texture_budget_mb must be at least 16, got {}", texture_budget_mb);
  if (width < 320 || height < 240)
    return fmt::format("the window must be at least 320 x 240, got {} x {}", width, height);
  return {};
}

void StudioOptions::check() const {
  if (const std::string problem = validate(); !problem.empty())
    throw std::invalid_argument("studio options: " + problem);
}

int parse_studio_options(int argc, char** argv, StudioOptions* o) {
  CLI::App cli{"ipd-studio: inspect and fix rock pairs, IPD live"};
  cli.set_version_flag("--version", std::string("ipd-studio ") + ipd::version(), "Print the version and exit");
  cli.add_option("STUDY", o->study, "Study directory (default: the built-in demo study, generated on first run)");
  cli.add_option("--screenshot", o->screenshot, "Render --frames frames, save the window as this PNG and exit");
  cli.add_option("--frames", o->frames, "Frames to render before the screenshot")->check(CLI::Range(1, 100000));
  cli.add_flag("--frame-stats", o->frame_stats,
               "Print open_ms, frame_ms median=X p95=Y max=Z (and scene_ms with --cycle-scenes) at exit");
  cli.add_option("--cycle-scenes", o->cycle_scenes,
                 "With --screenshot: move to the next scene every N frames, once the last change is fully drawn; "
                 "prints scene_ms (request to both full pictures drawn)");
  cli.add_option("--cycle-step", o->cycle_step,
                 "Scenes to move per cycle (1: the prefetched neighbour; e.g. 7: far jumps)")
      ->check(CLI::Range(1, 1000000));
  cli.add_option("--replay", o->replay, "Run the actions of this file, one per frame, then exit (see docs/gui.md)");
  cli.add_option("--texture-budget-mb", o->texture_budget_mb, "Texture cache size")->check(CLI::Range(16, 65536));
  cli.add_option("--size", o->width, "Window width")->check(CLI::Range(320, 10000));
  cli.add_option("--height", o->height, "Window height")->check(CLI::Range(240, 10000));
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return cli.exit(e);
  }
  o->size_given = cli.count("--size") + cli.count("--height") > 0;
  o->exe_dir = std::filesystem::path(argv[0]).parent_path().string();
  return -1;
}

}  // namespace ipd::studio
