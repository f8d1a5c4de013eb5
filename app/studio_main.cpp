// ipd-studio: the inspection GUI. A thin loop in the manner of Dear ImGui's examples: the session (core/)
// holds the state, the views (ui/) draw it and return commands, workers (studio_workers) do the disk work.
#define GL_GLEXT_PROTOTYPES
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <fmt/format.h>
#include <imgui.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <thread>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "data_files.h"
#include "ipd/atomic_file.h"
#include "ipd/demo_study.h"
#include "ipd/session.h"
#include "studio_workers.h"
#include "views.h"

namespace fs = std::filesystem;
using namespace ipd;

namespace {

struct Texture {
  GLuint id = 0;
  int width = 0, height = 0;  // of the original picture
  std::string error;
};

std::string demo_dir() {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  const char* home = std::getenv("HOME");
  const fs::path base = xdg && *xdg ? fs::path(xdg) : fs::path(home ? home : "/tmp") / ".cache";
  return (base / "ipd-studio" / "demo-study").string();
}

GLuint upload(const cv::Mat& rgba) {
  GLuint id = 0;
  glGenTextures(1, &id);
  glBindTexture(GL_TEXTURE_2D, id);
  // Mipmaps: pictures are mostly shown smaller than they are, and sampling a reduced level is both
  // smoother and much cheaper for a software rasteriser.
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, rgba.cols, rgba.rows, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data);
  glGenerateMipmap(GL_TEXTURE_2D);
  return id;
}

void save_screenshot(int w, int h, const std::string& path) {
  cv::Mat rgba(h, w, CV_8UC4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data);
  cv::Mat bgr;
  cv::cvtColor(rgba, bgr, cv::COLOR_RGBA2BGR);
  cv::flip(bgr, bgr, 0);
  std::vector<uchar> png;
  cv::imencode(".png", bgr, png);
  write_file_atomically(path, std::string(png.begin(), png.end()));
}

void load_font(const std::string& exe_dir) {
  ImGuiIO& io = ImGui::GetIO();
  // A font from assets/ if one was put there, else Debian's DejaVu (fonts-dejavu-core), else ImGui's own.
  for (const std::string& p : {find_data_file("fonts/DejaVuSans.ttf", IPD_ASSETS_DIR), exe_dir + "/../../assets/fonts/DejaVuSans.ttf",
                               std::string("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf")}) {
    std::error_code ec;
    if (fs::exists(p, ec) && io.Fonts->AddFontFromFileTTF(p.c_str(), 15.0f)) return;
  }
  io.Fonts->AddFontDefault();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App cli{"ipd-studio: inspect and fix rock pairs, IPD live"};
  std::string study, screenshot;
  int frames = 60, width = 1600, height = 900;
  bool frame_stats = false;
  cli.add_option("STUDY", study, "Study directory (default: the built-in demo study, generated on first run)");
  cli.add_option("--screenshot", screenshot, "Render --frames frames, save the window as this PNG and exit");
  cli.add_option("--frames", frames, "Frames to render before the screenshot")->check(CLI::Range(1, 100000));
  cli.add_flag("--frame-stats", frame_stats, "Print frame_ms median=X p95=Y at exit");
  int cycle_scenes = 0;
  cli.add_option("--cycle-scenes", cycle_scenes,
                 "With --screenshot: move to the next scene every N frames and print scene_change_ms (time until "
                 "both pictures show)");
  cli.add_option("--size", width, "Window width")->check(CLI::Range(320, 10000));
  cli.add_option("--height", height, "Window height")->check(CLI::Range(240, 10000));
  CLI11_PARSE(cli, argc, argv);
  const bool demo = study.empty();
  if (demo) study = demo_dir();

  if (!glfwInit()) {
    fmt::print(stderr, "error: cannot initialise GLFW (no display? run under xvfb-run)\n");
    return 1;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 0);
  GLFWwindow* window = glfwCreateWindow(width, height, ("IPD Studio - " + study).c_str(), nullptr, nullptr);
  if (!window) {
    fmt::print(stderr, "error: cannot open a window with OpenGL 3\n");
    glfwTerminate();
    return 1;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(screenshot.empty() ? 1 : 0);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
  ImGui::StyleColorsDark();
  ImGui::GetStyle().Colors[ImGuiCol_WindowBg].w = 1.0f;
  ImGui::GetStyle().Colors[ImGuiCol_ChildBg] = ImVec4(0, 0, 0, 0);
  load_font(fs::path(argv[0]).parent_path().string());
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 130");

  // Opening (and for the demo, generating) runs off the UI thread.
  std::future<Session> opening = std::async(std::launch::async, [study, demo] {
    if (demo && !fs::exists(fs::path(study) / "study.yaml")) write_demo_study(study);
    return Session::open(study);
  });
  std::optional<Session> session;
  std::string open_error;
  studio::PictureLoader loader;
  studio::Saver saver;
  std::map<std::string, Texture> textures;
  ui::UiState ui;
  std::vector<double> frame_ms;
  struct ExportResult {
    std::mutex mu;
    std::string message;
  };
  const auto export_result = std::make_shared<ExportResult>();  // shared with detached export threads
  int counted = 0, settle = 0;
  std::vector<double> change_ms;
  std::chrono::steady_clock::time_point change_started{};
  bool changing = false, change_shown = false;
  float split = 0.62f;

  while (!glfwWindowShouldClose(window)) {
    const auto t0 = std::chrono::steady_clock::now();
    glfwPollEvents();
    if (!session && open_error.empty() &&
        opening.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
      try {
        session.emplace(opening.get());
        if (!session->scenes().empty()) ui.scene = ui::browser_order(*session, ui).front();
      } catch (const std::exception& e) {
        open_error = e.what();
      }
    }
    for (auto& d : loader.take_ready()) {
      Texture t;
      t.width = d.width;
      t.height = d.height;
      t.error = d.error;
      if (!d.rgba.empty()) t.id = upload(d.rgba);
      if (textures.count(d.key) && textures[d.key].id) glDeleteTextures(1, &textures[d.key].id);
      textures[d.key] = t;
    }
    for (const auto& e : saver.take_errors()) ui.status = "save failed: " + e;

    // Pictures: the current scene first, then its neighbours in the browser's order.
    auto picture = [&](const std::string& domain, const std::string& stem, bool urgent) {
      const std::string key = domain + "/" + stem;
      const auto it = textures.find(key);
      if (it == textures.end()) {
        const Domain* d = session->study().domain(domain);
        const auto img = d->images.find(stem);
        loader.request(key, img == d->images.end() ? "" : img->second, urgent);
        textures[key] = Texture{};
        textures[key].error = "loading...";
        return ui::Picture{nullptr, 0, 0, "loading..."};
      }
      return ui::Picture{it->second.id ? reinterpret_cast<ImTextureID>(static_cast<intptr_t>(it->second.id)) : nullptr,
                         it->second.width, it->second.height, it->second.error};
    };

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(vp->WorkPos);
    ImGui::SetNextWindowSize(vp->WorkSize);
    ImGui::Begin("IPD Studio", nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoBringToFrontOnFocus |
                     ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBackground);
    ui::UiCommands cmd;
    if (!open_error.empty()) {
      ImGui::TextColored({1, 0.4f, 0.3f, 1}, "Could not open the study:");
      ImGui::TextWrapped("%s", open_error.c_str());
    } else if (!session) {
      ImGui::Text(demo ? "Generating and opening the demo study at %s ..." : "Opening %s ...", study.c_str());
    } else {
      Session& s = *session;
      ui.order = ui::browser_order(s, ui);  // once per frame: it summarises every scene
      ui::handle_shortcuts(s, ui, cmd);
      ui::Picture left, right;
      if (cycle_scenes > 0 && counted > 0 && counted % cycle_scenes == 0 && !changing && s.scenes().size() > 1) {
        const auto& order = ui.order;
        const auto at = std::find(order.begin(), order.end(), ui.scene);
        cmd.goto_scene = order[((at - order.begin()) + 1) % order.size()];
        ui.scene = cmd.goto_scene;
        change_started = std::chrono::steady_clock::now();
        changing = true;
      }
      if (!s.scenes().empty()) {
        const std::string& stem = s.scenes()[ui.scene].stem;
        left = picture(s.left_domain(), stem, true);
        right = picture(s.right_domain(), stem, true);
        const auto& order = ui.order;
        const auto at = std::find(order.begin(), order.end(), ui.scene);
        // Both pictures are in: the change is complete once this frame is drawn (measured below).
        change_shown = changing && left.placeholder != "loading..." && right.placeholder != "loading...";
        for (int step : {1, -1}) {
          if (at == order.end()) break;
          const long k = (at - order.begin()) + step;
          if (k < 0 || k >= static_cast<long>(order.size())) continue;
          picture(s.left_domain(), s.scenes()[order[k]].stem, false);
          picture(s.right_domain(), s.scenes()[order[k]].stem, false);
        }
      }
      if (ImGui::BeginTable("layout", 3, ImGuiTableFlags_Resizable | ImGuiTableFlags_BordersInnerV)) {
        ImGui::TableSetupColumn("browser", ImGuiTableColumnFlags_WidthFixed, 280);
        ImGui::TableSetupColumn("main", ImGuiTableColumnFlags_WidthStretch);
        ImGui::TableSetupColumn("ipd", ImGuiTableColumnFlags_WidthFixed, 440);
        ImGui::TableNextRow();
        const float h = ImGui::GetContentRegionAvail().y;
        ImGui::TableNextColumn();
        ImGui::BeginChild("browser", {0, h});
        ui::draw_study_browser(s, ui, cmd);
        if (!s.labels().errors.empty() && ImGui::CollapsingHeader("label file problems")) {
          for (const auto& e : s.labels().errors) ImGui::TextWrapped("%s", e.to_string().c_str());
        }
        ImGui::EndChild();
        ImGui::TableNextColumn();
        ImGui::BeginChild("pictures", {0, h * split});
        ui::draw_side_by_side(s, ui, left, right, cmd);
        ImGui::EndChild();
        ImGui::InvisibleButton("##split", {-1, 6});
        if (ImGui::IsItemActive()) split = std::clamp(split + ImGui::GetIO().MouseDelta.y / h, 0.2f, 0.85f);
        if (ImGui::IsItemHovered() || ImGui::IsItemActive()) ImGui::SetMouseCursor(ImGuiMouseCursor_ResizeNS);
        const float rest = ImGui::GetContentRegionAvail().y;
        ImGui::BeginChild("registration", {ImGui::GetContentRegionAvail().x * 0.6f, rest}, true);
        ui::draw_registration(s, ui, cmd);
        ImGui::EndChild();
        ImGui::SameLine();
        ImGui::BeginChild("pairtable", {0, rest}, true);
        ui::draw_pair_table(s, ui, cmd);
        ImGui::EndChild();
        ImGui::TableNextColumn();
        ImGui::BeginChild("ipd", {0, h});
        ui::draw_ipd_panel(s, ui, cmd);
        ImGui::EndChild();
        ImGui::EndTable();
      }
      // Apply what the user asked for.
      if (!cmd.left_domain.empty() && s.select_domains(cmd.left_domain, cmd.right_domain)) {
        ui.scene = s.scenes().empty() ? 0 : ui::browser_order(s, ui).front();
        ui.rerun.reset();
      }
      if (!cmd.model.empty()) s.select(s.pair_index(), cmd.model);
      if (cmd.conf_threshold >= 0) s.set_conf_threshold(cmd.conf_threshold);
      if (cmd.goto_scene >= 0 && cmd.goto_scene != ui.scene) {
        ui.scene = cmd.goto_scene;
        ui.selected_left = ui.selected_right = -1;
        ui.rerun.reset();
        ui.anim_t = 1.0f;
      }
      auto submit = [&](SaveJob job) {
        if (s.read_only()) ui.status = "read-only study: the edit is kept in memory; use save as";
        else saver.submit(std::move(job));
      };
      for (const auto& e : cmd.edits) submit(s.apply(ui.scene, e));
      if (cmd.undo)
        if (auto job = s.undo()) submit(std::move(*job)), ui.scene = std::max(0, s.last_edited_scene());
      if (cmd.redo)
        if (auto job = s.redo()) submit(std::move(*job)), ui.scene = std::max(0, s.last_edited_scene());
      if (cmd.save_as && ui.save_as_dir[0]) {
        for (auto& job : s.save_all_to(ui.save_as_dir)) saver.submit(std::move(job));
        ui.status = std::string("edited pairs written under ") + ui.save_as_dir + "/pairs/";
      }
      if (cmd.export_figures && !s.scenes().empty()) {
        // The same files `ipd figure` writes, by the same code (the CLI renders them off-screen); run in
        // the background so the window stays responsive.
        const fs::path ipd_exe = fs::path(argv[0]).parent_path() / "ipd";
        const fs::path dir = s.read_only() ? fs::current_path() : fs::path(s.study().root) / "figures";
        const std::string stem = s.scenes()[ui.scene].stem, a = s.left_domain(), b = s.right_domain();
        const std::string base = (dir / (stem + "_" + a + "_" + b)).string();
        auto quote = [](const std::string& x) {
          std::string q = "'";
          for (char c : x) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
          return q + "'";
        };
        const std::string common = " " + quote(s.study().root) + " --scene " + quote(stem) + " --a " + quote(a) +
                                   " --b " + quote(b) + " --model " + quote(s.model());
        const std::string command = quote(ipd_exe.string()) + " figure pairs" + common + " --out " +
                                    quote(base + "_pairs.png") + " >/dev/null 2>&1 && " + quote(ipd_exe.string()) +
                                    " figure registration" + common + " --out " + quote(base + "_registration.png") +
                                    " >/dev/null 2>&1";
        ui.status = "exporting " + base + "_pairs.png and _registration.png ...";
        std::thread([command, base, exported = export_result] {
          const int rc = std::system(command.c_str());
          std::lock_guard<std::mutex> l(exported->mu);
          exported->message = rc == 0 ? "exported " + base + "_pairs.png and _registration.png"
                                     : "export failed (is the ipd tool next to ipd-studio?)";
        }).detach();
      }
      {
        std::lock_guard<std::mutex> l(export_result->mu);
        if (!export_result->message.empty()) ui.status = std::exchange(export_result->message, {});
      }
      if (cmd.rerun_registration && !s.scenes().empty()) {
        RegistrationOptions o = s.study().config.registration;
        o.method = ui.rerun_method == 0 ? RegistrationMethod::kConsensus
                   : ui.rerun_method == 1 ? RegistrationMethod::kPaper : RegistrationMethod::kCpd;
        o.seed = static_cast<std::uint64_t>(std::max(0, ui.rerun_seed));
        o.aspect = s.study().aspect();
        const auto& [a, b] = s.domain_pairs()[s.pair_index()];
        const std::string& stem = s.scenes()[ui.scene].stem;
        ui.rerun = register_rocks(s.labels().gt_of(a, stem).boxes, s.labels().gt_of(b, stem).boxes, o);
        ui.anim_t = 0.0f;
        ui.playing = true;
      }
      // Keep the textures of nearby scenes only.
      if (textures.size() > 24) {
        for (auto it = textures.begin(); it != textures.end();) {
          const bool near = !s.scenes().empty() && it->first.find("/" + s.scenes()[ui.scene].stem) != std::string::npos;
          if (!near && it->second.id) {
            glDeleteTextures(1, &it->second.id);
            it = textures.erase(it);
          } else {
            ++it;
          }
        }
      }
    }
    ImGui::End();
    ImGui::Render();
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(window, &fw, &fh);
    glViewport(0, 0, fw, fh);
    // The window background is this clear, not a blended full-screen quad: on a software rasteriser
    // (llvmpipe) every covered pixel costs, and the clear is by far the cheapest way to paint them.
    const ImVec4 bg = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
    glClearColor(bg.x, bg.y, bg.z, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (!screenshot.empty()) glFinish();
    if (change_shown) {
      change_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - change_started).count());
      changing = change_shown = false;
    }
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (!screenshot.empty() && (session || !open_error.empty())) {
      // Count frames once the study is open and the current pictures are in (or after a grace period).
      if (loader.idle() || ++settle > 600) {
        if (counted > 2) frame_ms.push_back(ms);  // the first frames upload textures
        if (++counted >= frames) {
          save_screenshot(fw, fh, screenshot);
          break;
        }
      }
    }
    glfwSwapBuffers(window);
  }
  if (frame_stats && !frame_ms.empty()) {
    std::sort(frame_ms.begin(), frame_ms.end());
    fmt::print("frame_ms median={:.2f} p95={:.2f}\n", frame_ms[frame_ms.size() / 2],
               frame_ms[std::min(frame_ms.size() - 1, frame_ms.size() * 95 / 100)]);
  }
  if (!change_ms.empty()) {
    std::sort(change_ms.begin(), change_ms.end());
    fmt::print("scene_change_ms median={:.2f} max={:.2f} over {} changes\n", change_ms[change_ms.size() / 2],
               change_ms.back(), change_ms.size());
  }
  if (!screenshot.empty()) fmt::print("{}\n", screenshot);
  for (auto& [k, t] : textures)
    if (t.id) glDeleteTextures(1, &t.id);
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  glfwTerminate();
  return open_error.empty() ? 0 : 1;
}
