/// \file main.cpp
/// adaptex-studio: window (GLFW 3.3), OpenGL 3.3 core context, Dear ImGui 1.86, and the fixed frame
/// loop around the App. Also the scripted mode used by tests and documentation:
///   adaptex-studio MESH|PROJECT [--replay S.json] [--screenshot OUT.png] [--exit-after-frames K] ...
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

#include "adaptex/core/allocator.h"
#include "adaptex/core/atomic_output.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "app.h"
#include "gl_renderer.h"
#include "tablet.h"
#include "ui.h"

namespace {

using namespace adaptex;
using namespace adaptex::studio;

/// A mouse event held until Dear ImGui has seen the frame's mouse position (see WindowContext).
struct MouseEvent {
  enum class Kind { Button, Cursor, Scroll } kind = Kind::Cursor;
  MouseButton button = MouseButton::Left;
  bool pressed = false;
  Mods mods;
  double x = 0, y = 0;  // cursor position (framebuffer pixels) or scroll steps (y)
};

/// Everything the GLFW callbacks need (reached through the window user pointer, not a global).
/// Mouse events are queued and given to the App after ImGui::NewFrame(), with io.WantCaptureMouse of
/// that frame: a scroll or click just after the cursor entered a panel goes to the panel, not to the
/// 3-D view (with last frame's flag it went to the view).
struct WindowContext {
  App* app = nullptr;
  double scale_x = 1, scale_y = 1;  // framebuffer pixels per window unit
  std::vector<MouseEvent> mouse;    // queued since the last frame, in order
  TabletPressure* tablet = nullptr; // pen pressure of this frame's dabs (none: the test hook's or 1)
};

/// Gives the queued mouse events to the App, in order.
void dispatch_mouse(WindowContext& w) {
  if (w.tablet) w.app->set_pen_pressure(w.tablet->poll());
  for (const MouseEvent& e : w.mouse) {
    switch (e.kind) {
      case MouseEvent::Kind::Button: w.app->on_mouse_button(e.button, e.pressed, e.mods); break;
      case MouseEvent::Kind::Cursor: w.app->on_cursor(e.x, e.y); break;
      case MouseEvent::Kind::Scroll: w.app->on_scroll(e.y); break;
    }
  }
  w.mouse.clear();
}

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
    MouseEvent e{MouseEvent::Kind::Button, b, action == GLFW_PRESS, mods_of(mods)};
    ctx(win).mouse.push_back(e);
  });
  glfwSetCursorPosCallback(w, [](GLFWwindow* win, double x, double y) {
    MouseEvent e{MouseEvent::Kind::Cursor};
    e.x = x * ctx(win).scale_x;
    e.y = y * ctx(win).scale_y;
    ctx(win).mouse.push_back(e);
  });
  glfwSetScrollCallback(w, [](GLFWwindow* win, double, double dy) {
    MouseEvent e{MouseEvent::Kind::Scroll};
    e.y = dy;
    ctx(win).mouse.push_back(e);
  });
  glfwSetKeyCallback(w, [](GLFWwindow* win, int key, int, int action, int mods) {
    if (action != GLFW_RELEASE) ctx(win).app->on_key(key, true, mods_of(mods));
  });
  // Closing the window asks Save / Discard / Cancel when strokes are unsaved (App::request_quit).
  glfwSetWindowCloseCallback(w, [](GLFWwindow* win) {
    glfwSetWindowShouldClose(win, GLFW_FALSE);
    ctx(win).app->request_quit();
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

const std::vector<std::string> kInspectModes = {"texture", "uv", "importance", "stretch", "ls2", "compare", "density"};

/// Everything given on the command line.
struct CommandLine {
  std::string mesh, replay, screenshot, history_out, texture_out, export_dir, project, stats_out;
  std::string window = "1280x800", config_dir, recovery_dir, inspect, decal, stencil, stencil_place;
  std::string adapt_mode = to_string(AdaptOptions{}.mode);
  std::string recover;  // yes | no | ask; empty: ask, no for scripted runs
  int exit_after = -1, texture_size = 0, orbit_frames = 0;
  bool hide_ui = false, no_vsync = false, no_recovery = false, wireframe = false, no_refine = false;
  bool checker = false, fixed_layout = false, unwrap = false, pbr = false;
  double yaw = 0, pitch = 0;
  int width = 1280, height = 800;
};

/// Parses argv into \p c. \return an exit code when the program should stop (help, bad option).
std::optional<int> parse_command_line(int argc, char** argv, CommandLine& c) {
  CLI::App cli{"adaptex-studio: paint on 3-D models; the texture adapts to what you paint"};
  cli.add_option("mesh", c.mesh,
                 "Mesh file to open (OBJ, OFF, PLY, STL, glTF), builtin:trefoil|sphere|torus|plane, or a project "
                 "(.adaptex, or a project .json)");
  cli.add_option("--project", c.project, "Open a project file (.adaptex or .json)");
  cli.add_option("--replay", c.replay, "Replay a stroke file onto the mesh (version 2: open it as the layered material)");
  cli.add_option("--screenshot", c.screenshot, "Write a PNG of the window on the last scripted frame");
  cli.add_option("--exit-after-frames", c.exit_after,
                 "Quit after K frames once the model is loaded and the texture is up to date");
  cli.add_option("--history-out", c.history_out, "On exit, write the stroke history (stroke file)");
  cli.add_option("--texture-out", c.texture_out, "On exit, write the texture (PNG)");
  cli.add_option("--export-obj", c.export_dir, "On exit, export OBJ+MTL+PNG into this folder");
  cli.add_option("--stats", c.stats_out, "On exit, write frame-time / dab-latency statistics (JSON)");
  cli.add_option("--window", c.window, "Window size WxH");
  cli.add_option("--config-dir", c.config_dir, "Config folder (recent files); default $XDG_CONFIG_HOME/adaptex");
  cli.add_option("--recovery-dir", c.recovery_dir, "Autosave / recovery folder; default the config folder");
  cli.add_flag("--no-recovery", c.no_recovery, "Do not autosave a recovery file");
  CLI::Option* recover =
      cli.add_option("--recover", c.recover,
                     "Recovery files left by a session that did not end cleanly: yes (recover the newest), no (leave "
                     "them untouched), ask (default; no for scripted runs: --replay, --exit-after-frames, "
                     "--orbit-frames). --recover alone: yes")
          ->expected(0, 1);
  cli.add_flag("--hide-ui", c.hide_ui, "Hide the panels (clean screenshots)");
  cli.add_flag("--wireframe", c.wireframe, "Start with the wireframe overlay on");
  cli.add_flag("--checker", c.checker, "Start with the texel-density checker on the model (C)");
  cli.add_flag("--pbr", c.pbr, "Start with the lit material preview on (V)");
  cli.add_flag("--fixed-layout", c.fixed_layout, "Once loaded, show the fixed layout at the same texture size (L)");
  cli.add_flag("--no-vsync", c.no_vsync, "Do not wait for vertical sync");
  cli.add_option("--texture-size", c.texture_size, "Texture width = height in texels (default 1024)");
  std::vector<std::string> modes;
  for (AdaptMode m : adapt_modes()) modes.push_back(to_string(m));
  cli.add_option("--adapt", c.adapt_mode, "Re-parameterization after each stroke (as adaptex paint --adapt)")
      ->check(CLI::IsMember(modes))
      ->capture_default_str();
  cli.add_flag("--unwrap", c.unwrap,
               "Unwrap the model afresh even when it has its own UV atlas and base-colour texture (default: paint "
               "on them)");
  cli.add_flag("--no-refine", c.no_refine, "Keep the input's vertices (density-flow refines large triangles)");
  cli.add_option("--yaw", c.yaw, "Initial camera yaw (degrees)");
  cli.add_option("--pitch", c.pitch, "Initial camera pitch (degrees)");
  cli.add_option("--decal", c.decal, "Once loaded, project this image as a decal through its stencil (kept shown)");
  cli.add_option("--stencil", c.stencil, "Once loaded, show this image as a decal stencil (P projects it)");
  cli.add_option("--stencil-place", c.stencil_place,
                 "Stencil of --stencil / --decal: X,Y,HEIGHT,DEGREES (window pixels; default centred)");
  cli.add_option("--inspect", c.inspect, "Open the Inspect panel: texture|uv|importance|stretch|ls2|compare|density")
      ->check(CLI::IsMember(kInspectModes));
  cli.add_option("--orbit-frames", c.orbit_frames, "Benchmark: orbit the camera for N frames, then quit");
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return cli.exit(e);
  }
  if (recover->count() > 0 && c.recover.empty()) c.recover = "yes";
  if (!c.recover.empty() && c.recover != "yes" && c.recover != "no" && c.recover != "ask") {
    std::cerr << "adaptex-studio: --recover: expected yes, no or ask, got '" << c.recover << "'\n";
    return 2;
  }
  double sx, sy, sh, sd;
  if (!c.stencil_place.empty() &&
      (std::sscanf(c.stencil_place.c_str(), "%lf,%lf,%lf,%lf", &sx, &sy, &sh, &sd) != 4 || !(sh >= 8))) {
    std::cerr << "adaptex-studio: --stencil-place: expected X,Y,HEIGHT,DEGREES with HEIGHT >= 8, e.g. 640,400,300,15\n";
    return 2;
  }
  if (std::sscanf(c.window.c_str(), "%dx%d", &c.width, &c.height) != 2 || c.width < 64 || c.height < 64) {
    std::cerr << "adaptex-studio: --window: expected WxH, e.g. 1280x800\n";
    return 2;
  }
  return std::nullopt;
}

/// Config and recovery folders from the command line and the environment.
AppOptions app_options(const CommandLine& c) {
  AppOptions opt;
  if (!c.config_dir.empty()) {
    opt.config_dir = c.config_dir;
  } else if (const char* x = std::getenv("XDG_CONFIG_HOME"); x && *x) {
    opt.config_dir = std::filesystem::path(x) / "adaptex";
  } else if (const char* h = std::getenv("HOME"); h && *h) {
    opt.config_dir = std::filesystem::path(h) / ".config" / "adaptex";
  }
  opt.recovery_dir = c.no_recovery          ? std::filesystem::path()
                     : c.recovery_dir.empty() ? opt.config_dir
                                              : std::filesystem::path(c.recovery_dir);
  // A scripted run never blocks on a question and never takes another session's work by guessing.
  const bool scripted = !c.replay.empty() || c.exit_after >= 0 || c.orbit_frames > 0;
  const std::string mode = !c.recover.empty() ? c.recover : scripted ? "no" : "ask";
  opt.recover = mode == "yes" ? RecoverMode::Yes : mode == "no" ? RecoverMode::No : RecoverMode::Ask;
  if (!opt.recovery_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(opt.recovery_dir, ec);
  }
  return opt;
}

/// SIGTERM / SIGINT end the session without questions (outputs written), read through a signalfd.
class SignalWatcher {
 public:
  SignalWatcher() {
    sigset_t sigs;
    sigemptyset(&sigs);
    sigaddset(&sigs, SIGTERM);
    sigaddset(&sigs, SIGINT);
    pthread_sigmask(SIG_BLOCK, &sigs, nullptr);
    fd_ = signalfd(-1, &sigs, SFD_NONBLOCK | SFD_CLOEXEC);
  }
  ~SignalWatcher() {
    if (fd_ >= 0) close(fd_);
  }
  SignalWatcher(const SignalWatcher&) = delete;
  SignalWatcher& operator=(const SignalWatcher&) = delete;
  /// True once per received signal.
  bool received() {
    signalfd_siginfo si;
    return fd_ >= 0 && read(fd_, &si, sizeof si) == ssize_t(sizeof si);
  }

 private:
  int fd_ = -1;
};

/// A GLFW window with an OpenGL 3.3 core context (GLFW initialized for its lifetime).
class Window {
 public:
  Window(int width, int height, bool vsync) {
    glfwSetErrorCallback(
        [](int code, const char* msg) { std::cerr << "adaptex-studio: GLFW error " << code << ": " << msg << "\n"; });
    if (!glfwInit()) {
      error_ = "cannot initialize GLFW (no display?)";
      return;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    window_ = glfwCreateWindow(width, height, "adaptex studio", nullptr, nullptr);
    if (!window_) {
      error_ = "cannot create an OpenGL 3.3 core window";
      return;
    }
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(vsync ? 1 : 0);
  }
  ~Window() {
    if (window_) glfwDestroyWindow(window_);
    glfwTerminate();
  }
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;
  GLFWwindow* get() const { return window_; }
  const std::string& error() const { return error_; }

 private:
  GLFWwindow* window_ = nullptr;
  std::string error_;
};

/// Dear ImGui with its GLFW + OpenGL 3 backends, attached to the App's window for its lifetime.
class ImGuiLayer {
 public:
  ImGuiLayer(GLFWwindow* w, WindowContext& wctx) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // layout is not persisted (keeps scripted runs reproducible)
    ImGui::StyleColorsDark();
    glfwSetWindowUserPointer(w, &wctx);
    install_callbacks(w);  // before ImGui's, which chain to ours
    ImGui_ImplGlfw_InitForOpenGL(w, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");
    int fw, fh, ww, wh;
    glfwGetFramebufferSize(w, &fw, &fh);
    glfwGetWindowSize(w, &ww, &wh);
    wctx.scale_x = ww > 0 ? double(fw) / ww : 1.0;
    wctx.scale_y = wh > 0 ? double(fh) / wh : 1.0;
    wctx.app->on_resize(fw, fh);
  }
  ~ImGuiLayer() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  ImGuiLayer(const ImGuiLayer&) = delete;
  ImGuiLayer& operator=(const ImGuiLayer&) = delete;
};

/// Applies the command line's settings and files to a new App. \return 2 if the stroke file is bad
int configure(App& app, const CommandLine& c) {
  app.view().show_ui = !c.hide_ui;
  app.view().wireframe = c.wireframe;
  app.view().checker = c.checker;
  app.view().pbr = c.pbr;
  PaintSessionOptions& o = app.session_options();
  if (c.texture_size > 0) o.texture_size = std::clamp(c.texture_size, 16, adaptex::kMaxTextureSize);
  app.set_texture_size_from_model(c.texture_size <= 0);
  app.set_unwrap(c.unwrap);
  o.adapt.mode = parse_adapt_mode(c.adapt_mode);
  if (c.no_refine) o.adapt.refine.enabled = false;
  if (!c.project.empty()) app.open_project(c.project);
  if (!c.mesh.empty()) app.request_open_file(c.mesh);  // nothing is unsaved yet: opens without asking
  app.recover_at_start();
  if (c.replay.empty()) return 0;
  try {
    AnyStrokeFile any = load_any_strokes(c.replay);  // version 2: opened as the layered document
    if (const StrokeFile* v1 = std::get_if<StrokeFile>(&any))
      app.replay(*v1);
    else
      app.open_material(std::get<MaterialStrokeFile>(std::move(any)));
  } catch (const std::exception& e) {
    std::cerr << "adaptex-studio: " << e.what() << "\n";
    return 2;
  }
  return 0;
}

/// The scripted steps of a run (tests, documentation, benchmarks), once the model is ready.
class Script {
 public:
  Script(const CommandLine& c, StudioUi& ui) : c_(c), decal_(c.decal), stencil_(c.stencil) {
    for (size_t k = 0; k < kInspectModes.size(); ++k)
      if (c.inspect == kInspectModes[k]) ui.show_inspect(int(k));
  }
  /// Before the UI: initial view, comparison, decal, "ready" line, orbit benchmark.
  void before_ui(App& app) {
    // A scripted run starts from the settled layout of its strokes, without waiting for a pause.
    if (!ready_printed_) app.settle_adaptation_now();
    // Loaded (or nothing to load: a start without a model counts its frames too).
    idle_ = app.idle() && !app.load_running();
    if (idle_ && (c_.yaw != 0 || c_.pitch != 0) && !view_applied_) {
      app.camera().yaw = c_.yaw * 3.14159265358979 / 180;
      app.camera().pitch = c_.pitch * 3.14159265358979 / 180;
      view_applied_ = true;
    }
    if (idle_ && c_.inspect == "compare" && !compare_requested_) {
      app.request_compare();
      compare_requested_ = true;
    }
    if (idle_ && !decal_.empty()) {
      load_stencil(app, decal_);
      app.project_decal(1.0);
      decal_.clear();
    }
    if (idle_ && !stencil_.empty()) {
      load_stencil(app, stencil_);
      stencil_.clear();
    }
    if (idle_ && c_.fixed_layout && !fixed_requested_) {
      app.toggle_fixed_layout();
      fixed_requested_ = true;
    }
    if (idle_ && !ready_printed_) {
      std::cout << "adaptex-studio: ready" << std::endl;
      app.reset_stats();  // statistics cover the interactive session, not the loading
      ready_printed_ = true;
    }
    if (c_.orbit_frames > 0 && app.has_model() && !app.load_running()) {
      app.camera().orbit(4.0, 0.0);
      if (++orbit_done_ >= c_.orbit_frames) app.quit_now();
    }
  }
  /// After rendering: --exit-after-frames (with the --screenshot of the last frame).
  void after_render(App& app) {
    if (!idle_ || c_.exit_after < 0) return;
    if (++idle_frames_ >= c_.exit_after) {
      if (!c_.screenshot.empty()) app.screenshot(c_.screenshot);
      app.quit_now();
    }
  }
  /// SIGTERM / SIGINT: with a --screenshot, one more frame for it; then quit without questions.
  void on_signal(App& app) {
    if (!c_.screenshot.empty() && c_.exit_after < 0) {
      app.screenshot(c_.screenshot);
      final_frame_ = true;
    } else {
      app.quit_now();
    }
  }
  bool final_frame() const { return final_frame_; }

 private:
  /// Loads \p image as the stencil, placed by --stencil-place.
  void load_stencil(App& app, const std::string& image) const {
    app.load_decal(image);
    double x, y, h, deg;
    if (!app.stencil() || std::sscanf(c_.stencil_place.c_str(), "%lf,%lf,%lf,%lf", &x, &y, &h, &deg) != 4) return;
    app.stencil()->centre = Vec2(x, y);
    app.stencil()->height = h;
    app.stencil()->angle = deg * 3.14159265358979 / 180;
  }

  const CommandLine& c_;
  std::string decal_, stencil_;
  bool idle_ = false, view_applied_ = false, ready_printed_ = false, compare_requested_ = false;
  bool fixed_requested_ = false;
  bool final_frame_ = false;
  int idle_frames_ = 0, orbit_done_ = 0;
};

/// One frame: input, background results, UI, scene, scripted steps, swap.
void frame(GLFWwindow* w, App& app, StudioUi& ui, Script& script, SignalWatcher& signals, bool measure) {
  glfwPollEvents();  // 1. input: keys act on the App at once, mouse events are queued
  if (script.final_frame()) app.quit_now();
  if (signals.received()) script.on_signal(app);
  app.begin_frame();  // 2. background results, autosave
  script.before_ui(app);
  ImGui_ImplOpenGL3_NewFrame();  // 3. UI
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  const ImGuiIO& io = ImGui::GetIO();
  app.set_ui_capture(io.WantCaptureMouse, io.WantCaptureKeyboard, io.WantTextInput);
  dispatch_mouse(ctx(w));  // routed by this frame's WantCaptureMouse (dabs are painted here)
  ui.draw(app);
  ImGui::Render();
  app.set_ui_capture(io.WantCaptureMouse, io.WantCaptureKeyboard, io.WantTextInput);
  app.render();  // 4. scene, then the UI on top
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  script.after_render(app);  // 5. scripted exit / screenshot, statistics
  if (measure) glFinish();   // measured frames include the GPU work
  app.end_frame();
  glfwSwapBuffers(w);
}

void write_stats(const App& app, const CommandLine& c) {
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
  j["window"] = c.window;
  j["texture_size"] = app.session_options().texture_size;
  j["adapt"] = to_string(app.session_options().adapt.mode);
  AtomicOutput out;  // all or nothing, as every other output
  std::ofstream o(out.add(c.stats_out));
  o << j.dump(1) << "\n";
  o.close();
  if (!o) throw OutputError(c.stats_out + ": cannot write the statistics");
  out.commit();
}

/// The --*-out outputs after the last frame. \return 1 if a scripted run reported an error
int write_outputs(App& app, const CommandLine& c) {
  if (!c.history_out.empty()) app.save_history(c.history_out);
  if (!c.texture_out.empty()) app.save_texture(c.texture_out);
  if (!c.export_dir.empty()) {
    app.export_obj(c.export_dir);
    // A layered material not settled yet: its export is written when the settle arrives.
    if (app.exporting() && !app.wait_idle(3600)) {
      std::cerr << "adaptex-studio: error: the export to " << c.export_dir << " did not finish\n";
      return 1;
    }
  }
  if (!c.stats_out.empty()) {
    try {
      write_stats(app, c);
    } catch (const std::exception& e) {
      std::cerr << "adaptex-studio: error: " << e.what() << "\n";
      return 1;
    }
  }
  for (const auto& m : app.messages())
    if (m.error && c.exit_after >= 0) return 1;
  return 0;
}

/// Runs the App in \p w until it quits. \return the exit code
int run(GLFWwindow* w, const CommandLine& c, SignalWatcher& signals) {
  App app(std::make_unique<GlRenderer>(), app_options(c));
  WindowContext wctx;
  wctx.app = &app;
  ImGuiLayer imgui(w, wctx);
  TabletPressure tablet(w);
  if (const auto p = test_pressure_from_env()) {
    app.set_pen_pressure(*p);  // the test hook: every dab at this pressure
    std::cout << "adaptex-studio: test hook: pen pressure " << *p << std::endl;
  } else if (tablet.available()) {
    wctx.tablet = &tablet;
    if (tablet.pens() > 0) std::cout << "adaptex-studio: " << tablet.describe() << std::endl;
  }
  if (const int rc = configure(app, c)) return rc;
  StudioUi ui;
  Script script(c, ui);
  const bool measure = c.orbit_frames > 0 || !c.stats_out.empty();
  while (!app.should_quit()) frame(w, app, ui, script, signals, measure);
  return write_outputs(app, c);
}

}  // namespace

int main(int argc, char** argv) {
  adaptex::keep_freed_memory_in_process_unless_disabled();
  CommandLine c;
  if (const auto rc = parse_command_line(argc, argv, c)) return *rc;
  SignalWatcher signals;
  Window window(c.width, c.height, !c.no_vsync);
  if (!window.get()) {
    std::cerr << "adaptex-studio: " << window.error() << "\n";
    return 1;
  }
  return run(window.get(), c, signals);
}
