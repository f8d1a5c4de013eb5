// ipd-studio: the inspection GUI. A thin window loop: StudioApp (studio_app.h) holds the worker that owns
// the study, the texture cache, the view state and the frame statistics; the views (ui/) draw a snapshot
// and return commands; StudioWindow (studio_window.h) is GLFW + OpenGL + ImGui.
#include <fmt/format.h>

#include <chrono>
#include <memory>
#include <thread>

#include "app/studio/studio_app.h"
#include "app/studio/studio_options.h"
#include "app/studio/studio_window.h"

namespace {
constexpr int kLoadingFramesPerSecond = 20;
}

int main(int argc, char** argv) {
  ipd::studio::StudioOptions o;
  if (const int rc = ipd::studio::parse_studio_options(argc, argv, &o); rc >= 0) return rc;
  std::unique_ptr<ipd::studio::StudioApp> app;
  try {
    app = std::make_unique<ipd::studio::StudioApp>(o);  // a bad replay file is reported before any window
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 2;
  }
  std::unique_ptr<ipd::studio::StudioWindow> window;
  try {
    window =
        std::make_unique<ipd::studio::StudioWindow>(o.width, o.height, o.headless(), !o.headless() && !o.size_given);
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 1;
  }
  app->set_help_key(ipd::studio::StudioWindow::help_key());
  while (!app->done()) {
    const auto frame_start = std::chrono::steady_clock::now();
    const ipd::studio::FrameClock clock;
    if (window->begin_frame()) app->request_quit();
    app->frame();
    window->render();
    if (const std::string shot = app->after_render(clock.ms(), clock.cpu_ms()); !shot.empty())
      window->save_screenshot(shot);
    window->present();
    // While a study loads, at most kLoadingFramesPerSecond frames are drawn: a software rasteriser (llvmpipe under
    // Xvfb) drawing frames unbounded takes the cores the load needs, and a progress bar needs no more.
    if (app->loading())
      std::this_thread::sleep_until(frame_start + std::chrono::microseconds(1000000 / kLoadingFramesPerSecond));
  }
  const int rc = app->print_stats();
  app.reset();  // textures go before the GL context
  return rc;
}
