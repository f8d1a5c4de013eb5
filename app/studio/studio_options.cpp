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

std::string parse_window_size(const std::string& text, int* width, int* height) {
  // W, or WxH (also WXH and W×H's ASCII spellings): each the whole number, in the window's range.
  auto number = [](const std::string& t, int lo, int hi, int* out) {
    if (t.empty() || t.size() > 6 || t.find_first_not_of("0123456789") != std::string::npos) return false;
    const int v = std::stoi(t);
    if (v < lo || v > hi) return false;
    *out = v;
    return true;
  };
  const size_t x = text.find_first_of("xX");
  int w = 0, h = 0;
  if (x == std::string::npos) {
    if (!number(text, 320, 10000, &w))
      return fmt::format("--size: expected a width from 320 to 10000, or WIDTHxHEIGHT (e.g. 1280x720), got '{}'", text);
    *width = w;
    return {};
  }
  if (!number(text.substr(0, x), 320, 10000, &w) || !number(text.substr(x + 1), 240, 10000, &h))
    return fmt::format(
        "--size: expected WIDTHxHEIGHT with a width from 320 to 10000 and a height from 240 to 10000 (e.g. "
        "1280x720), got '{}'",
        text);
  *width = w, *height = h;
  return {};
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
  std::string size;
  cli.add_option("--size", size, "Window size: WIDTHxHEIGHT (e.g. 1280x720), or the width alone");
  cli.add_option("--height", o->height, "Window height (or give it in --size)")->check(CLI::Range(240, 10000));
  try {
    cli.parse(argc, argv);
    if (!size.empty())
      if (const std::string why = parse_window_size(size, &o->width, &o->height); !why.empty())
        throw CLI::ValidationError(why);
  } catch (const CLI::ParseError& e) {
    return cli.exit(e);
  }
  o->size_given = cli.count("--size") + cli.count("--height") > 0;
  o->exe_dir = std::filesystem::path(argv[0]).parent_path().string();
  return -1;
}

}  // namespace ipd::studio
