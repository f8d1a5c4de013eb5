#include "app/studio/studio_window.h"

#include <algorithm>

#define GL_GLEXT_PROTOTYPES
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <cfloat>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "core/picture/picture_codec.h"
#include "core/util/atomic_file.h"
#include "ui/canvas/canvas.h"

namespace fs = std::filesystem;

namespace ipd::studio {

namespace {

void load_font() {
  // The figures' font (ui::default_font_file: assets/fonts/ if one was put there, else Debian's DejaVu from
  // fonts-dejavu-core), else ImGui's own.
  const std::string font = ui::default_font_file();
  std::error_code ec;
  // Latin-1 plus the typography core labels use: Δ, thin space and dashes (U+2009..2027: en dash in
  // ranges), superscript digits (footnote marks past ³), minus, ≈ (the Rank window's "≈ best"), ≤ ≥. ImGui's default
  // ranges stop at U+00FF and draw the rest as '?'.
  static const ImWchar kRanges[] = {0x0020, 0x00FF, 0x0394, 0x0394, 0x2009, 0x2027, 0x2070, 0x2079,
                                    0x2212, 0x2212, 0x2248, 0x2248, 0x2264, 0x2265, 0};
  if (fs::exists(font, ec) && ImGui::GetIO().Fonts->AddFontFromFileTTF(font.c_str(), 15.0f, nullptr, kRanges)) return;
  ImGui::GetIO().Fonts->AddFontDefault();
}

double thread_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

double wall_ms() {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

StudioWindow::StudioWindow(int width, int height, bool headless, bool fit_to_screen) : headless_(headless) {
  if (!glfwInit()) throw std::runtime_error("cannot initialise GLFW (no display? run under xvfb-run)");
  if (GLFWmonitor* monitor = fit_to_screen ? glfwGetPrimaryMonitor() : nullptr) {
    int x = 0, y = 0, w = 0, h = 0;
    glfwGetMonitorWorkarea(monitor, &x, &y, &w, &h);
    if (w >= 320 && h >= 240) width = std::min(width, w), height = std::min(height, h);
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 0);
  window_ = glfwCreateWindow(width, height, "IPD Studio", nullptr, nullptr);
  if (!window_) {
    glfwTerminate();
    throw std::runtime_error("cannot open a window with OpenGL 3");
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(headless ? 0 : 1);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
  ImGui::StyleColorsDark();
  ImGui::GetStyle().Colors[ImGuiCol_WindowBg].w = 1.0f;
  ImGui::GetStyle().Colors[ImGuiCol_ChildBg] = ImVec4(0, 0, 0, 0);
  load_font();
  // Before ImGui's backend, which calls the callback it finds installed before setting a key's state.
  glfwSetWindowUserPointer(window_, this);
  glfwSetKeyCallback(window_, &StudioWindow::on_key);
  ImGui_ImplGlfw_InitForOpenGL(window_, true);
  ImGui_ImplOpenGL3_Init("#version 130");
}

int StudioWindow::help_key() { return GLFW_KEY_F1; }

StudioWindow::~StudioWindow() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window_);
  glfwTerminate();
}

void StudioWindow::on_key(GLFWwindow* window, int key, int, int action, int) {
  auto* self = static_cast<StudioWindow*>(glfwGetWindowUserPointer(window));
  if (!self) return;
  if (action == GLFW_PRESS) self->taps_.pressed(key);
  if (action == GLFW_RELEASE) self->taps_.released(key);
}

bool StudioWindow::begin_frame() {
  glfwPollEvents();
  ImGuiIO& io = ImGui::GetIO();
  taps_.apply(io.KeysDown, static_cast<int>(IM_ARRAYSIZE(io.KeysDown)));
  const bool close = glfwWindowShouldClose(window_);
  if (close) glfwSetWindowShouldClose(window_, GLFW_FALSE);  // the quit warning decides
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  // A scripted run has no user: Xvfb's pointer rests mid-screen and would hover (highlight) whatever is
  // there in every screenshot, which reads as a selection.
  if (headless_) ImGui::GetIO().MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
  ImGui::NewFrame();
  return close;
}

void StudioWindow::render() {
  ImGui::Render();
  int fw = 0, fh = 0;
  glfwGetFramebufferSize(window_, &fw, &fh);
  glViewport(0, 0, fw, fh);
  // The background is this clear, not a blended full-screen quad: on a software rasteriser (llvmpipe)
  // every covered pixel costs, and the clear is by far the cheapest way to paint them.
  const ImVec4 bg = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
  glClearColor(bg.x, bg.y, bg.z, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  if (headless_) glFinish();
}

void StudioWindow::save_screenshot(const std::string& path) const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  cv::Mat rgba(h, w, CV_8UC4), bgr;
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data);
  cv::cvtColor(rgba, bgr, cv::COLOR_RGBA2BGR);
  cv::flip(bgr, bgr, 0);
  std::vector<uchar> png;
  if (!encode_picture(".png", bgr, &png)) throw std::runtime_error(path + ": cannot encode the screenshot as PNG");
  write_file_atomically(path, std::string(png.begin(), png.end()));
}

void StudioWindow::present() { glfwSwapBuffers(window_); }

FrameClock::FrameClock() : wall0_(wall_ms()), cpu0_(thread_cpu_ms()) {}
double FrameClock::ms() const { return wall_ms() - wall0_; }
double FrameClock::cpu_ms() const { return thread_cpu_ms() - cpu0_; }

}  // namespace ipd::studio
