// ipd-studio: the inspection GUI. A thin window loop: StudioApp (studio_app.h) holds the worker that owns
// the study, the texture cache and the view state; the views (ui/) draw a snapshot and return commands.
#define GL_GLEXT_PROTOTYPES
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <fmt/format.h>
#include <imgui.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "data_files.h"
#include "ipd/atomic_file.h"
#include "studio_app.h"

namespace fs = std::filesystem;

namespace {

// CPU time of the calling thread: a frame's own work, apart from waiting for the rasteriser or the machine.
double thread_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

void save_screenshot(int w, int h, const std::string& path) {
  cv::Mat rgba(h, w, CV_8UC4), bgr;
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data);
  cv::cvtColor(rgba, bgr, cv::COLOR_RGBA2BGR);
  cv::flip(bgr, bgr, 0);
  std::vector<uchar> png;
  cv::imencode(".png", bgr, png);
  ipd::write_file_atomically(path, std::string(png.begin(), png.end()));
}

void load_font(const std::string& exe_dir) {
  // A font from assets/ if one was put there, else Debian's DejaVu (fonts-dejavu-core), else ImGui's own.
  for (const std::string& p : {ipd::find_data_file("fonts/DejaVuSans.ttf", IPD_ASSETS_DIR), exe_dir + "/../../assets/fonts/DejaVuSans.ttf",
                               std::string("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf")}) {
    std::error_code ec;
    if (fs::exists(p, ec) && ImGui::GetIO().Fonts->AddFontFromFileTTF(p.c_str(), 15.0f)) return;
  }
  ImGui::GetIO().Fonts->AddFontDefault();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App cli{"ipd-studio: inspect and fix rock pairs, IPD live"};
  ipd::studio::StudioOptions o;
  int width = 1600, height = 900;
  cli.add_option("STUDY", o.study, "Study directory (default: the built-in demo study, generated on first run)");
  cli.add_option("--screenshot", o.screenshot, "Render --frames frames, save the window as this PNG and exit");
  cli.add_option("--frames", o.frames, "Frames to render before the screenshot")->check(CLI::Range(1, 100000));
  cli.add_flag("--frame-stats", o.frame_stats, "Print frame_ms median=X p95=Y max=Z at exit");
  cli.add_option("--cycle-scenes", o.cycle_scenes,
                 "With --screenshot: move to the next scene every N frames, once the last change is fully drawn; "
                 "prints scene_ms (request to both full pictures drawn)");
  cli.add_option("--cycle-step", o.cycle_step, "Scenes to move per cycle (1: the prefetched neighbour; e.g. 7: far jumps)")
      ->check(CLI::Range(1, 1000000));
  cli.add_option("--replay", o.replay, "Run the actions of this file, one per frame, then exit (see README)");
  cli.add_option("--texture-budget-mb", o.texture_budget_mb, "Texture cache size")->check(CLI::Range(16, 65536));
  cli.add_option("--size", width, "Window width")->check(CLI::Range(320, 10000));
  cli.add_option("--height", height, "Window height")->check(CLI::Range(240, 10000));
  CLI11_PARSE(cli, argc, argv);
  o.exe_dir = fs::path(argv[0]).parent_path().string();
  const bool headless_run = !o.screenshot.empty() || !o.replay.empty();
  std::unique_ptr<ipd::studio::StudioApp> app;
  try {
    app = std::make_unique<ipd::studio::StudioApp>(o);
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 2;
  }
  if (!glfwInit()) {
    fmt::print(stderr, "error: cannot initialise GLFW (no display? run under xvfb-run)\n");
    return 1;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 0);
  GLFWwindow* window = glfwCreateWindow(width, height, "IPD Studio", nullptr, nullptr);
  if (!window) {
    fmt::print(stderr, "error: cannot open a window with OpenGL 3\n");
    glfwTerminate();
    return 1;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(headless_run ? 0 : 1);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
  ImGui::StyleColorsDark();
  ImGui::GetStyle().Colors[ImGuiCol_WindowBg].w = 1.0f;
  ImGui::GetStyle().Colors[ImGuiCol_ChildBg] = ImVec4(0, 0, 0, 0);
  load_font(o.exe_dir);
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 130");
  while (!app->done()) {
    const auto t0 = std::chrono::steady_clock::now();
    const double cpu0 = thread_cpu_ms();
    glfwPollEvents();
    if (glfwWindowShouldClose(window)) {  // the quit warning decides
      glfwSetWindowShouldClose(window, GLFW_FALSE);
      app->request_quit();
    }
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    app->frame();
    ImGui::Render();
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(window, &fw, &fh);
    glViewport(0, 0, fw, fh);
    // The background is this clear, not a blended full-screen quad: on a software rasteriser (llvmpipe)
    // every covered pixel costs, and the clear is by far the cheapest way to paint them.
    const ImVec4 bg = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
    glClearColor(bg.x, bg.y, bg.z, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (headless_run) glFinish();
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (const std::string shot = app->after_render(ms, thread_cpu_ms() - cpu0); !shot.empty())
      save_screenshot(fw, fh, shot);
    glfwSwapBuffers(window);
  }
  const int rc = app->print_stats();
  app.reset();  // textures go before the GL context
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  glfwTerminate();
  return rc;
}
