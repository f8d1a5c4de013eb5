// ipd-studio's command line: what to open, and the benchmark/automation switches (--screenshot, --frames,
// --frame-stats, --cycle-scenes, --cycle-step, --replay).
#pragma once

#include <cstddef>
#include <string>

namespace ipd::studio {

struct StudioOptions {
  std::string study;       // empty: the demo study
  std::string exe_dir;     // where the `ipd` tool is (exports)
  std::string screenshot;  // render `frames` frames, save the window, exit
  int frames = 60;
  bool frame_stats = false;
  int cycle_scenes = 0;  // with --screenshot: next scene every N frames (after the last one is drawn)
  int cycle_step = 1;    // scenes to move per cycle (1: prefetched neighbour; more: a far jump)
  std::string replay;    // --replay FILE
  std::size_t texture_budget_mb = 512;
  int width = 1600, height = 900;  // the window
  // --size or --height given: the window is that size even past the screen. Otherwise an interactive window
  // shrinks to the screen's work area (a 1280 x 800 laptop cut off the right column and the status bar).
  bool size_given = false;

  // A run that ends by itself (screenshot or replay): no vsync, every frame finished before it is timed.
  bool headless() const { return !screenshot.empty() || !replay.empty(); }

  // Empty when usable; otherwise the field that is wrong and the accepted range, in one sentence (the
  // ranges the command line accepts; cycle_scenes <= 0 means no cycling).
  std::string validate() const;
  // Throws std::invalid_argument("studio options: " + validate()) when not usable.
  void check() const;
};

// Parses the command line into `o`. Returns -1 to go on, else the exit code (0 after --help, 2 for bad
// arguments, with CLI11's message printed).
// --size's value: "1280x720" sets both, "1280" the width alone; returns why it is refused (empty: accepted).
std::string parse_window_size(const std::string& text, int* width, int* height);

int parse_studio_options(int argc, char** argv, StudioOptions* o);

}  // namespace ipd::studio
