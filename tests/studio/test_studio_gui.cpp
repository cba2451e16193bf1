/// \file test_studio_gui.cpp
/// Acceptance tests of adaptex-studio as a real program: under Xvfb with Mesa's software OpenGL, the
/// app is driven with real X input events (xdotool) and its outputs are checked; a SIGKILLed session
/// is recovered from its autosave; quitting, closing the window and opening another mesh with unsaved
/// strokes ask Save / Discard / Cancel; a right drag moves the decal stencil before it is projected,
/// and the screen-space brush keeps its size on the screen while zooming. Skipped (with a message) when
/// Xvfb or xdotool is missing.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <dirent.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "adaptex/io/image_io.h"
#include "adaptex/core/shapes.h"
#include "adaptex/io/mesh_io.h"
#include "test_support.h"

// Last: Xlib's macros (None, Bool, Status, ...) must not reach the headers above.
#include <X11/Xlib.h>

extern char** environ;

namespace {

namespace fs = std::filesystem;
using adaptex::test::TempDir;
using namespace std::chrono_literals;

std::optional<fs::path> find_program(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::stringstream ss(path ? path : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(ss, dir, ':'))
    if (!dir.empty() && access((fs::path(dir) / name).c_str(), X_OK) == 0) return fs::path(dir) / name;
  return std::nullopt;
}

/// Spawns \p args with extra environment variables, stdout+stderr appended to \p log.
pid_t spawn(const std::vector<std::string>& args, const std::vector<std::string>& env_extra, const fs::path& log) {
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e) env.emplace_back(*e);
  env.insert(env.end(), env_extra.begin(), env_extra.end());
  std::vector<char*> argv, envp;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  for (const auto& e : env) envp.push_back(const_cast<char*>(e.c_str()));
  envp.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&fa);
  return rc == 0 ? pid : -1;
}

/// Waits for \p pid to exit; \return exit status or -1 on timeout.
int wait_exit(pid_t pid, std::chrono::seconds timeout) {
  const auto t0 = std::chrono::steady_clock::now();
  while (std::chrono::steady_clock::now() - t0 < timeout) {
    int st = 0;
    if (waitpid(pid, &st, WNOHANG) == pid) return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
    std::this_thread::sleep_for(50ms);
  }
  return -1;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

bool wait_for(const std::function<bool()>& cond, std::chrono::seconds timeout) {
  const auto t0 = std::chrono::steady_clock::now();
  while (std::chrono::steady_clock::now() - t0 < timeout) {
    if (cond()) return true;
    std::this_thread::sleep_for(100ms);
  }
  return cond();
}

/// A private Xvfb server for one test.
class Xvfb {
 public:
  explicit Xvfb(const fs::path& log) {
    auto xvfb = find_program("Xvfb");
    if (!xvfb) return;
    for (int n = 91; n < 300; ++n) {
      std::ostringstream sock, lock, disp;
      sock << "/tmp/.X11-unix/X" << n;
      lock << "/tmp/.X" << n << "-lock";
      disp << ":" << n;
      if (fs::exists(sock.str()) || fs::exists(lock.str())) continue;
      display_ = disp.str();
      pid_ = spawn({xvfb->string(), display_, "-screen", "0", "1024x768x24", "-nolisten", "tcp"}, {}, log);
      // Tests run in parallel (ctest -j): another test may have taken the same display between the
      // check above and the spawn. Then our server exits at once, and the socket that appears is the
      // other one's; the display is ours only if its lock file names our server's pid.
      if (pid_ > 0 && wait_for([&] { return fs::exists(sock.str()) && lock_pid(lock.str()) > 0; }, 10s) &&
          lock_pid(lock.str()) == pid_)
        return;
      stop();
    }
  }
  ~Xvfb() { stop(); }
  bool ok() const { return pid_ > 0; }
  const std::string& display() const { return display_; }
  std::vector<std::string> env() const { return {"DISPLAY=" + display_, "LIBGL_ALWAYS_SOFTWARE=1"}; }

 private:
  /// The pid written in an X server's lock file (/tmp/.X<n>-lock), or -1.
  static pid_t lock_pid(const std::string& lock) {
    std::ifstream in(lock);
    long pid = -1;
    return (in >> pid) ? static_cast<pid_t>(pid) : -1;
  }
  void stop() {
    if (pid_ > 0) {
      kill(pid_, SIGTERM);
      if (wait_exit(pid_, 5s) < 0) kill(pid_, SIGKILL), wait_exit(pid_, 5s);
    }
    pid_ = -1;
  }
  pid_t pid_ = -1;
  std::string display_;
};

#define REQUIRE_X_TOOLS()                                                                       \
  do {                                                                                          \
    if (!find_program("Xvfb")) GTEST_SKIP() << "Xvfb not installed (apt-get install xvfb): skipping the GUI test"; \
    if (!find_program("xdotool")) GTEST_SKIP() << "xdotool not installed: skipping the GUI test";                \
  } while (0)

/// Runs `xdotool ARGS` on the display of \p x. \return its exit status
int xdo(const Xvfb& x, const std::string& args) {
  return std::system(("DISPLAY=" + x.display() + " xdotool " + args).c_str());
}

/// The studio's window ids (xdotool search).
std::vector<unsigned long> studio_windows(const Xvfb& x) {
  std::vector<unsigned long> ids;
  FILE* p = popen(("DISPLAY=" + x.display() + " xdotool search --name 'adaptex studio'").c_str(), "r");
  if (!p) return ids;
  char line[64];
  while (std::fgets(line, sizeof line, p)) ids.push_back(std::strtoul(line, nullptr, 10));
  pclose(p);
  return ids;
}

/// Asks the studio's window to close as a window manager's close button does (a WM_DELETE_WINDOW
/// client message; Xvfb runs no window manager). \return false if no window was found
bool close_window(const Xvfb& x) {
  const std::vector<unsigned long> ids = studio_windows(x);
  if (ids.empty()) return false;
  Display* d = XOpenDisplay(x.display().c_str());
  if (!d) return false;
  for (unsigned long id : ids) {
    XEvent e{};
    e.xclient.type = ClientMessage;
    e.xclient.window = id;
    e.xclient.message_type = XInternAtom(d, "WM_PROTOCOLS", False);
    e.xclient.format = 32;
    e.xclient.data.l[0] = static_cast<long>(XInternAtom(d, "WM_DELETE_WINDOW", False));
    e.xclient.data.l[1] = CurrentTime;
    XSendEvent(d, id, False, NoEventMask, &e);
  }
  XFlush(d);
  XCloseDisplay(d);
  return true;
}

/// Drops \p file on the studio's window at window pixel (x, y) as a file manager does: the XDND
/// protocol (XdndEnter / XdndPosition / XdndDrop, then the text/uri-list selection GLFW asks for).
/// \return false if no window took it within 10 s
bool drop_file(const Xvfb& x, const fs::path& file, int px, int py) {
  const std::vector<unsigned long> ids = studio_windows(x);
  if (ids.empty()) return false;
  Display* d = XOpenDisplay(x.display().c_str());
  if (!d) return false;
  const Window source = XCreateSimpleWindow(d, DefaultRootWindow(d), 0, 0, 1, 1, 0, 0, 0);
  const Atom selection = XInternAtom(d, "XdndSelection", False), uri_list = XInternAtom(d, "text/uri-list", False);
  XSetSelectionOwner(d, selection, source, CurrentTime);
  const auto send = [&](Window target, const char* type, long l1, long l2, long l3, long l4) {
    XEvent e{};
    e.xclient.type = ClientMessage;
    e.xclient.window = target;
    e.xclient.message_type = XInternAtom(d, type, False);
    e.xclient.format = 32;
    e.xclient.data.l[0] = static_cast<long>(source);
    e.xclient.data.l[1] = l1;
    e.xclient.data.l[2] = l2;
    e.xclient.data.l[3] = l3;
    e.xclient.data.l[4] = l4;
    XSendEvent(d, target, False, NoEventMask, &e);
  };
  const std::string uri = "file://" + file.string() + "\r\n";
  bool answered = false;
  for (unsigned long target : ids) {
    send(target, "XdndEnter", 5L << 24, static_cast<long>(uri_list), 0, 0);
    send(target, "XdndPosition", 0, (long(px) << 16) | py, CurrentTime,
         static_cast<long>(XInternAtom(d, "XdndActionCopy", False)));
    send(target, "XdndDrop", 0, CurrentTime, 0, 0);
  }
  XFlush(d);
  const auto t0 = std::chrono::steady_clock::now();
  while (!answered && std::chrono::steady_clock::now() - t0 < 10s) {
    while (XPending(d)) {
      XEvent e;
      XNextEvent(d, &e);
      if (e.type != SelectionRequest) continue;
      const XSelectionRequestEvent& r = e.xselectionrequest;
      XChangeProperty(d, r.requestor, r.property, r.target, 8, PropModeReplace,
                      reinterpret_cast<const unsigned char*>(uri.data()), static_cast<int>(uri.size()));
      XEvent n{};
      n.xselection.type = SelectionNotify;
      n.xselection.requestor = r.requestor;
      n.xselection.selection = r.selection;
      n.xselection.target = r.target;
      n.xselection.property = r.property;
      n.xselection.time = r.time;
      XSendEvent(d, r.requestor, False, NoEventMask, &n);
      XFlush(d);
      answered = true;
    }
    std::this_thread::sleep_for(20ms);
  }
  std::this_thread::sleep_for(500ms);  // the source window outlives the transfer (XdndFinished)
  XDestroyWindow(d, source);
  XCloseDisplay(d);
  return answered;
}

/// Occurrences of \p needle in the file \p log.
int count_in(const fs::path& log, const std::string& needle) {
  const std::string text = slurp(log);
  int n = 0;
  for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++n;
  return n;
}

bool running(pid_t pid) {
  int st = 0;
  return waitpid(pid, &st, WNOHANG) == 0;
}

/// A left-button drag across the sphere in the middle of an 800x600 window (right of the panel), at
/// height \p y.
std::string paint_drag(int y = 200) {
  std::ostringstream cmd;
  cmd << "mousemove 330 " << y << " sleep 0.3 mousedown 1 sleep 0.2";
  for (int px = 340; px <= 470; px += 10) cmd << " mousemove " << px << " " << y << " sleep 0.05";
  cmd << " sleep 0.2 mouseup 1 sleep 0.3 mousemove 700 80 sleep 0.5";
  return cmd.str();
}

const char* const kAsking = "unsaved strokes: asking Save / Discard / Cancel";
const char* const kCancelled = "cancelled: the unsaved strokes are kept";

/// Mean RGB of a screen rectangle (x, y from the top-left, inclusive ranges).
std::array<double, 3> mean_rgb(const adaptex::ImageRGBA8& shot, int x0, int x1, int y0, int y1) {
  std::array<double, 3> m{0, 0, 0};
  int n = 0;
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const uint8_t* p = shot.texel(x, shot.height - 1 - y);  // ImageRGBA8 rows are bottom-up
      for (int c = 0; c < 3; ++c) m[c] += p[c];
      ++n;
    }
  for (double& v : m) v /= n;
  return m;
}

/// Texture colour where the ray from the origin through \p dir meets the textured mesh (the sphere
/// seen from its centre), or nullopt.
std::optional<adaptex::Vec3> colour_towards(const adaptex::TexturedMesh& tm, const adaptex::ImageRGBA8& texture,
                                            adaptex::Vec3 dir) {
  dir.normalize();
  for (int f = 0; f < tm.mesh.num_faces(); ++f) {
    const auto& F = tm.mesh.faces[f];
    const adaptex::Vec3 a = tm.mesh.positions[F[0]], e1 = tm.mesh.positions[F[1]] - a, e2 = tm.mesh.positions[F[2]] - a;
    const adaptex::Vec3 pv = dir.cross(e2);
    const double det = e1.dot(pv);
    if (std::abs(det) < 1e-15) continue;
    const adaptex::Vec3 tv = -a;  // ray origin 0
    const double u = tv.dot(pv) / det, v = dir.dot(tv.cross(e1)) / det, t = e2.dot(tv.cross(e1)) / det;
    if (u < 0 || v < 0 || u + v > 1 || t <= 0) continue;
    const auto& U = tm.param.uv_faces[f];
    const adaptex::Vec2 uv = (1 - u - v) * tm.param.uv[U[0]] + u * tm.param.uv[U[1]] + v * tm.param.uv[U[2]];
    return adaptex::sample_bilinear(texture, uv.x(), uv.y());
  }
  return std::nullopt;
}

/// Waits for "adaptex-studio: ready" in \p log.
bool wait_ready(const fs::path& log) {
  return wait_for([&] { return slurp(log).find("adaptex-studio: ready") != std::string::npos; }, 120s);
}

/// SIGTERM (the scripted end: outputs and the --screenshot written). \return the exit status
int terminate(pid_t app) {
  kill(app, SIGTERM);
  const int rc = wait_exit(app, 60s);
  if (rc < 0) kill(app, SIGKILL), wait_exit(app, 5s);
  return rc;
}

/// The app on builtin:sphere in an 800x600 window without recovery files, writing its history to
/// \p hist at the end.
pid_t spawn_sphere(const Xvfb& x, const fs::path& dir, const fs::path& log, const fs::path& hist) {
  return spawn({ADAPTEX_STUDIO_PATH, "builtin:sphere", "--window", "800x600", "--texture-size", "256", "--config-dir",
                (dir / "cfg").string(), "--no-recovery", "--history-out", hist.string()},
               x.env(), log);
}

/// Each test gets a temporary folder and its own Xvfb server (skipped without Xvfb or xdotool).
class StudioGui : public ::testing::Test {
 protected:
  void SetUp() override {
    REQUIRE_X_TOOLS();
    x = std::make_unique<Xvfb>(dir.path / "xvfb.log");
    ASSERT_TRUE(x->ok()) << slurp(dir.path / "xvfb.log");
  }
  TempDir dir;
  std::unique_ptr<Xvfb> x;
};

TEST_F(StudioGui, XdotoolDragPaintsTheSurfaceUnderTheCursor) {
  const fs::path log = dir.path / "app.log", hist = dir.path / "history.json", tex = dir.path / "texture.png",
                 shot = dir.path / "shot.png", exp = dir.path / "export";
  const pid_t app = spawn({ADAPTEX_STUDIO_PATH, "builtin:sphere", "--window", "800x600", "--texture-size", "512",
                           "--config-dir", (dir.path / "cfg").string(), "--no-recovery", "--history-out",
                           hist.string(), "--texture-out", tex.string(), "--screenshot", shot.string(),
                           "--export-obj", exp.string()},
                          x->env(), log);
  ASSERT_GT(app, 0);
  ASSERT_TRUE(wait_ready(log)) << slurp(log);
  // A real drag across the middle of the sphere, right of the panels (x > 310).
  std::ostringstream cmd;
  cmd << "DISPLAY=" << x->display() << " xdotool mousemove 330 300 sleep 0.3 mousedown 1 sleep 0.2";
  for (int px = 340; px <= 470; px += 10) cmd << " mousemove " << px << " 300 sleep 0.05";
  cmd << " sleep 0.2 mouseup 1 sleep 0.3 mousemove 700 80 sleep 0.5";
  ASSERT_EQ(std::system(cmd.str().c_str()), 0);
  ASSERT_EQ(terminate(app), 0) << slurp(log);

  // 1. The stroke history gained dabs on the visible surface under the drag.
  std::ifstream hin(hist);
  const auto h = nlohmann::json::parse(hin);
  ASSERT_EQ(h["strokes"].size(), 1u) << h.dump();
  const auto& dabs = h["strokes"][0]["dabs"];
  ASSERT_GE(dabs.size(), 8u);
  double xmin = 1e9, xmax = -1e9;
  std::vector<adaptex::Vec3> pts;
  for (const auto& d : dabs) {
    const adaptex::Vec3 p(d[0].get<double>(), d[1].get<double>(), d[2].get<double>());
    EXPECT_NEAR(p.norm(), 1.0, 3e-3);  // on the unit sphere
    EXPECT_GT(p.z(), 0.5);              // the side facing the camera (+Z)
    EXPECT_NEAR(p.y(), 0.0, 0.05);      // along the horizontal drag through the centre
    xmin = std::min(xmin, p.x());
    xmax = std::max(xmax, p.x());
    pts.push_back(p);
  }
  EXPECT_LT(xmin, -0.15);
  EXPECT_GT(xmax, 0.2);

  // 2. The texture changed there: the texel under each dab centre has the brush colour.
  adaptex::TexturedMesh tm;
  for (const auto& e : fs::directory_iterator(exp))
    if (e.path().extension() == ".obj") tm = adaptex::read_textured_obj(e.path());
  ASSERT_GT(tm.mesh.num_faces(), 0);
  const adaptex::ImageRGBA8 texture = adaptex::read_image(tex);
  for (const auto& p : pts) {
    const auto col = colour_towards(tm, texture, p);  // the sphere is seen whole from its centre
    EXPECT_TRUE(col) << p.transpose();
    const adaptex::Vec3 c = col.value_or(adaptex::Vec3::Zero());
    EXPECT_NEAR(c.x(), 0.85, 0.03);
    EXPECT_NEAR(c.y(), 0.10, 0.03);
  }

  // 3. The screenshot shows the paint along the drag, and not elsewhere on the model.
  const adaptex::ImageRGBA8 s = adaptex::read_image(shot);
  ASSERT_EQ(s.width, 800);
  const auto on = mean_rgb(s, 360, 440, 296, 304), off = mean_rgb(s, 360, 440, 150, 170),
             bg = mean_rgb(s, 740, 790, 20, 60);
  EXPECT_GT(on[0], 120) << on[0] << " " << on[1] << " " << on[2];
  EXPECT_GT(on[0] - on[1], 80);
  EXPECT_LT(std::abs(off[0] - off[1]), 25) << off[0] << " " << off[1];  // unpainted (white, shaded)
  EXPECT_GT(off[0], 120);
  EXPECT_LT(bg[0], 100);  // the dark background
}

TEST_F(StudioGui, SigkilledSessionIsRecoveredFromTheAutosave) {
  const fs::path strokes = dir.path / "s.json", rec = dir.path / "rec", log = dir.path / "app.log";
  std::ofstream(strokes) << R"({"format":"adaptex.strokes","version":1,"strokes":[{"color":[0.1,0.3,0.9],
    "radius":0.2,"hardness":0.5,"dabs":[[0,0,1],[0.3,0.2,0.93]]}]})";
  const pid_t app = spawn({ADAPTEX_STUDIO_PATH, "builtin:sphere", "--window", "640x480", "--texture-size", "256",
                           "--replay", strokes.string(), "--config-dir", (dir.path / "cfg").string(),
                           "--recovery-dir", rec.string()},
                          x->env(), log);
  ASSERT_GT(app, 0);
  ASSERT_TRUE(wait_for([&] { return fs::exists(rec / "recovery.json"); }, 120s)) << slurp(log);
  kill(app, SIGKILL);
  wait_exit(app, 10s);
  ASSERT_TRUE(fs::exists(rec / "recovery.json"));

  const fs::path hist = dir.path / "h.json", log2 = dir.path / "app2.log";
  const pid_t again = spawn({ADAPTEX_STUDIO_PATH, "--window", "640x480", "--texture-size", "256", "--recover",
                             "--recovery-dir", rec.string(), "--config-dir", (dir.path / "cfg").string(),
                             "--history-out", hist.string(), "--exit-after-frames", "3"},
                            x->env(), log2);
  ASSERT_GT(again, 0);
  ASSERT_EQ(wait_exit(again, 120s), 0) << slurp(log2);
  EXPECT_NE(slurp(log2).find("recovery file found"), std::string::npos) << slurp(log2);
  std::ifstream hin(hist);
  const auto h = nlohmann::json::parse(hin);
  ASSERT_EQ(h["strokes"].size(), 1u);
  EXPECT_EQ(h["strokes"][0]["dabs"].size(), 2u);
  EXPECT_NEAR(h["strokes"][0]["dabs"][1][0].get<double>(), 0.3, 1e-12);
  // The recovered strokes were never saved: the scripted exit keeps them in the recovery file.
  EXPECT_TRUE(fs::exists(rec / "recovery.json"));
  EXPECT_NE(slurp(log2).find("unsaved strokes kept in"), std::string::npos) << slurp(log2);
}

// Ctrl+Q held for 0.3 s: a shortcut read through Dear ImGui is lost when press and release fall in one
// frame, which a loaded machine makes slow (seen with four GUI tests in parallel beside a build).
constexpr const char* kHoldCtrlQ = "keydown ctrl+q sleep 0.3 keyup ctrl+q";

/// Ctrl+Q, then \p key once \p log holds the quit prompt \p asked times: the app's exit code, -2 when
/// the prompt never came or a key was not sent, -1 when the app did not exit (it is killed then).
int quit_answering(const Xvfb& x, pid_t app, const fs::path& log, int asked, const char* key) {
  if (xdo(x, kHoldCtrlQ) != 0 || !wait_for([&] { return count_in(log, kAsking) == asked; }, 30s) ||
      xdo(x, key) != 0)
    return -2;
  const int rc = wait_exit(app, 60s);
  if (rc < 0) kill(app, SIGKILL), wait_exit(app, 5s);
  return rc;
}

TEST_F(StudioGui, QuittingWithUnsavedStrokesAsksAndCancelKeepsTheAppRunning) {
  const fs::path log = dir.path / "app.log", rec = dir.path / "rec", hist = dir.path / "h.json";
  const pid_t app = spawn({ADAPTEX_STUDIO_PATH, "builtin:sphere", "--window", "800x600", "--texture-size", "256",
                           "--config-dir", (dir.path / "cfg").string(), "--recovery-dir", rec.string(),
                           "--history-out", hist.string()},
                          x->env(), log);
  ASSERT_GT(app, 0);
  ASSERT_TRUE(wait_ready(log)) << slurp(log);
  ASSERT_EQ(xdo(*x, paint_drag()), 0);
  ASSERT_TRUE(wait_for([&] { return fs::exists(rec / "recovery.json"); }, 60s)) << slurp(log);

  // Ctrl+Q asks; Escape (Cancel) keeps the app running with its strokes.
  ASSERT_EQ(xdo(*x, kHoldCtrlQ), 0);
  ASSERT_TRUE(wait_for([&] { return count_in(log, kAsking) == 1; }, 30s)) << slurp(log);
  std::this_thread::sleep_for(1s);
  EXPECT_TRUE(running(app));
  ASSERT_EQ(xdo(*x, "key Escape"), 0);
  ASSERT_TRUE(wait_for([&] { return count_in(log, kCancelled) == 1; }, 30s)) << slurp(log);
  std::this_thread::sleep_for(1s);
  EXPECT_TRUE(running(app));
  EXPECT_TRUE(fs::exists(rec / "recovery.json"));

  // Closing the window asks too.
  ASSERT_TRUE(close_window(*x));
  ASSERT_TRUE(wait_for([&] { return count_in(log, kAsking) == 2; }, 30s)) << slurp(log);
  std::this_thread::sleep_for(1s);
  EXPECT_TRUE(running(app));
  ASSERT_EQ(xdo(*x, "key Escape"), 0);
  ASSERT_TRUE(wait_for([&] { return count_in(log, kCancelled) == 2; }, 30s)) << slurp(log);
  // As after the first answer: the closing pop-up holds the keyboard (ImGui's WantCaptureKeyboard)
  // until the next frame, and a frame can take longer than the log line under load.
  std::this_thread::sleep_for(1s);
  EXPECT_TRUE(running(app));

  // Discard (D) quits, and only then is the recovery file removed.
  ASSERT_EQ(quit_answering(*x, app, log, 3, "key d"), 0) << slurp(log);
  EXPECT_FALSE(fs::exists(rec / "recovery.json"));
  std::ifstream hin(hist);
  EXPECT_EQ(nlohmann::json::parse(hin)["strokes"].size(), 1u);  // the stroke was there until the end
}

TEST_F(StudioGui, OpeningAnotherMeshWithUnsavedStrokesAsks) {
  const fs::path log = dir.path / "app.log", hist = dir.path / "h.json";
  const pid_t app = spawn_sphere(*x, dir.path, log, hist);
  ASSERT_GT(app, 0);
  ASSERT_TRUE(wait_ready(log)) << slurp(log);
  ASSERT_EQ(xdo(*x, paint_drag()), 0);
  // File panel: type a mesh into the path field (below the menu bar) and press Open. Clicks hold the
  // button for 0.2 s: Dear ImGui 1.86 misses a press and release that fall in one (slow) frame.
  ASSERT_EQ(xdo(*x, "mousemove 110 59 mousedown 1 sleep 0.2 mouseup 1 sleep 0.3 type --delay 40 builtin:torus"), 0);
  ASSERT_EQ(xdo(*x, "sleep 0.3 mousemove 259 59 mousedown 1 sleep 0.2 mouseup 1"), 0);
  ASSERT_TRUE(wait_for([&] { return count_in(log, kAsking) == 1; }, 30s)) << slurp(log);
  ASSERT_EQ(xdo(*x, "key Escape"), 0);
  ASSERT_TRUE(wait_for([&] { return count_in(log, kCancelled) == 1; }, 30s)) << slurp(log);
  std::this_thread::sleep_for(2s);
  EXPECT_EQ(slurp(log).find("loaded builtin:torus"), std::string::npos) << slurp(log);  // nothing was opened
  // Open asks again; Discard (D) opens the torus.
  ASSERT_EQ(xdo(*x, "mousemove 259 59 mousedown 1 sleep 0.2 mouseup 1"), 0);
  ASSERT_TRUE(wait_for([&] { return count_in(log, kAsking) == 2; }, 30s)) << slurp(log);
  ASSERT_EQ(xdo(*x, "key d"), 0);
  ASSERT_TRUE(wait_for([&] { return slurp(log).find("loaded builtin:torus") != std::string::npos; }, 120s))
      << slurp(log);
  ASSERT_EQ(terminate(app), 0) << slurp(log);
  std::ifstream hin(hist);
  EXPECT_EQ(nlohmann::json::parse(hin)["strokes"].size(), 0u);  // the torus' empty history
}

TEST_F(StudioGui, StencilPreviewMovesWithARightDragAndOnlyTheCoveredRegionIsPainted) {
  adaptex::write_png(dir.path / "green.png", adaptex::ImageRGBA8(64, 64, {0, 220, 0, 255}));
  const fs::path log = dir.path / "app.log", hist = dir.path / "h.json", tex = dir.path / "t.png",
                 shot = dir.path / "shot.png", exp = dir.path / "export";
  // The stencil starts centred (400, 300), 300 pixels high, over the sphere, which is framed in the
  // middle of the 800x600 window; the panels are hidden so that the whole view takes the mouse.
  const pid_t app = spawn({ADAPTEX_STUDIO_PATH, "builtin:sphere", "--window", "800x600", "--texture-size", "512",
                           "--adapt", "none", "--hide-ui", "--stencil", (dir.path / "green.png").string(),
                           "--config-dir", (dir.path / "cfg").string(), "--no-recovery", "--history-out",
                           hist.string(), "--texture-out", tex.string(), "--export-obj", exp.string(),
                           "--screenshot", shot.string()},
                          x->env(), log);
  ASSERT_GT(app, 0);
  ASSERT_TRUE(wait_ready(log)) << slurp(log);
  ASSERT_TRUE(wait_for([&] { return slurp(log).find("loaded as a stencil") != std::string::npos; }, 30s));
  // A right drag 200 pixels to the right moves the stencil (nothing is painted, the view does not turn).
  ASSERT_EQ(xdo(*x, "mousemove 400 300 sleep 0.3 mousedown 3 sleep 0.2 mousemove 450 300 sleep 0.1 mousemove 500 300 "
                   "sleep 0.1 mousemove 550 300 sleep 0.1 mousemove 600 300 sleep 0.3 mouseup 3 sleep 0.3"),
            0);
  ASSERT_EQ(xdo(*x, "mousemove 790 590 sleep 0.3 key p"), 0);
  ASSERT_TRUE(wait_for([&] { return slurp(log).find("projected the stencil") != std::string::npos; }, 30s))
      << slurp(log);
  std::this_thread::sleep_for(1s);
  ASSERT_EQ(terminate(app), 0) << slurp(log);

  // One decal stroke, looking through the moved stencil: right of the view's centre.
  std::ifstream hin(hist);
  const auto h = nlohmann::json::parse(hin);
  ASSERT_EQ(h["strokes"].size(), 1u) << h.dump();
  const auto& st = h["strokes"][0];
  const double fx = st["target"][0].get<double>() - st["eye"][0].get<double>();
  EXPECT_GT(fx, 0.05) << st.dump();
  // The surface under the moved stencil is green, the rest of the front untouched (white).
  adaptex::TexturedMesh tm;
  for (const auto& e : fs::directory_iterator(exp))
    if (e.path().extension() == ".obj") tm = adaptex::read_textured_obj(e.path());
  ASSERT_GT(tm.mesh.num_faces(), 0);
  const adaptex::ImageRGBA8 texture = adaptex::read_image(tex);
  for (double y : {-0.3, 0.0, 0.3}) {
    for (double px : {0.55, 0.7}) {
      const auto c = colour_towards(tm, texture, adaptex::Vec3(px, y, std::sqrt(1 - px * px - y * y)));
      ASSERT_TRUE(c);
      EXPECT_NEAR(c->y(), 220 / 255.0, 0.05) << px << " " << y;
      EXPECT_LT(c->x(), 0.1) << px << " " << y;
    }
    for (double px : {-0.6, -0.3, 0.0, 0.2}) {
      const auto c = colour_towards(tm, texture, adaptex::Vec3(px, y, std::sqrt(1 - px * px - y * y)));
      ASSERT_TRUE(c);
      EXPECT_GT(c->x(), 0.95) << px << " " << y;  // the white paper
    }
    const auto back = colour_towards(tm, texture, adaptex::Vec3(0.7, y, -0.5));
    ASSERT_TRUE(back);
    EXPECT_GT(back->x(), 0.95);  // hidden from the eye: never painted
  }
  // The screenshot: the semi-transparent preview is where the stencil was moved (green over the
  // background right of the sphere), not where it started (the left of the sphere stays white).
  const adaptex::ImageRGBA8 s = adaptex::read_image(shot);
  ASSERT_EQ(s.width, 800);
  const auto moved = mean_rgb(s, 620, 680, 200, 400), start = mean_rgb(s, 290, 380, 260, 340),
             outside = mean_rgb(s, 20, 120, 200, 400);
  EXPECT_GT(moved[1] - moved[0], 40) << moved[0] << " " << moved[1];
  EXPECT_LT(std::abs(outside[1] - outside[0]), 15) << outside[0] << " " << outside[1];
  EXPECT_LT(std::abs(start[1] - start[0]), 15) << start[0] << " " << start[1];
  EXPECT_GT(start[0], 120);
}

/// Radius of the brush circle around window pixel (cx, cy): the distance to the first dark pixel of
/// its outer ring to the right, on the sphere's light surface. -1 if none.
int circle_radius(const adaptex::ImageRGBA8& shot, int cx, int cy) {
  for (int x = cx + 2; x < shot.width; ++x) {
    const uint8_t* p = shot.texel(x, shot.height - 1 - cy);
    if (p[0] < 90 && p[1] < 90 && p[2] < 90) return x - cx;
  }
  return -1;
}

/// Right edge of the sphere on row \p y: the last light pixel (the background is dark grey).
int sphere_right_edge(const adaptex::ImageRGBA8& shot, int y) {
  int edge = -1;
  for (int x = 0; x < shot.width; ++x)
    if (shot.texel(x, shot.height - 1 - y)[0] > 120) edge = x;
  return edge;
}

TEST_F(StudioGui, BrushKeepsItsOnScreenSizeWhileZooming) {
  // Two sessions with the default (screen-space) brush: one as framed, one zoomed in with the wheel.
  // In each: a short stroke, then the cursor rests on the sphere and the last frame is captured.
  int radius[2], edge[2];
  double world[2];
  for (int zoomed = 0; zoomed < 2; ++zoomed) {
    const char* const names[2][3] = {{"app0.log", "s0.png", "h0.json"}, {"app1.log", "s1.png", "h1.json"}};
    const fs::path log = dir.path / names[zoomed][0], shot = dir.path / names[zoomed][1],
                   hist = dir.path / names[zoomed][2];
    const pid_t app = spawn({ADAPTEX_STUDIO_PATH, "builtin:sphere", "--window", "800x600", "--texture-size", "256",
                             "--adapt", "none", "--config-dir", (dir.path / "cfg").string(), "--no-recovery",
                             "--history-out", hist.string(), "--screenshot", shot.string()},
                            x->env(), log);
    ASSERT_GT(app, 0);
    ASSERT_TRUE(wait_ready(log)) << slurp(log);
    // Three wheel steps up over the view (zoom in) for the second session. The first scrolls right
    // after the cursor enters the side panel: the panel's scroll, not the view's. (This does not catch
    // routing by the previous frame's capture flag: at these frame rates the move and the wheel fall in
    // different frames; tried with the old order, it passed too.)
    const std::string wheel = zoomed ? "mousemove 400 300 sleep 0.3 click 4 sleep 0.2 click 4 sleep 0.2 click 4"
                                     : "mousemove 600 300 sleep 0.3 mousemove 150 300 click 4 click 4 click 4";
    ASSERT_EQ(xdo(*x, wheel + " sleep 0.3"), 0);
    ASSERT_EQ(xdo(*x, "mousemove 380 200 sleep 0.3 mousedown 1 sleep 0.2 mousemove 400 200 sleep 0.1 mousemove 420 200 "
                     "sleep 0.2 mouseup 1 sleep 0.3 mousemove 400 300 sleep 0.2 mousemove 401 300 sleep 1"),
              0);
    ASSERT_EQ(terminate(app), 0) << slurp(log);
    const adaptex::ImageRGBA8 s = adaptex::read_image(shot);
    ASSERT_EQ(s.width, 800);
    radius[zoomed] = circle_radius(s, 401, 300);
    edge[zoomed] = sphere_right_edge(s, 300);
    std::ifstream hin(hist);
    const auto h = nlohmann::json::parse(hin);
    ASSERT_EQ(h["strokes"].size(), 1u);
    world[zoomed] = h["strokes"][0]["radius"].get<double>();
  }
  EXPECT_GT(edge[1], edge[0] + 40) << edge[0] << " " << edge[1];  // the wheel zoomed in over the view only
  EXPECT_NEAR(radius[0], 25, 3);                                  // the default 25-pixel radius
  EXPECT_NEAR(radius[1], radius[0], 1) << radius[0] << " " << radius[1];  // the same size on screen
  EXPECT_LT(world[1], world[0] * 0.85) << world[0] << " " << world[1];    // so smaller on the model
}

TEST_F(StudioGui, FileMenuOpensAMeshThroughTheInAppBrowser) {
  // ADAPTEX_STUDIO_DIALOG=builtin: the in-app browser instead of GTK's dialog (which xdotool did not
  // drive without a window manager). The browser opens with the keyboard in its Name field.
  const fs::path log = dir.path / "app.log", mesh = dir.path / "ring.obj";
  adaptex::write_obj(mesh, adaptex::shapes::torus(24, 12, 1.0, 0.3), nullptr);
  std::vector<std::string> env = x->env();
  env.push_back("ADAPTEX_STUDIO_DIALOG=builtin");
  const pid_t app = spawn({ADAPTEX_STUDIO_PATH, "builtin:sphere", "--window", "800x600", "--texture-size", "256",
                           "--config-dir", (dir.path / "cfg").string(), "--no-recovery"},
                          env, log);
  ASSERT_GT(app, 0);
  ASSERT_TRUE(wait_ready(log)) << slurp(log);
  // Ctrl+O (File > Open mesh...), held across frames as Ctrl+Q above; the browser says when it is open.
  ASSERT_EQ(xdo(*x, "mousemove 600 300 sleep 0.2 keydown ctrl+o sleep 0.3 keyup ctrl+o"), 0);
  // Printed once the browser's Name field has the keyboard.
  ASSERT_TRUE(wait_for([&] { return slurp(log).find("file browser: Open mesh") != std::string::npos; }, 60s))
      << slurp(log);
  ASSERT_EQ(xdo(*x, "type --delay 40 '" + mesh.string() + "'"), 0);
  ASSERT_EQ(xdo(*x, "sleep 0.3 keydown Return sleep 0.3 keyup Return"), 0);
  ASSERT_TRUE(wait_for([&] { return slurp(log).find("loaded " + mesh.string()) != std::string::npos; }, 120s))
      << slurp(log);
  ASSERT_EQ(terminate(app), 0) << slurp(log);
}

// ---- recovery after a crash, however the app starts ------------------------------------------------

/// A key held across frames (Dear ImGui 1.86 and a slow frame lose a press and release in one frame).
std::string hold(const std::string& key) { return "keydown " + key + " sleep 0.3 keyup " + key; }

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in, nullptr, false);
}

/// The strokes of a project or recovery file (empty when it is missing or unreadable).
nlohmann::json project_strokes(const fs::path& p) {
  const auto j = read_json(p);
  if (!j.is_object() || !j.contains("strokes")) return nlohmann::json::array();
  return j["strokes"]["strokes"];
}

/// recovery*.json files in \p dir.
std::vector<fs::path> recovery_files(const fs::path& dir) {
  std::vector<fs::path> out;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string n = it->path().filename().string();
    if (n.rfind("recovery", 0) == 0 && it->path().extension() == ".json") out.push_back(it->path());
  }
  return out;
}

/// The dabs of each stroke of a stroke array (what a history, a project and a recovery file share).
std::vector<nlohmann::json> dabs_of(const nlohmann::json& strokes) {
  std::vector<nlohmann::json> out;
  for (const auto& s : strokes) out.push_back(s["dabs"]);
  return out;
}

/// A project file with no strokes on builtin:sphere, as Save As writes one.
void write_empty_project(const fs::path& p) {
  std::ofstream(p) << R"({"format":"adaptex.studio-project","version":1,"mesh":"builtin:sphere",)"
                   << R"("strokes":{"format":"adaptex.strokes","version":1,"strokes":[]}})";
}

/// True if the studio's adaptation worker thread (named adaptex-adapt) is running or runnable now.
bool adapt_worker_running(pid_t pid) {
  const fs::path tasks = "/proc/" + std::to_string(pid) + "/task";
  std::error_code ec;
  for (fs::directory_iterator it(tasks, ec), end; !ec && it != end; it.increment(ec)) {
    if (slurp(it->path() / "comm").rfind("adaptex-adapt", 0) != 0) continue;
    const std::string stat = slurp(it->path() / "stat");
    const size_t close = stat.rfind(')');
    if (close != std::string::npos && close + 2 < stat.size() && stat[close + 2] == 'R') return true;
  }
  return false;
}

enum class Start { Bare, Model, Project, Scripted };  // Bare: no argument (Xlib defines None)

std::string start_name(const ::testing::TestParamInfo<Start>& info) {
  switch (info.param) {
    case Start::Bare: return "NoArgument";
    case Start::Model: return "WithTheModel";
    case Start::Project: return "WithTheProject";
    case Start::Scripted: return "ScriptedReplay";
  }
  return "?";
}

class StudioRecoveryGui : public StudioGui, public ::testing::WithParamInterface<Start> {};
class StudioModalGui : public StudioRecoveryGui {};

/// Files with extension \p ext in \p dir.
int count_files(const fs::path& dir, const std::string& ext) {
  int n = 0;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) n += it->path().extension() == ext;
  return n;
}

// Session 1 opens a project, paints a stroke and is killed (SIGKILL) once the stroke is autosaved.
// Session 2 starts with the model, the project or nothing, answers the prompt with R (Recover) and
// Ctrl+S: the project file then holds exactly the autosaved strokes (the project path was kept).
TEST_P(StudioRecoveryGui, Kill9ThenRecoverGivesTheStrokesBackAndKeepsTheProjectPath) {
  const fs::path project = dir.path / "work.adaptex", rec = dir.path / "rec", cfg = dir.path / "cfg",
                 log1 = dir.path / "app1.log", log2 = dir.path / "app2.log", hist = dir.path / "h.json";
  write_empty_project(project);
  const std::vector<std::string> common = {"--window", "800x600", "--texture-size", "256", "--config-dir",
                                           cfg.string(), "--recovery-dir", rec.string()};
  std::vector<std::string> args = {ADAPTEX_STUDIO_PATH, project.string()};
  args.insert(args.end(), common.begin(), common.end());
  const pid_t first = spawn(args, x->env(), log1);
  ASSERT_GT(first, 0);
  ASSERT_TRUE(wait_ready(log1)) << slurp(log1);
  ASSERT_EQ(xdo(*x, paint_drag()), 0);
  ASSERT_TRUE(wait_for([&] { return project_strokes(rec / "recovery.json").size() == 1; }, 60s)) << slurp(log1);
  kill(first, SIGKILL);
  wait_exit(first, 10s);
  const nlohmann::json autosaved = read_json(rec / "recovery.json");
  ASSERT_EQ(autosaved["project"], project.string());  // the recovery file names its project and mesh
  ASSERT_EQ(autosaved["mesh"], "builtin:sphere");

  args = {ADAPTEX_STUDIO_PATH};
  if (GetParam() == Start::Model) args.push_back("builtin:sphere");
  if (GetParam() == Start::Project) args.push_back(project.string());
  args.insert(args.end(), common.begin(), common.end());
  args.insert(args.end(), {"--history-out", hist.string()});
  const pid_t again = spawn(args, x->env(), log2);
  ASSERT_GT(again, 0);
  ASSERT_TRUE(wait_for([&] { return count_in(log2, "dialog: Recover unsaved strokes?") == 1; }, 120s))
      << slurp(log2);
  ASSERT_TRUE(wait_ready(log2)) << slurp(log2);  // the model given on the command line is loaded
  const int loaded = count_in(log2, "loaded builtin:sphere");
  ASSERT_EQ(xdo(*x, hold("r")), 0);
  ASSERT_TRUE(wait_for([&] { return count_in(log2, "recovered 1 stroke on " + project.string()) == 1; }, 30s))
      << slurp(log2);
  ASSERT_TRUE(wait_for([&] { return count_in(log2, "loaded builtin:sphere") > loaded; }, 120s)) << slurp(log2);
  ASSERT_EQ(xdo(*x, "mousemove 600 300 sleep 0.2 " + hold("ctrl+s")), 0);
  ASSERT_TRUE(wait_for([&] { return count_in(log2, "saved project " + project.string()) == 1; }, 30s))
      << slurp(log2);
  ASSERT_EQ(terminate(again), 0) << slurp(log2);
  EXPECT_EQ(project_strokes(project), autosaved["strokes"]["strokes"]);  // identical strokes, in the project
  EXPECT_EQ(dabs_of(read_json(hist)["strokes"]), dabs_of(autosaved["strokes"]["strokes"]));
  EXPECT_TRUE(recovery_files(rec).empty());  // saved: no recovery file is left
  EXPECT_EQ(slurp(log2).find("Assertion"), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(AnyStart, StudioRecoveryGui, ::testing::Values(Start::Bare, Start::Model, Start::Project),
                         start_name);

TEST_F(StudioGui, Kill9WhileTheAdaptationWorkerRunsIsRecoveredWithTheSameStrokes) {
  const fs::path rec = dir.path / "rec", cfg = dir.path / "cfg", log1 = dir.path / "app1.log",
                 log2 = dir.path / "app2.log", hist = dir.path / "h.json";
  const std::vector<std::string> common = {ADAPTEX_STUDIO_PATH, "builtin:sphere", "--window", "800x600",
                                           "--texture-size", "1024", "--config-dir", cfg.string(),
                                           "--recovery-dir", rec.string()};
  const pid_t first = spawn(common, x->env(), log1);
  ASSERT_GT(first, 0);
  ASSERT_TRUE(wait_ready(log1)) << slurp(log1);
  // Strokes until one is autosaved while the adaptation worker (density-flow, the default) runs.
  bool caught = false;
  size_t strokes = 0;
  for (int k = 0; k < 6 && !caught; ++k) {
    ASSERT_EQ(xdo(*x, paint_drag(170 + 25 * k)), 0);
    ++strokes;
    const auto t0 = std::chrono::steady_clock::now();
    while (!caught && std::chrono::steady_clock::now() - t0 < 5s) {
      caught = project_strokes(rec / "recovery.json").size() == strokes && adapt_worker_running(first);
      if (caught) kill(first, SIGKILL);
      std::this_thread::sleep_for(10ms);
    }
  }
  if (!caught) kill(first, SIGKILL);
  wait_exit(first, 10s);
  ASSERT_TRUE(caught) << "the adaptation worker was never seen running after an autosave\n" << slurp(log1);
  const nlohmann::json autosaved = read_json(rec / "recovery.json");
  ASSERT_EQ(autosaved["strokes"]["strokes"].size(), strokes);

  std::vector<std::string> args = common;
  args.insert(args.end(), {"--history-out", hist.string()});
  const pid_t again = spawn(args, x->env(), log2);
  ASSERT_GT(again, 0);
  ASSERT_TRUE(wait_for([&] { return count_in(log2, "dialog: Recover unsaved strokes?") == 1; }, 120s))
      << slurp(log2);
  ASSERT_TRUE(wait_ready(log2)) << slurp(log2);
  ASSERT_EQ(xdo(*x, hold("r")), 0);
  ASSERT_TRUE(wait_for([&] { return count_in(log2, "loaded builtin:sphere") == 2; }, 120s)) << slurp(log2);
  ASSERT_EQ(terminate(again), 0) << slurp(log2);
  EXPECT_EQ(dabs_of(read_json(hist)["strokes"]), dabs_of(autosaved["strokes"]["strokes"]));
  // Recovered, not saved: the scripted end keeps them in a recovery file (the same one).
  EXPECT_EQ(project_strokes(rec / "recovery.json"), autosaved["strokes"]["strokes"]);
}

TEST_F(StudioGui, TwoScriptedReplaysWithTheSameRecoveryFolderBothExport) {
  const fs::path strokes = dir.path / "s.json", rec = dir.path / "rec";
  std::ofstream(strokes) << R"({"format":"adaptex.strokes","version":1,"strokes":[{"color":[0.1,0.3,0.9],
    "radius":0.2,"hardness":0.5,"dabs":[[0,0,1],[0.3,0.2,0.93]]}]})";
  std::string first_recovery;
  for (int run = 0; run < 2; ++run) {
    const fs::path out = dir.path / ("out" + std::to_string(run)), log = dir.path / ("run" + std::to_string(run) + ".log");
    const pid_t app = spawn({ADAPTEX_STUDIO_PATH, "builtin:sphere", "--replay", strokes.string(), "--export-obj",
                             out.string(), "--recovery-dir", rec.string(), "--config-dir", (dir.path / "cfg").string(),
                             "--window", "640x480", "--texture-size", "256", "--exit-after-frames", "30"},
                            x->env(), log);
    ASSERT_GT(app, 0);
    ASSERT_EQ(wait_exit(app, 180s), 0) << slurp(log);
    EXPECT_EQ(count_files(out, ".obj"), 1) << slurp(log);
    EXPECT_EQ(count_files(out, ".png"), 1) << slurp(log);
    EXPECT_EQ(slurp(log).find("dialog:"), std::string::npos) << slurp(log);  // never asked
    if (run == 0) {
      ASSERT_TRUE(fs::exists(rec / "recovery.json"));  // its replayed strokes, never saved
      first_recovery = slurp(rec / "recovery.json");
    } else {
      // --recover no (the scripted default): the first run's file is left as it was, and says so.
      EXPECT_NE(slurp(log).find("recovery file " + (rec / "recovery.json").string() + " left untouched (--recover no)"),
                std::string::npos)
          << slurp(log);
      EXPECT_EQ(slurp(rec / "recovery.json"), first_recovery);
    }
  }
}

// Every modal of the app, in every start mode, each opened while other windows appear: the recovery
// prompt on the first frame (with the loading window), the in-app file browser, an error, the unsaved
// strokes question. Dear ImGui 1.86 aborted with `blocking_modal != NULL` on the first of these.
TEST_P(StudioModalGui, EveryModalOpensAndClosesWithoutAborting) {
  const fs::path project = dir.path / "work.adaptex", rec = dir.path / "rec", log = dir.path / "app.log",
                 mesh = dir.path / "ring.obj", strokes = dir.path / "s.json";
  write_empty_project(project);
  adaptex::write_obj(mesh, adaptex::shapes::torus(24, 12, 1.0, 0.3), nullptr);
  std::ofstream(strokes) << R"({"format":"adaptex.strokes","version":1,"strokes":[{"color":[0.1,0.3,0.9],
    "radius":0.2,"hardness":0.5,"dabs":[[0,0,1],[0.3,0.2,0.93]]}]})";
  fs::create_directories(rec);
  std::ofstream(rec / "recovery.json") << R"({"format":"adaptex.studio-project","version":1,"mesh":"builtin:torus",)"
                                       << R"("strokes":{"format":"adaptex.strokes","version":1,"strokes":[{)"
                                       << R"("color":[0.9,0.3,0.1],"radius":0.2,"dabs":[[0,0,1]]}]}})";
  const std::string orphan = slurp(rec / "recovery.json");
  std::vector<std::string> args = {ADAPTEX_STUDIO_PATH};
  if (GetParam() == Start::Model || GetParam() == Start::Scripted) args.push_back("builtin:sphere");
  if (GetParam() == Start::Project) args.push_back(project.string());
  if (GetParam() == Start::Scripted) args.insert(args.end(), {"--replay", strokes.string()});
  args.insert(args.end(), {"--window", "800x600", "--texture-size", "256", "--config-dir", (dir.path / "cfg").string(),
                           "--recovery-dir", rec.string(), "--recover", "ask"});
  std::vector<std::string> env = x->env();
  env.push_back("ADAPTEX_STUDIO_DIALOG=builtin");
  const pid_t app = spawn(args, env, log);
  ASSERT_GT(app, 0);
  const auto shown = [&](const std::string& title, int n) {
    return wait_for([&] { return count_in(log, "dialog: " + title) >= n; }, 60s);
  };
  // 1. The recovery prompt; Esc (Later) keeps the file.
  ASSERT_TRUE(shown("Recover unsaved strokes?", 1)) << slurp(log);
  ASSERT_TRUE(wait_ready(log)) << slurp(log);
  ASSERT_EQ(xdo(*x, "mousemove 600 300 sleep 0.2 " + hold("Escape")), 0);
  ASSERT_TRUE(wait_for([&] { return count_in(log, "for later") == 1; }, 30s)) << slurp(log);
  // 2. Without a model: the in-app browser opens one.
  int browsed = 0;
  if (GetParam() == Start::Bare) {
    ASSERT_EQ(xdo(*x, "sleep 0.5 " + hold("ctrl+o")), 0);
    ASSERT_TRUE(shown("Choose a file", ++browsed)) << slurp(log);
    ASSERT_TRUE(wait_for([&] { return count_in(log, "file browser: Open mesh") == browsed; }, 30s));
    ASSERT_EQ(xdo(*x, "type --delay 40 '" + mesh.string() + "'"), 0);
    ASSERT_EQ(xdo(*x, "sleep 0.3 " + hold("Return")), 0);
    ASSERT_TRUE(wait_for([&] { return count_in(log, "loaded " + mesh.string()) == 1; }, 120s)) << slurp(log);
  }
  // 3. Unsaved strokes: Ctrl+Q asks, Esc cancels.
  ASSERT_EQ(xdo(*x, "sleep 0.5 " + paint_drag()), 0);
  ASSERT_EQ(xdo(*x, hold("ctrl+q")), 0);
  ASSERT_TRUE(shown("Unsaved strokes", 1)) << slurp(log);
  ASSERT_EQ(xdo(*x, hold("Escape")), 0);
  ASSERT_TRUE(wait_for([&] { return count_in(log, kCancelled) == 1; }, 30s)) << slurp(log);
  // 4. The browser again, a mesh that does not exist: Save / Discard / Cancel first (D), then an error.
  ASSERT_EQ(xdo(*x, "sleep 0.5 " + hold("ctrl+o")), 0);
  ASSERT_TRUE(shown("Choose a file", ++browsed)) << slurp(log);
  ASSERT_TRUE(wait_for([&] { return count_in(log, "file browser: Open mesh") == browsed; }, 30s));
  ASSERT_EQ(xdo(*x, "type --delay 40 '" + (dir.path / "missing.obj").string() + "'"), 0);
  ASSERT_EQ(xdo(*x, "sleep 0.3 " + hold("Return")), 0);
  ASSERT_TRUE(shown("Unsaved strokes", 2)) << slurp(log);
  ASSERT_EQ(xdo(*x, hold("d")), 0);
  ASSERT_TRUE(shown("Error", 1)) << slurp(log);
  ASSERT_EQ(xdo(*x, "sleep 0.3 " + hold("Return")), 0);  // Enter (or Esc) closes it
  std::this_thread::sleep_for(1s);
  ASSERT_TRUE(running(app)) << slurp(log);
  ASSERT_EQ(terminate(app), 0) << slurp(log);
  EXPECT_EQ(slurp(log).find("Assertion"), std::string::npos) << slurp(log);
  EXPECT_EQ(slurp(rec / "recovery.json"), orphan);  // Later: untouched
}

INSTANTIATE_TEST_SUITE_P(EveryStart, StudioModalGui,
                         ::testing::Values(Start::Bare, Start::Model, Start::Project, Start::Scripted), start_name);

// Started with no argument, the prompt is answered Later (Esc); dropping the mesh the strokes belong to
// on the window asks again, and Recover (R) gives them back on it.
TEST_F(StudioGui, DroppingTheMeshOfALaterRecoveryOnTheWindowOffersItAgain) {
  const fs::path rec = dir.path / "rec", log = dir.path / "app.log", hist = dir.path / "h.json",
                 mesh = dir.path / "ball.obj";
  adaptex::write_obj(mesh, adaptex::shapes::sphere(32, 16), nullptr);
  fs::create_directories(rec);
  std::ofstream(rec / "recovery.json") << R"({"format":"adaptex.studio-project","version":1,"mesh":")" << mesh.string()
                                       << R"(","strokes":{"format":"adaptex.strokes","version":1,"strokes":[{)"
                                       << R"("color":[0.9,0.3,0.1],"radius":0.2,"dabs":[[0,0,1],[0.2,0,0.98]]}]}})";
  const pid_t app = spawn({ADAPTEX_STUDIO_PATH, "--window", "800x600", "--texture-size", "256", "--config-dir",
                           (dir.path / "cfg").string(), "--recovery-dir", rec.string(), "--history-out", hist.string()},
                          x->env(), log);
  ASSERT_GT(app, 0);
  ASSERT_TRUE(wait_for([&] { return count_in(log, "dialog: Recover unsaved strokes?") == 1; }, 60s)) << slurp(log);
  ASSERT_EQ(xdo(*x, "mousemove 600 300 sleep 0.2 " + hold("Escape")), 0);
  ASSERT_TRUE(wait_for([&] { return count_in(log, "for later") == 1; }, 30s)) << slurp(log);
  // Dropped again if nothing came of it (seen once in 8 runs under load: GLFW asked for the selection
  // and the drop callback never came), as a user would.
  bool offered = false;
  int drops = 0;
  for (; drops < 3 && !offered; ++drops) {
    ASSERT_TRUE(drop_file(*x, mesh, 500, 300)) << slurp(log);
    offered = wait_for([&] { return count_in(log, "dialog: Recover unsaved strokes?") == 2; }, 20s);
  }
  ASSERT_TRUE(offered) << drops << " drops\n" << slurp(log);
  ASSERT_EQ(xdo(*x, hold("r")), 0);
  ASSERT_TRUE(wait_for([&] { return count_in(log, "recovered 1 stroke on " + mesh.string()) == 1; }, 30s))
      << slurp(log);
  // Loaded after the recovery (the drop's own load may have been replaced by it).
  ASSERT_TRUE(wait_for(
      [&] {
        const std::string text = slurp(log);
        const size_t loaded = text.rfind("loaded " + mesh.string());
        return loaded != std::string::npos && loaded > text.find("recovered 1 stroke");
      },
      120s))
      << slurp(log);
  ASSERT_EQ(terminate(app), 0) << slurp(log);
  const auto h = read_json(hist)["strokes"];
  ASSERT_EQ(h.size(), 1u);
  EXPECT_EQ(h[0]["dabs"], nlohmann::json::parse("[[0,0,1],[0.2,0,0.98]]"));
}

TEST_F(StudioGui, EscapeClosesAnOpenMenu) {
  const fs::path log = dir.path / "app.log", hist = dir.path / "h.json";
  const pid_t app = spawn_sphere(*x, dir.path, log, hist);
  ASSERT_GT(app, 0);
  ASSERT_TRUE(wait_ready(log)) << slurp(log);
  // File menu, then Esc; a drag on the view then paints (with the menu open, the press would only close it).
  ASSERT_EQ(xdo(*x, "mousemove 18 9 sleep 0.2 mousedown 1 sleep 0.2 mouseup 1 sleep 0.5 mousemove 600 300 sleep 0.3 " +
                        hold("Escape") + " sleep 0.3"),
            0);
  ASSERT_EQ(xdo(*x, paint_drag(300)), 0);
  ASSERT_EQ(terminate(app), 0) << slurp(log);
  EXPECT_EQ(read_json(hist)["strokes"].size(), 1u);
}

TEST_F(StudioGui, TheViewKeepsDrawingWhileTheDesktopFileDialogIsOpen) {
  const fs::path log = dir.path / "app.log", shot = dir.path / "shot.png";
  const pid_t app = spawn({ADAPTEX_STUDIO_PATH, "builtin:sphere", "--window", "800x600", "--texture-size", "256",
                           "--config-dir", (dir.path / "cfg").string(), "--no-recovery", "--screenshot",
                           shot.string()},
                          x->env(), log);
  ASSERT_GT(app, 0);
  ASSERT_TRUE(wait_ready(log)) << slurp(log);
  ASSERT_EQ(xdo(*x, "mousemove 600 300 sleep 0.2 " + hold("ctrl+o")), 0);
  if (!wait_for([&] { return count_in(log, "dialog: File dialog") == 1; }, 30s)) {
    terminate(app);
    GTEST_SKIP() << "no desktop file dialog (built without GTK 3?)\n" << slurp(log);
  }
  std::this_thread::sleep_for(1s);
  // SIGTERM is handled by the frame loop: it ends the app only if frames are still drawn.
  ASSERT_EQ(terminate(app), 0) << slurp(log);
  const adaptex::ImageRGBA8 s = adaptex::read_image(shot);
  EXPECT_EQ(s.width, 800);
}

}  // namespace

// ---- a model with its own UV atlas and texture --------------------------------------------------

/// Three unit squares in a row facing +Z: on the left (x in [-1.5,-0.5]) a chart of its own, as a fan
/// with one degenerate UV triangle; in the middle and on the right two squares on one chart, the right
/// one mirrored (its texels shared with the middle one, which the file lists first). The 128^2
/// texture: yellow where u < 0.25, green elsewhere in the shared chart, blue in the other one, grey
/// outside. Written as DIR/twins.obj + twins.mtl + twins.png.
struct AtlasModel {
  adaptex::ImageRGBA8 texture;
  std::vector<std::array<adaptex::Vec2, 3>> face_uvs;  ///< Per face, its corners' UVs as written.
};

AtlasModel write_atlas_model(const fs::path& dir) {
  AtlasModel m;
  const int n = 128;
  m.texture = adaptex::ImageRGBA8(n, n, {128, 128, 128, 255});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double u = (i + 0.5) / n, v = (j + 0.5) / n;
      std::array<std::uint8_t, 3> c{128, 128, 128};
      if (v > 0.03 && v < 0.97 && u > 0.03 && u < 0.47) c = u < 0.25 ? std::array<std::uint8_t, 3>{230, 200, 30}
                                                                    : std::array<std::uint8_t, 3>{30, 160, 60};
      if (v > 0.03 && v < 0.97 && u > 0.53 && u < 0.97) c = {40, 60, 200};
      std::uint8_t* px = m.texture.texel(i, j);
      px[0] = c[0], px[1] = c[1], px[2] = c[2];
    }
  adaptex::write_png(dir / "twins.png", m.texture);
  std::ofstream(dir / "twins.mtl") << "newmtl paint\nKd 1 1 1\nmap_Kd twins.png\n";
  std::ofstream obj(dir / "twins.obj");
  obj << "mtllib twins.mtl\nusemtl paint\n";
  int v = 0, t = 0;
  const double left[3] = {-0.5, 0.5, -1.5};  // file order: shared chart, its mirror, the other chart
  auto uv_of = [&](int square, double x, double y) {
    const double lx = x - left[square], vv = 0.05 + 0.9 * (y + 0.5);
    if (square == 0) return adaptex::Vec2(0.05 + 0.4 * lx, vv);
    if (square == 1) return adaptex::Vec2(0.45 - 0.4 * lx, vv);  // mirrored onto square 0's texels
    return adaptex::Vec2(0.55 + 0.4 * lx, vv);
  };
  for (int s = 0; s < 3; ++s) {
    const double x0 = left[s];
    const std::vector<adaptex::Vec2> corners = {{x0, -0.5}, {x0 + 1, -0.5}, {x0 + 1, 0.5}, {x0, 0.5}, {x0 + 0.5, 0}};
    for (const auto& c : corners) obj << "v " << c.x() << " " << c.y() << " 0\n";
    std::vector<adaptex::Vec2> uvs;
    for (const auto& c : corners) uvs.push_back(uv_of(s, c.x(), c.y()));
    if (s == 2) uvs.push_back(uvs[4]), uvs.push_back(uvs[4]);  // the degenerate triangle's corners
    for (const auto& q : uvs) obj << "vt " << q.x() << " " << q.y() << "\n";
    // A fan of four triangles around the centre (corner 4), counter-clockwise seen from +Z.
    for (int k = 0; k < 4; ++k) {
      int a = k, b = (k + 1) % 4, ta = a, tb = b;
      if (s == 2 && k == 3) ta = 5, tb = 6;  // all three UVs at the centre: degenerate
      obj << "f " << v + 5 << "/" << t + 5 << " " << v + a + 1 << "/" << t + ta + 1 << " " << v + b + 1 << "/"
          << t + tb + 1 << "\n";
      m.face_uvs.push_back({uvs[4], uvs[size_t(ta)], uvs[size_t(tb)]});
    }
    v += 5;
    t += int(uvs.size());
  }
  return m;
}

/// True where \p shot differs from the background (taken at the right edge of row \p y0).
bool on_model(const adaptex::ImageRGBA8& shot, int x, int y, int y0) {
  const auto bg = mean_rgb(shot, shot.width - 3, shot.width - 3, y0, y0);
  const auto c = mean_rgb(shot, x, x, y, y);
  return std::abs(c[0] - bg[0]) + std::abs(c[1] - bg[1]) + std::abs(c[2] - bg[2]) > 40;
}

/// The columns the three-square model spans on row \p y (its left end may lie under the panel: found
/// from its right end and its height, a third of its width).
std::pair<int, int> model_span(const adaptex::ImageRGBA8& shot, int y) {
  int x1 = shot.width - 1;
  while (x1 > 0 && !on_model(shot, x1, y, y)) --x1;
  int top = y, bottom = y;
  while (top > 0 && on_model(shot, x1 - 10, top - 1, y)) --top;
  while (bottom < shot.height - 1 && on_model(shot, x1 - 10, bottom + 1, y)) ++bottom;
  return {x1 - 3 * (bottom - top + 1), x1};
}

enum class Hue { Yellow, Green, Blue, Red, Other };
Hue hue(const std::array<double, 3>& c) {
  const double r = c[0], g = c[1], b = c[2];
  if (r > 1.6 * g && r > 1.6 * b) return Hue::Red;
  if (r > 2 * b && g > 2 * b && r > 0.8 * g) return Hue::Yellow;
  if (g > 1.5 * r && g > 1.5 * b) return Hue::Green;
  if (b > 1.5 * r && b > 1.5 * g) return Hue::Blue;
  return Hue::Other;
}
std::string hue_name(Hue h) {
  const char* names[] = {"yellow", "green", "blue", "red", "other"};
  return names[int(h)];
}

TEST_F(StudioGui, ATexturedModelOpensOnItsAtlasAndAStrokeIsSavedReopenedAndExportedOnIt) {
  const AtlasModel model = write_atlas_model(dir.path);
  const fs::path obj = dir.path / "twins.obj", cfg = dir.path / "cfg", log1 = dir.path / "app1.log",
                 log2 = dir.path / "app2.log", log3 = dir.path / "app3.log", before = dir.path / "before.png",
                 after = dir.path / "after.png", exp = dir.path / "export", project = dir.path / "twins.adaptex";
  const std::vector<std::string> common = {"--window", "1000x600", "--config-dir", cfg.string(), "--no-recovery"};
  auto args = [&](std::vector<std::string> a) {
    a.insert(a.begin(), ADAPTEX_STUDIO_PATH);
    a.insert(a.end(), common.begin(), common.end());
    return a;
  };

  // 1. Opened, it shows its own texture on its own layout: blue, yellow | green, green | yellow (the
  //    mirrored square).
  pid_t app = spawn(args({obj.string(), "--adapt", "none", "--exit-after-frames", "3", "--screenshot", before.string()}),
                    x->env(), log1);
  ASSERT_GT(app, 0);
  ASSERT_EQ(wait_exit(app, 120s), 0) << slurp(log1);
  EXPECT_NE(slurp(log1).find("painting on its artist's UV atlas"), std::string::npos) << slurp(log1);
  const adaptex::ImageRGBA8 s1 = adaptex::read_image(before);
  const int cy = 300;
  const auto [x0, x1] = model_span(s1, cy);
  ASSERT_GT(x1 - x0, 300);
  ASSERT_GT(x0 + (x1 - x0) / 6, 320) << "the model is under the panel";
  const double w = x1 - x0;
  auto at = [&](const adaptex::ImageRGBA8& s, double fx, int y) {
    const int px = int(x0 + fx * w);
    return mean_rgb(s, px - 2, px + 2, y - 2, y + 2);
  };
  const std::vector<std::pair<double, Hue>> pattern = {
      {2.5 / 12, Hue::Blue}, {5.0 / 12, Hue::Yellow}, {7.0 / 12, Hue::Green}, {9.0 / 12, Hue::Green},
      {11.0 / 12, Hue::Yellow}};
  for (const auto& [fx, h] : pattern) EXPECT_EQ(hue_name(hue(at(s1, fx, cy))), hue_name(h)) << fx;

  // 2. A vertical red stroke on the middle square's yellow part; quit, Save.
  app = spawn(args({obj.string(), "--adapt", "none"}), x->env(), log2);
  ASSERT_GT(app, 0);
  ASSERT_TRUE(wait_ready(log2)) << slurp(log2);
  const int sx = int(x0 + 5 * w / 12);
  std::ostringstream drag;
  drag << "mousemove " << sx << " " << cy - 50 << " sleep 0.3 mousedown 1 sleep 0.2";
  for (int y = cy - 45; y <= cy + 50; y += 5) drag << " mousemove " << sx << " " << y << " sleep 0.05";
  drag << " sleep 0.2 mouseup 1 sleep 0.5 mousemove 950 80 sleep 0.3";
  ASSERT_EQ(xdo(*x, drag.str()), 0);
  ASSERT_EQ(quit_answering(*x, app, log2, 1, "key s"), 0) << slurp(log2);
  const nlohmann::json saved = read_json(project);
  ASSERT_TRUE(saved.is_object()) << slurp(log2);
  EXPECT_EQ(saved["layout"], "atlas");
  EXPECT_EQ(saved["adapt"]["texture_size"], 128);  // the texture's own size
  ASSERT_EQ(project_strokes(project).size(), 1u);

  // 3. Reopened from the project: the stroke on the middle square and, through the shared texels, on
  //    its mirror image on the right; the rest of the pattern as it was. Exported as OBJ.
  app = spawn(args({project.string(), "--exit-after-frames", "3", "--screenshot", after.string(), "--export-obj",
                    exp.string()}),
              x->env(), log3);
  ASSERT_GT(app, 0);
  ASSERT_EQ(wait_exit(app, 120s), 0) << slurp(log3);
  const adaptex::ImageRGBA8 s2 = adaptex::read_image(after);
  EXPECT_EQ(hue_name(hue(at(s2, 5.0 / 12, cy))), hue_name(Hue::Red));
  EXPECT_EQ(hue_name(hue(at(s2, 11.0 / 12, cy))), hue_name(Hue::Red));  // the mirrored square
  for (double fx : {7.0 / 12, 9.0 / 12}) EXPECT_EQ(hue_name(hue(at(s2, fx, cy))), hue_name(Hue::Green)) << fx;
  EXPECT_EQ(hue_name(hue(at(s2, 2.5 / 12, cy))), hue_name(Hue::Blue));
  EXPECT_EQ(hue_name(hue(at(s2, 4.25 / 12, cy))), hue_name(Hue::Yellow));  // beside the stroke

  // The exported UVs are the input's, corner by corner; the exported texture is the input's outside
  // the stroke (u = 0.15 on the shared chart) and red on it.
  fs::path out_obj;
  for (const auto& e : fs::directory_iterator(exp))
    if (e.path().extension() == ".obj") out_obj = e.path();
  ASSERT_FALSE(out_obj.empty()) << slurp(log3);
  const adaptex::TexturedMesh tm = adaptex::read_textured_obj(out_obj);
  ASSERT_EQ(size_t(tm.mesh.num_faces()), model.face_uvs.size());
  double uv_error = 0;
  for (size_t f = 0; f < model.face_uvs.size(); ++f)
    for (int k = 0; k < 3; ++k)
      uv_error = std::max(uv_error, (tm.param.uv[size_t(tm.param.uv_faces[f][k])] - model.face_uvs[f][size_t(k)]).norm());
  EXPECT_LT(uv_error, 1e-5);
  fs::path out_png = out_obj;
  out_png.replace_extension(".png");
  const adaptex::ImageRGBA8 tex = adaptex::read_image(out_png);
  ASSERT_EQ(tex.width, 128);
  int same = 0, differ = 0, red = 0;
  for (int j = 6; j < 122; ++j)
    for (int i = 6; i < 122; ++i) {
      // The gutter between the charts, and the part of the third chart that only its degenerate
      // triangle would cover (no texel stands for it).
      if (i > 58 && i < 98) continue;
      const double u = (i + 0.5) / 128;
      const std::uint8_t *a = tex.texel(i, j), *b = model.texture.texel(i, j);
      const bool equal = std::abs(a[0] - b[0]) <= 1 && std::abs(a[1] - b[1]) <= 1 && std::abs(a[2] - b[2]) <= 1;
      if (std::abs(u - 0.15) > 0.08) {
        same += equal, differ += !equal;
      } else {
        red += a[0] > 180 && a[1] < 80 && a[2] < 80;
      }
    }
  EXPECT_EQ(differ, 0) << same;
  EXPECT_GT(same, 5000);
  EXPECT_GT(red, 100);

  // 4. With adaptation (the default schedule: after every stroke), the same stroke painted by hand
  //    adapts the atlas in the background; quit, Save.
  const fs::path log4 = dir.path / "app4.log", log5 = dir.path / "app5.log", adapted = dir.path / "adapted.png",
                 exp2 = dir.path / "export2", project2 = dir.path / "adapted.adaptex";
  app = spawn(args({obj.string(), "--adapt", "density-flow"}), x->env(), log4);
  ASSERT_GT(app, 0);
  ASSERT_TRUE(wait_ready(log4)) << slurp(log4);
  ASSERT_EQ(xdo(*x, drag.str()), 0);
  ASSERT_TRUE(wait_for([&] { return count_in(log4, "adapted the artist's atlas") >= 1; }, 300s)) << slurp(log4);
  fs::remove(project);  // Save writes the suggested path
  ASSERT_EQ(quit_answering(*x, app, log4, 1, "key s"), 0) << slurp(log4);
  ASSERT_EQ(project_strokes(project).size(), 1u) << slurp(log4);
  fs::rename(project, project2);

  // 5. Reopened: adapted again to the same layout; the stroke on both mirror images; exported: the
  //    UVs changed, and corners that shared a UV still do.
  app = spawn(args({project2.string(), "--exit-after-frames", "3", "--screenshot", adapted.string(), "--export-obj",
                    exp2.string()}),
              x->env(), log5);
  ASSERT_GT(app, 0);
  ASSERT_EQ(wait_exit(app, 300s), 0) << slurp(log5);
  EXPECT_EQ(count_in(log5, "adapted the artist's atlas"), 1) << slurp(log5);
  const adaptex::ImageRGBA8 s3 = adaptex::read_image(adapted);
  EXPECT_EQ(hue_name(hue(at(s3, 5.0 / 12, cy))), hue_name(Hue::Red));
  EXPECT_EQ(hue_name(hue(at(s3, 11.0 / 12, cy))), hue_name(Hue::Red));  // the mirrored square
  EXPECT_EQ(hue_name(hue(at(s3, 2.5 / 12, cy))), hue_name(Hue::Blue));
  fs::path obj2;
  for (const auto& e : fs::directory_iterator(exp2))
    if (e.path().extension() == ".obj") obj2 = e.path();
  ASSERT_FALSE(obj2.empty()) << slurp(log5);
  const adaptex::TexturedMesh tm2 = adaptex::read_textured_obj(obj2);
  ASSERT_EQ(size_t(tm2.mesh.num_faces()), model.face_uvs.size());
  auto uv2 = [&](size_t f, int k) { return tm2.param.uv[size_t(tm2.param.uv_faces[f][k])]; };
  double moved = 0;
  int shared = 0;
  for (size_t f = 0; f < model.face_uvs.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      moved = std::max(moved, (uv2(f, k) - model.face_uvs[f][size_t(k)]).norm());
      if (f >= 11) continue;  // not the degenerate triangle (the last), which the library gives an area
      for (size_t g = 0; g < 11; ++g)
        for (int l = 0; l < 3; ++l)
          if ((f != g || k != l) && (model.face_uvs[f][size_t(k)] - model.face_uvs[g][size_t(l)]).norm() < 1e-9) {
            ++shared;
            EXPECT_LT((uv2(f, k) - uv2(g, l)).norm(), 1e-5) << f << " " << g;
          }
    }
  EXPECT_GT(moved, 1e-3);
  EXPECT_GE(shared, 16);  // the shared chart's corners, on both squares
}

// ---- a layered material, painted by hand ------------------------------------------------------

namespace {

/// The centre of widget \p id as the app last traced it (ADAPTEX_STUDIO_UI_TRACE=1), if it has.
std::optional<std::pair<int, int>> widget(const fs::path& log, const std::string& id) {
  const std::string text = slurp(log), needle = "adaptex-studio: ui " + id + " at ";
  const size_t at = text.rfind(needle);
  if (at == std::string::npos) return std::nullopt;
  std::istringstream in(text.substr(at + needle.size()));
  int x = 0, y = 0;
  if (!(in >> x >> y)) return std::nullopt;
  return std::make_pair(x, y);
}

/// Clicks widget \p id where it is now (held across frames, as keys are). The press waits until the
/// traced position has stayed put for 0.6 s with the pointer on it: panels still move in the first
/// frames after the start, and a press on where a widget was misses it.
bool click_widget(const Xvfb& x, const fs::path& log, const std::string& id) {
  std::optional<std::pair<int, int>> w;
  if (!wait_for([&] { return (w = widget(log, id)).has_value(); }, 30s)) return false;
  const auto settled = [&] {
    const auto before = widget(log, id);
    std::ostringstream move;
    move << "mousemove " << before->first << " " << before->second << " sleep 0.6";
    if (xdo(x, move.str()) != 0) return false;
    return (w = widget(log, id)) == before;
  };
  if (!wait_for(settled, 30s)) return false;
  // Long enough that a slow frame (llvmpipe, a composite running) sees the press and the release apart.
  return xdo(x, "mousedown 1 sleep 1.0 mouseup 1 sleep 0.8") == 0;
}

/// Clicks the collapsing header \p header until widget \p inside is traced (up to three clicks, 10 s
/// apart): a click in the first frames after the start can miss while the panels still move.
bool open_section(const Xvfb& x, const fs::path& log, const std::string& header,
                  const std::string& inside) {
  for (int i = 0; i < 3; ++i) {
    if (!click_widget(x, log, header)) return false;
    if (wait_for([&] { return widget(log, inside).has_value(); }, 10s)) return true;
  }
  return false;
}

std::string read_file_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// A vertical left drag at x = 520 down the ball (y 240 to 420).
std::string vertical_drag() {
  std::ostringstream vertical;
  vertical << "mousemove 520 240 sleep 0.3 mousedown 1 sleep 0.2";
  for (int y = 250; y <= 420; y += 10) vertical << " mousemove 520 " << y << " sleep 0.05";
  vertical << " sleep 0.2 mouseup 1 sleep 0.5";
  return vertical.str();
}

/// A layered material painted by hand on a ball (1000x650 window, texture 256): its files, the
/// studio started on the mesh, saved + exported, reopened from the project, and `adaptex paint`.
struct BallSession {
  fs::path mesh, log, log2, log3, hist, project, glb, shot, lit, exp, cli;
  std::vector<std::string> env, common;

  BallSession(const fs::path& dir, const Xvfb& x, const std::vector<std::string>& extra_env)
      : mesh(dir / "ball.obj"), log(dir / "app.log"), log2(dir / "app2.log"), log3(dir / "app3.log"),
        hist(dir / "ball_strokes.json"), project(dir / "ball.adaptex"), glb(dir / "ball.glb"),
        shot(dir / "reopened.png"), lit(dir / "lit.png"), exp(dir / "export"),
        cli(dir / "cli"), env(x.env()),
        common({"--window", "1000x650", "--texture-size", "256", "--config-dir", (dir / "cfg").string(),
                "--no-recovery"}) {
    adaptex::write_obj(mesh, adaptex::shapes::sphere(32, 16, 1.0), nullptr);
    env.push_back("ADAPTEX_STUDIO_UI_TRACE=1");
    env.insert(env.end(), extra_env.begin(), extra_env.end());
  }
  /// The studio on the mesh, writing the strokes to `hist` on exit. \return its pid (<= 0: failed)
  pid_t start() const {
    std::vector<std::string> args = {ADAPTEX_STUDIO_PATH, mesh.string(), "--history-out", hist.string()};
    args.insert(args.end(), common.begin(), common.end());
    const pid_t app = spawn(args, env, log);
    return app > 0 && wait_ready(log) ? app : -1;
  }
  /// Save As (the suggested ball.adaptex beside the mesh), Export GLB (ball.glb), quit. Clicked again
  /// if a slow frame lost the click (saving and exporting twice write the same files).
  bool save_export_quit(const Xvfb& x, pid_t app) const {
    const auto click_until = [&](const std::string& id, const fs::path& file) {
      for (int attempt = 0; attempt < 3; ++attempt)
        if (click_widget(x, log, id) && wait_for([&] { return fs::exists(file); }, 20s)) return true;
      return false;
    };
    return click_until("Save As", project) && click_until("Export GLB", glb) && terminate(app) == 0;
  }
  /// Reopens the saved project for 3 frames, exporting OBJ on exit. \return its screenshot
  std::optional<adaptex::ImageRGBA8> reopen() const {
    std::vector<std::string> args = {ADAPTEX_STUDIO_PATH, project.string(), "--exit-after-frames", "3",
                                     "--screenshot",      shot.string(),    "--export-obj",          exp.string()};
    args.insert(args.end(), common.begin(), common.end());
    const pid_t app = spawn(args, env, log2);
    if (app <= 0 || wait_exit(app, 300s) != 0) return std::nullopt;
    return adaptex::read_image(shot);
  }
  /// Reopens the saved project, presses V (the lit material preview) and quits. \return its screenshot
  std::optional<adaptex::ImageRGBA8> reopen_lit(const Xvfb& x) const {
    std::vector<std::string> args = {ADAPTEX_STUDIO_PATH, project.string(), "--screenshot", lit.string()};
    args.insert(args.end(), common.begin(), common.end());
    const pid_t app = spawn(args, env, log3);
    if (app <= 0 || !wait_ready(log3)) return std::nullopt;
    if (xdo(x, "mousemove 520 560 sleep 0.3 " + hold("v") + " sleep 0.5") != 0 || terminate(app) != 0)
      return std::nullopt;
    return adaptex::read_image(lit);
  }
  /// What `adaptex paint` writes for the saved stroke file: the same GLB and OBJ files, byte for byte.
  void expect_exports_are_adaptex_paints() const {
    const auto r = adaptex::test::run_cli("paint '" + mesh.string() + "' --strokes '" + hist.string() +
                                          "' --size 256 -o '" + cli.string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(read_file_bytes(glb), read_file_bytes(cli / "ball.glb"));
    for (const char* f : {"ball.obj", "ball.png", "ball_roughness.png", "ball_metallic.png", "ball_normal.png",
                          "ball_height.png"})
      EXPECT_EQ(read_file_bytes(exp / f), read_file_bytes(cli / f)) << f;
  }
};

}  // namespace

TEST_F(StudioGui, PaintsBaseColourAndMetalOnTwoLayersShowsThemLitAndExportsWhatAdaptexPaintWrites) {
  const BallSession b(dir.path, *x, {});
  const pid_t app = b.start();
  ASSERT_GT(app, 0) << slurp(b.log);
  // 1. Base colour (the default red brush) on layer 1: a horizontal drag across the ball.
  ASSERT_EQ(xdo(*x, paint_drag(330)), 0);
  // 2. The Material window (Brush panel: Layers and channels); Add layer: layer 2, active. The brush
  //    paints roughness and metallic (0.2, 1: a polished metal): a vertical drag.
  ASSERT_TRUE(open_section(*x, b.log, "Layers and channels", "Add layer")) << slurp(b.log);
  ASSERT_TRUE(click_widget(*x, b.log, "Add layer"));
  ASSERT_TRUE(wait_for([&] { return widget(b.log, "layer 2 visible").has_value(); }, 30s)) << slurp(b.log);
  std::this_thread::sleep_for(1s);  // the panel settles (its hint line goes)
  ASSERT_TRUE(click_widget(*x, b.log, "Base colour"));
  ASSERT_TRUE(click_widget(*x, b.log, "Roughness"));
  ASSERT_TRUE(click_widget(*x, b.log, "Metallic"));
  ASSERT_EQ(xdo(*x, vertical_drag()), 0);
  // 3. Hide layer 2, then undo (the hide, not the stroke: checked in the saved file below).
  ASSERT_TRUE(click_widget(*x, b.log, "layer 2 visible"));
  ASSERT_EQ(xdo(*x, "mousemove 520 500 sleep 0.3 " + hold("ctrl+z") + " sleep 0.5"), 0);
  // 4. Save As, Export GLB, quit.
  ASSERT_TRUE(b.save_export_quit(*x, app)) << slurp(b.log);

  // The strokes, as a stroke file of version 2: base colour on layer 1, roughness on layer 2, shown.
  const nlohmann::json h = read_json(b.hist);
  ASSERT_TRUE(h.is_object()) << slurp(b.log);
  EXPECT_EQ(h["version"], 2);
  ASSERT_EQ(h["layers"].size(), 2u) << h.dump();
  ASSERT_EQ(h["layers"][0]["strokes"].size(), 1u);
  ASSERT_EQ(h["layers"][1]["strokes"].size(), 1u);
  EXPECT_TRUE(h["layers"][0]["strokes"][0]["channels"].contains("base_color"));
  EXPECT_EQ(h["layers"][1]["strokes"][0]["channels"], nlohmann::json({{"roughness", 0.2}, {"metallic", 1.0}}));
  EXPECT_EQ(h["layers"][1]["visible"], true);
  const nlohmann::json p = read_json(b.project);
  EXPECT_EQ(p["version"], 2);
  EXPECT_EQ(p["material"]["layers"], h["layers"]);

  // 5. Reopened from the project: the same layers; exported as OBJ on exit.
  const auto s = b.reopen();
  ASSERT_TRUE(s.has_value()) << slurp(b.log2);
  const auto red = mean_rgb(*s, 420, 450, 326, 334), white = mean_rgb(*s, 420, 450, 200, 210);
  EXPECT_GT(red[0] - red[1], 80) << red[0] << " " << red[1];  // layer 1's base colour on the drag
  EXPECT_LT(std::abs(white[0] - white[1]), 25) << white[0] << " " << white[1];  // unpainted above it

  // 6. What `adaptex paint` writes for the saved stroke file: the same GLB and OBJ files, byte for byte.
  b.expect_exports_are_adaptex_paints();

  // 7. Reopened again, the lit preview toggled with V: the polished metal stroke of layer 2 (white in
  //    the base colour) mirrors the darker ground, the white paper beside it hardly changes.
  const auto l = b.reopen_lit(*x);
  ASSERT_TRUE(l.has_value()) << slurp(b.log3);
  const auto change = [&](int x0, int x1, int y0, int y1) {  // base colour -> lit, summed over RGB
    const auto a = mean_rgb(*s, x0, x1, y0, y1), c = mean_rgb(*l, x0, x1, y0, y1);
    return std::abs(a[0] - c[0]) + std::abs(a[1] - c[1]) + std::abs(a[2] - c[2]);
  };
  const double metal = change(512, 524, 365, 405), paper = change(440, 452, 365, 405);
  EXPECT_GT(metal, paper + 100) << metal << " " << paper;
}

// Mask and fill by hand, with the pen-pressure test hook: a layer filled red, a mask painted black
// along a vertical drag (every dab at the hooked pressure 0.5, the radius curve switched on), a mask
// fill undone; saved, reopened, exported: what `adaptex paint` writes for the saved file.
TEST_F(StudioGui, MaskPaintingAndFillWithPressureSaveReopenAndExportAsAdaptexPaint) {
  // The documented test hook: xdotool sends no pressure.
  const BallSession b(dir.path, *x, {"ADAPTEX_STUDIO_TEST_PRESSURE=0.5"});
  const pid_t app = b.start();
  ASSERT_GT(app, 0) << slurp(b.log);
  EXPECT_EQ(count_in(b.log, "test hook: pen pressure 0.5"), 1) << slurp(b.log);
  // 1. The pressure curve of the radius (Brush panel, Pen pressure), then the Material window.
  ASSERT_TRUE(open_section(*x, b.log, "Pen pressure", "Pressure -> radius")) << slurp(b.log);
  ASSERT_TRUE(click_widget(*x, b.log, "Pressure -> radius"));
  ASSERT_TRUE(open_section(*x, b.log, "Layers and channels", "Add layer")) << slurp(b.log);
  // 2. Add layer (layer 2), Fill layer: layer 2 all red (the default brush).
  ASSERT_TRUE(click_widget(*x, b.log, "Add layer"));
  ASSERT_TRUE(wait_for([&] { return widget(b.log, "layer 2 visible").has_value(); }, 30s)) << slurp(b.log);
  std::this_thread::sleep_for(1s);  // the panel settles (its hint line goes)
  ASSERT_TRUE(click_widget(*x, b.log, "Fill layer"));
  // 3. Add mask, Paint on the mask (value 0: hides layer 2), a vertical drag.
  ASSERT_TRUE(click_widget(*x, b.log, "Add mask"));
  ASSERT_TRUE(wait_for([&] { return widget(b.log, "Remove mask").has_value(); }, 30s)) << slurp(b.log);
  ASSERT_TRUE(click_widget(*x, b.log, "Paint on the mask"));
  ASSERT_EQ(xdo(*x, vertical_drag()), 0);
  // 4. Fill mask (hides the whole layer), undone.
  ASSERT_TRUE(click_widget(*x, b.log, "Fill mask"));
  ASSERT_EQ(xdo(*x, "mousemove 520 500 sleep 0.3 " + hold("ctrl+z") + " sleep 0.5"), 0);
  // 5. Save As, Export GLB, quit.
  ASSERT_TRUE(b.save_export_quit(*x, app)) << slurp(b.log);

  const nlohmann::json h = read_json(b.hist);
  ASSERT_TRUE(h.is_object()) << slurp(b.log);
  ASSERT_EQ(h["layers"].size(), 2u) << h.dump();
  const nlohmann::json& l2 = h["layers"][1];
  ASSERT_EQ(l2["strokes"].size(), 1u) << l2.dump();
  EXPECT_EQ(l2["strokes"][0]["type"], "fill");
  EXPECT_TRUE(l2["strokes"][0]["channels"].contains("base_color"));
  ASSERT_TRUE(l2.contains("mask")) << l2.dump();
  const nlohmann::json& mask = l2["mask"]["strokes"];
  ASSERT_EQ(mask.size(), 1u) << l2.dump();  // the mask fill was undone
  EXPECT_EQ(l2["mask"]["value"], 1);
  EXPECT_EQ(mask[0]["type"], "brush");
  EXPECT_EQ(mask[0]["value"], 0);
  ASSERT_GT(mask[0]["dabs"].size(), 3u);
  for (const auto& d : mask[0]["dabs"]) {
    ASSERT_EQ(d.size(), 4u) << d.dump();  // [x, y, z, p]
    EXPECT_EQ(d[3], 0.5);
  }
  EXPECT_EQ(mask[0]["pressure"]["radius"], nlohmann::json::parse("[[0, 0.2], [0.5, 0.6], [1, 1]]"));
  EXPECT_EQ(read_json(b.project)["material"]["layers"], h["layers"]);

  // 6. Reopened from the project: red (layer 2) beside the drag, the paper (layer 1) along it.
  const auto s = b.reopen();
  ASSERT_TRUE(s.has_value()) << slurp(b.log2);
  const auto red = mean_rgb(*s, 420, 450, 326, 334), band = mean_rgb(*s, 516, 524, 300, 360);
  EXPECT_GT(red[0] - red[1], 80) << red[0] << " " << red[1];
  EXPECT_LT(std::abs(band[0] - band[1]), 25) << band[0] << " " << band[1];

  // 7. `adaptex paint` of the saved stroke file: the same GLB and OBJ files, byte for byte.
  b.expect_exports_are_adaptex_paints();
}

// The per-channel eyedropper and brush presets by hand: on a layered material the eyedropper (I)
// picks the composited base colour and roughness of an unpainted point (white, 0.5) into the brush;
// Save preset writes them; a broken preset is one error line and Load preset of a good one applies it.
TEST_F(StudioGui, EyedropperPicksTheChannelsAndPresetsSaveAndLoadTheBrush) {
  const BallSession b(dir.path, *x, {"ADAPTEX_STUDIO_DIALOG=builtin"});
  const fs::path preset = dir.path / "brush.json";
  const pid_t app = b.start();
  ASSERT_GT(app, 0) << slurp(b.log);
  ASSERT_TRUE(open_section(*x, b.log, "Layers and channels", "Add layer")) << slurp(b.log);
  ASSERT_TRUE(click_widget(*x, b.log, "Add layer"));
  ASSERT_TRUE(wait_for([&] { return widget(b.log, "layer 2 visible").has_value(); }, 30s)) << slurp(b.log);
  std::this_thread::sleep_for(1s);
  ASSERT_TRUE(click_widget(*x, b.log, "Roughness"));  // picks base colour and roughness
  // The eyedropper on the unpainted ball, then the brush again.
  ASSERT_EQ(xdo(*x, "mousemove 500 330 sleep 0.3 " + hold("i") + " sleep 0.3 mousedown 1 sleep 0.3 mouseup 1 sleep 0.5 " +
                        hold("b")),
            0);
  ASSERT_TRUE(open_section(*x, b.log, "Presets", "Save preset")) << slurp(b.log);
  for (int attempt = 0; attempt < 3 && !fs::exists(preset); ++attempt)
    if (click_widget(*x, b.log, "Save preset")) wait_for([&] { return fs::exists(preset); }, 20s);
  ASSERT_TRUE(fs::exists(preset)) << slurp(b.log);
  const nlohmann::json p = read_json(preset);
  EXPECT_EQ(p["format"], "adaptex.brush-preset");
  EXPECT_EQ(p["brush"]["channels"]["base_color"], nlohmann::json::parse("[1.0, 1.0, 1.0]")) << p.dump();
  EXPECT_EQ(p["brush"]["channels"]["roughness"], 0.5) << p.dump();  // the background's roughness
  // A broken preset: one error line naming the file and the field.
  {
    std::ofstream(preset) << R"({"format": "adaptex.brush-preset", "version": 1, "brush": {"opacity": 3}})";
  }
  ASSERT_TRUE(click_widget(*x, b.log, "Load preset"));
  ASSERT_TRUE(wait_for([&] { return count_in(b.log, "brush: \"opacity\" must be in [0, 1] (got 3)") == 1; }, 20s))
      << slurp(b.log);
  ASSERT_EQ(xdo(*x, "sleep 0.5 " + hold("Escape") + " sleep 0.5"), 0);  // closes the error pop-up
  {
    std::ofstream(preset) << R"({"format": "adaptex.brush-preset", "version": 1, "brush": {"opacity": 0.25}})";
  }
  ASSERT_TRUE(click_widget(*x, b.log, "Load preset"));
  ASSERT_TRUE(wait_for([&] { return count_in(b.log, "loaded the brush preset") == 1; }, 20s)) << slurp(b.log);
  for (int attempt = 0; attempt < 3 && read_json(preset)["brush"].size() < 3; ++attempt)
    if (click_widget(*x, b.log, "Save preset")) wait_for([&] { return read_json(preset)["brush"].size() >= 3; }, 20s);
  EXPECT_EQ(read_json(preset)["brush"]["opacity"], 0.25) << slurp(b.log);
  // Open preset... chooses the file in a dialog (the in-app browser here); the path field follows it.
  const fs::path soft = dir.path / "soft.json";
  {
    std::ofstream(soft) << R"({"format": "adaptex.brush-preset", "version": 1, "brush": {"opacity": 0.6}})";
  }
  ASSERT_TRUE(click_widget(*x, b.log, "Open preset"));
  ASSERT_TRUE(wait_for([&] { return count_in(b.log, "file browser: Load brush preset") == 1; }, 30s)) << slurp(b.log);
  ASSERT_EQ(xdo(*x, "type --delay 40 '" + soft.string() + "'"), 0);
  ASSERT_EQ(xdo(*x, "sleep 0.3 " + hold("Return")), 0);
  ASSERT_TRUE(wait_for([&] { return count_in(b.log, "loaded the brush preset") == 2; }, 20s)) << slurp(b.log);
  for (int attempt = 0; attempt < 3 && read_json(soft)["brush"].size() < 3; ++attempt)
    if (click_widget(*x, b.log, "Save preset")) wait_for([&] { return read_json(soft)["brush"].size() >= 3; }, 20s);
  EXPECT_EQ(read_json(soft)["brush"]["opacity"], 0.6) << slurp(b.log);
  EXPECT_EQ(terminate(app), 0);
}
