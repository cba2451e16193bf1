/// \file main.cpp
/// adaptex-studio: window (GLFW 3.3), OpenGL 3.3 core context, Dear ImGui 1.86, and the fixed frame
/// loop around the App. Also the scripted mode used by tests and documentation:
///   adaptex-studio MESH [--replay S.json] [--screenshot OUT.png] [--exit-after-frames K] ...
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>
#include <poll.h>
#include <signal.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "adaptex/core/limits.h"
#include "app.h"
#include "gl_renderer.h"
#include "ui.h"

namespace {

using namespace adaptex;
using namespace adaptex::studio;

/// Everything the GLFW callbacks need (reached through the window user pointer, not a global).
struct WindowContext {
  App* app = nullptr;
  double scale_x = 1, scale_y = 1;  // framebuffer pixels per window unit
};

Mods mods_of(int m) { return Mods{(m & GLFW_MOD_SHIFT) != 0, (m & GLFW_MOD_CONTROL) != 0, (m & GLFW_MOD_ALT) != 0}; }
WindowContext& ctx(GLFWwindow* w) { return *static_cast<WindowContext*>(glfwGetWindowUserPointer(w)); }

void install_callbacks(GLFWwindow* w) {
  glfwSetFramebufferSizeCallback(w, [](GLFWwindow* win, int width, int height) {
    int ww, wh;
    glfwGetWindowSize(win, &ww, &wh);
    ctx(win).scale_x = ww > 0 ? double(width) / ww : 1.0;
    ctx(win).scale_y = wh > 0 ? double(height) / wh : 1.0;
    ctx(win).app->on_resize(width, height);
  });
  glfwSetMouseButtonCallback(w, [](GLFWwindow* win, int button, int action, int mods) {
    if (button > 2 || action == GLFW_REPEAT) return;
    const MouseButton b = button == GLFW_MOUSE_BUTTON_LEFT    ? MouseButton::Left
                          : button == GLFW_MOUSE_BUTTON_RIGHT ? MouseButton::Right
                                                              : MouseButton::Middle;
    ctx(win).app->on_mouse_button(b, action == GLFW_PRESS, mods_of(mods));
  });
  glfwSetCursorPosCallback(w, [](GLFWwindow* win, double x, double y) {
    ctx(win).app->on_cursor(x * ctx(win).scale_x, y * ctx(win).scale_y);
  });
  glfwSetScrollCallback(w, [](GLFWwindow* win, double, double dy) { ctx(win).app->on_scroll(dy); });
  glfwSetKeyCallback(w, [](GLFWwindow* win, int key, int, int action, int mods) {
    if (action != GLFW_RELEASE) ctx(win).app->on_key(key, true, mods_of(mods));
  });
  glfwSetDropCallback(w, [](GLFWwindow* win, int count, const char** paths) {
    std::vector<std::string> p(paths, paths + count);
    ctx(win).app->on_drop(p);
  });
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, size_t(q * (v.size() - 1) + 0.5))];
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App cli{"adaptex-studio: paint on 3-D models; the texture adapts to what you paint"};
  std::string mesh, replay, screenshot, history_out, texture_out, export_dir, project, stats_out, window = "1280x800";
  std::string config_dir, recovery_dir, adapt_mode;
  int exit_after = -1, texture_size = 0, orbit_frames = 0;
  bool recover = false, hide_ui = false, no_vsync = false, no_recovery = false, wireframe = false;
  double yaw = 0, pitch = 0;
  cli.add_option("mesh", mesh, "Mesh file to open (OBJ, OFF, PLY, STL, glTF) or builtin:trefoil|sphere|torus|plane");
  cli.add_option("--project", project, "Open a project file (.json)");
  cli.add_option("--replay", replay, "Replay a stroke file onto the mesh");
  cli.add_option("--screenshot", screenshot, "Write a PNG of the window on the last scripted frame");
  cli.add_option("--exit-after-frames", exit_after,
                 "Quit after K frames once the model is loaded and the texture is up to date");
  cli.add_option("--history-out", history_out, "On exit, write the stroke history (stroke file)");
  cli.add_option("--texture-out", texture_out, "On exit, write the texture (PNG)");
  cli.add_option("--export-obj", export_dir, "On exit, export OBJ+MTL+PNG into this folder");
  cli.add_option("--stats", stats_out, "On exit, write frame-time / dab-latency statistics (JSON)");
  cli.add_option("--window", window, "Window size WxH");
  cli.add_option("--config-dir", config_dir, "Config folder (recent files); default $XDG_CONFIG_HOME/adaptex");
  cli.add_option("--recovery-dir", recovery_dir, "Autosave / recovery folder; default the config folder");
  cli.add_flag("--no-recovery", no_recovery, "Do not autosave a recovery file");
  cli.add_flag("--recover", recover, "Load an autosaved recovery file without asking");
  cli.add_flag("--hide-ui", hide_ui, "Hide the panels (clean screenshots)");
  cli.add_flag("--wireframe", wireframe, "Start with the wireframe overlay on");
  cli.add_flag("--no-vsync", no_vsync, "Do not wait for vertical sync");
  cli.add_option("--texture-size", texture_size, "Texture width = height in texels (default 1024)");
  cli.add_option("--adapt", adapt_mode, "Re-parameterization after each stroke: none|single|two-stage")
      ->check(CLI::IsMember({"none", "single", "two-stage"}));
  cli.add_option("--yaw", yaw, "Initial camera yaw (degrees)");
  cli.add_option("--pitch", pitch, "Initial camera pitch (degrees)");
  std::string inspect, decal;
  cli.add_option("--decal", decal, "Once loaded, project this image as a decal from the initial view");
  cli.add_option("--inspect", inspect, "Open the Inspect panel: texture|uv|importance|stretch|ls2|compare")
      ->check(CLI::IsMember({"texture", "uv", "importance", "stretch", "ls2", "compare"}));
  cli.add_option("--orbit-frames", orbit_frames, "Benchmark: orbit the camera for N frames, then quit");
  CLI11_PARSE(cli, argc, argv);

  int win_w = 1280, win_h = 800;
  if (std::sscanf(window.c_str(), "%dx%d", &win_w, &win_h) != 2 || win_w < 64 || win_h < 64) {
    std::cerr << "adaptex-studio: --window: expected WxH, e.g. 1280x800\n";
    return 2;
  }
  AppOptions opt;
  if (!config_dir.empty()) {
    opt.config_dir = config_dir;
  } else if (const char* x = std::getenv("XDG_CONFIG_HOME"); x && *x) {
    opt.config_dir = std::filesystem::path(x) / "adaptex";
  } else if (const char* h = std::getenv("HOME"); h && *h) {
    opt.config_dir = std::filesystem::path(h) / ".config" / "adaptex";
  }
  opt.recovery_dir = no_recovery ? std::filesystem::path() : recovery_dir.empty() ? opt.config_dir : std::filesystem::path(recovery_dir);
  opt.auto_recover = recover;
  if (!opt.recovery_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(opt.recovery_dir, ec);
  }

  // SIGTERM / SIGINT end the session cleanly (outputs written); read through a signalfd.
  sigset_t sigs;
  sigemptyset(&sigs);
  sigaddset(&sigs, SIGTERM);
  sigaddset(&sigs, SIGINT);
  pthread_sigmask(SIG_BLOCK, &sigs, nullptr);
  const int sig_fd = signalfd(-1, &sigs, SFD_NONBLOCK | SFD_CLOEXEC);

  glfwSetErrorCallback([](int code, const char* msg) { std::cerr << "adaptex-studio: GLFW error " << code << ": " << msg << "\n"; });
  if (!glfwInit()) {
    std::cerr << "adaptex-studio: cannot initialize GLFW (no display?)\n";
    return 1;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  GLFWwindow* window_ptr = glfwCreateWindow(win_w, win_h, "adaptex studio", nullptr, nullptr);
  if (!window_ptr) {
    std::cerr << "adaptex-studio: cannot create an OpenGL 3.3 core window\n";
    glfwTerminate();
    return 1;
  }
  glfwMakeContextCurrent(window_ptr);
  glfwSwapInterval(no_vsync ? 0 : 1);

  int rc = 0;
  {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // layout is not persisted (keeps scripted runs reproducible)
    ImGui::StyleColorsDark();

    App app(std::make_unique<GlRenderer>(), opt);
    WindowContext wctx;
    wctx.app = &app;
    glfwSetWindowUserPointer(window_ptr, &wctx);
    install_callbacks(window_ptr);  // before ImGui's, which chain to ours
    ImGui_ImplGlfw_InitForOpenGL(window_ptr, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");
    {
      int fw, fh, ww, wh;
      glfwGetFramebufferSize(window_ptr, &fw, &fh);
      glfwGetWindowSize(window_ptr, &ww, &wh);
      wctx.scale_x = ww > 0 ? double(fw) / ww : 1.0;
      wctx.scale_y = wh > 0 ? double(fh) / wh : 1.0;
      app.on_resize(fw, fh);
    }
    app.view().show_ui = !hide_ui;
    app.view().wireframe = wireframe;
    if (texture_size > 0) app.adapt().texture_size = std::clamp(texture_size, 16, adaptex::kMaxTextureSize);
    if (adapt_mode == "single") app.adapt().mode = AdaptMode::Single;
    if (adapt_mode == "two-stage") app.adapt().mode = AdaptMode::TwoStage;
    if (!project.empty()) app.open_project(project);
    if (!mesh.empty()) app.open_mesh(mesh);
    if (!replay.empty()) {
      try {
        app.replay(load_strokes(replay));
      } catch (const std::exception& e) {
        std::cerr << "adaptex-studio: " << e.what() << "\n";
        rc = 2;
      }
    }
    const bool apply_view = yaw != 0 || pitch != 0;
    bool view_applied = false, ready_printed = false;
    int idle_frames = 0, orbit_done = 0;
    StudioUi ui;
    const std::vector<std::string> inspect_modes = {"texture", "uv", "importance", "stretch", "ls2", "compare"};
    for (size_t k = 0; k < inspect_modes.size(); ++k)
      if (inspect == inspect_modes[k]) ui.show_inspect(int(k));
    bool adapt_requested = false, compare_requested = false;
    bool final_frame = false;  // after SIGTERM / SIGINT: one more frame for the --screenshot
    while (!glfwWindowShouldClose(window_ptr) && !app.should_quit() && rc == 0) {
      // 1. input (callbacks run inside glfwPollEvents and act on the App at once)
      glfwPollEvents();
      if (final_frame) app.request_quit();
      if (sig_fd >= 0) {
        signalfd_siginfo si;
        if (read(sig_fd, &si, sizeof si) == ssize_t(sizeof si)) {
          if (!screenshot.empty() && exit_after < 0) {
            app.screenshot(screenshot);
            final_frame = true;
          } else {
            app.request_quit();
          }
        }
      }
      // 2. background results, autosave
      app.begin_frame();
      const bool idle = app.idle() && app.has_model() && !app.load_running();
      if (idle && apply_view && !view_applied) {
        app.camera().yaw = yaw * 3.14159265358979 / 180;
        app.camera().pitch = pitch * 3.14159265358979 / 180;
        view_applied = true;
      }
      if (app.has_model() && !app.load_running() && !adapt_requested && !replay.empty() &&
          app.adapt().mode != AdaptMode::None) {
        app.request_adapt();  // re-parameterize for the replayed strokes, as after a painted stroke
        adapt_requested = true;
      }
      if (idle && inspect == "compare" && !compare_requested) {
        app.request_compare();
        compare_requested = true;
      }
      if (idle && !decal.empty()) {
        app.load_decal(decal);
        app.project_decal(1.0);
        decal.clear();
      }
      if (idle && !ready_printed) {
        std::cout << "adaptex-studio: ready" << std::endl;
        app.reset_stats();  // statistics cover the interactive session, not the loading
        ready_printed = true;
      }
      if (orbit_frames > 0 && app.has_model() && !app.load_running()) {
        app.camera().orbit(4.0, 0.0);
        if (++orbit_done >= orbit_frames) app.request_quit();
      }
      // 3. UI
      ImGui_ImplOpenGL3_NewFrame();
      ImGui_ImplGlfw_NewFrame();
      ImGui::NewFrame();
      ui.draw(app);
      ImGui::Render();
      app.set_ui_capture(io.WantCaptureMouse, io.WantCaptureKeyboard);
      // 4. scene, then the UI on top
      app.render();
      ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
      // 5. scripted screenshot / exit, statistics
      if (idle && exit_after >= 0) {
        ++idle_frames;
        if (idle_frames >= exit_after) {
          if (!screenshot.empty()) app.screenshot(screenshot);
          app.request_quit();
        }
      }
      if (orbit_frames > 0 || !stats_out.empty()) glFinish();  // measured frames include the GPU work
      app.end_frame();
      glfwSwapBuffers(window_ptr);
    }
    if (!history_out.empty()) app.save_history(history_out);
    if (!texture_out.empty()) app.save_texture(texture_out);
    if (!export_dir.empty()) app.export_obj(export_dir);
    if (!stats_out.empty()) {
      const Stats& s = app.stats();
      std::vector<double> frames(s.frame_ms.begin() + std::min<size_t>(s.frame_ms.size(), 2), s.frame_ms.end());
      nlohmann::json j;
      j["frames"] = frames.size();
      j["frame_ms_median"] = percentile(frames, 0.5);
      j["frame_ms_p95"] = percentile(frames, 0.95);
      j["dab_events"] = s.dab_latency_ms.size();
      j["dab_to_screen_ms_median"] = percentile(s.dab_latency_ms, 0.5);
      j["dab_to_screen_ms_max"] = percentile(s.dab_latency_ms, 1.0);
      j["dab_to_screen_frames_max"] =
          s.dab_latency_frames.empty() ? 0 : *std::max_element(s.dab_latency_frames.begin(), s.dab_latency_frames.end());
      j["dab_paint_ms_median"] = percentile(s.dab_paint_ms, 0.5);
      j["dabs"] = s.dab_paint_ms.size();
      j["faces"] = app.mesh() ? app.mesh()->num_faces() : 0;
      j["window"] = window;
      j["texture_size"] = app.adapt().texture_size;
      std::ofstream(stats_out) << j.dump(1) << "\n";
    }
    for (const auto& m : app.messages())
      if (m.error && exit_after >= 0) rc = rc ? rc : 1;
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  glfwDestroyWindow(window_ptr);
  glfwTerminate();
  if (sig_fd >= 0) close(sig_fd);
  return rc;
}
