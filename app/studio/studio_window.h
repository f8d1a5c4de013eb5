// The window of ipd-studio: GLFW, an OpenGL 3 context and ImGui with its GLFW/OpenGL3 backends, set up in
// the constructor and torn down in the destructor; one call per step of a frame.
#pragma once

#include <string>

#include "app/studio/key_taps.h"

struct GLFWwindow;

namespace ipd::studio {

class StudioWindow {
 public:
  // Throws std::runtime_error (no display, no OpenGL 3).
  // `fit_to_screen`: width x height at most the primary monitor's work area.
  StudioWindow(int width, int height, bool headless, bool fit_to_screen);
  // F1 as the GLFW backend indexes ImGui's KeysDown (by GLFW key codes).
  static int help_key();
  ~StudioWindow();
  StudioWindow(const StudioWindow&) = delete;
  StudioWindow& operator=(const StudioWindow&) = delete;

  // Events, then a new ImGui frame; true when the user asked to close the window (the app decides).
  bool begin_frame();
  // Renders what ImGui built; a headless run waits for the rasteriser so the frame's time is all of it.
  void render();
  void save_screenshot(const std::string& path) const;  // the frame just rendered, as PNG (atomically)
  void present();

 private:
  static void on_key(GLFWwindow* window, int key, int scancode, int action, int mods);
  GLFWwindow* window_ = nullptr;
  bool headless_ = false;
  KeyTaps taps_;
};

// Wall-clock and this thread's CPU time since construction: a frame's time, and its own share of it (apart
// from waiting for the rasteriser or the machine).
class FrameClock {
 public:
  FrameClock();
  double ms() const;
  double cpu_ms() const;

 private:
  double wall0_, cpu0_;
};

}  // namespace ipd::studio
