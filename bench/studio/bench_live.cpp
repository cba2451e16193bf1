// The studio's adaptation while painting, as a session (issue 10: "the studio uses the same path:
// with adaptation on, frame time while painting does not rise"; docs/studio.md, "Measurements").
//
// adaptex-studio's app logic (App with the null renderer: no GPU, the UI thread's own work only) gets
// a generated `mixed` history one stroke every --interval-ms, as an artist would paint it, and runs
// frames in between at 60 Hz. With the default options (schedule each-stroke, density-flow) the live
// each-stroke session (live_adaptation.h) adapts in the background. Printed per window of strokes:
//   - UI frame time (begin_frame + render + end_frame: polling, swapping in adapted surfaces and
//     painting the strokes made since onto them, uploads): median / p95 / max;
//   - adaptation lag: from a stroke's arrival to the end of the cycle that adapted to it (the surface
//     is then ready to swap in): median / max;
//   - strokes per cycle (a session that falls behind catches up in one cycle per batch).
// Then the time to settle after the last stroke (end mode's layout, PaintSession::finish), and, for
// comparison, what the studio did before after every stroke: paint_history() of the whole history from
// the initial layout (end mode), timed once at strokes 10, N/2 and N.
//
//   adaptex_bench_studio_live [--mesh armadillo] [--strokes 200] [--size 1024] [--interval-ms 500]
//                             [--seed 1] [--window 20]
//
// --mesh: a stem of ADAPTEX_SHARED_DIR/meshes (armadillo, kitten, ...), a path, or builtin:NAME.
// The history is generated in batches of 40 strokes with seeds S, S+1, ... (as adaptex_bench_session).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <sys/resource.h>
#include <thread>
#include <vector>

#include "adaptex/adapt/session.h"
#include "adaptex/paint/generate.h"
#include "../common/session_history.h"
#include "app.h"
#include "backend.h"
#include "live_adaptation.h"

using namespace adaptex;
using namespace adaptex::studio;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

struct Args {
  std::string mesh = "armadillo";
  int strokes = 200;
  int size = 1024;
  double interval_ms = 500;
  int seed = 1;
  int window = 20;
};

double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(q * double(v.size() - 1) + 0.5))];
}

std::string resolve(const std::string& m) {
  if (m.rfind("builtin:", 0) == 0 || fs::exists(m)) return m;
  for (const char* ext : {".obj", ".ply", ".off"}) {
    const fs::path p = fs::path(ADAPTEX_SHARED_DIR) / "meshes" / (m + ext);
    if (fs::exists(p)) return p.string();
  }
  return {};
}

struct Window {
  std::vector<double> frame_ms, lag_ms;
};

/// One frame of the app, timed.
double frame(App& app) {
  const auto t0 = Clock::now();
  app.begin_frame();
  app.render();
  app.end_frame();
  return ms_between(t0, Clock::now());
}

int run(const Args& a) {
  const std::string path = resolve(a.mesh);
  if (path.empty()) {
    std::printf("skipped: mesh %s not found (no ../shared?)\n", a.mesh.c_str());
    return 0;
  }
  App app(std::make_unique<NullRenderer>(), AppOptions{});
  app.on_resize(1280, 800);
  app.session_options().texture_size = a.size;
  app.open_mesh(path);
  if (!app.wait_idle(600) || !app.has_model()) {
    std::fprintf(stderr, "could not load %s\n", path.c_str());
    return 2;
  }
  const auto mesh = std::make_shared<const TriMesh>(*app.mesh());
  const Parameterization initial = *app.param();
  const StrokeFile history = bench::session_history(*mesh, a.strokes, a.seed);
  std::printf("mesh %s: %d faces, texture %d², %d strokes one every %.0f ms, method %s, schedule each-stroke\n",
              a.mesh.c_str(), mesh->num_faces(), a.size, a.strokes, a.interval_ms,
              to_string(app.session_options().adapt.mode));

  const int n = a.strokes;
  std::vector<Window> windows((n + a.window - 1) / a.window);
  std::vector<Clock::time_point> added(static_cast<size_t>(n));
  std::vector<double> lag(static_cast<size_t>(n), -1.0);
  const auto frame_period = std::chrono::microseconds(16667);
  const auto start = Clock::now();
  auto next_frame = start;
  int next_stroke = 0;
  size_t checked = 0;  // strokes whose lag is known
  std::vector<double> snapshot_ms;
  while (true) {
    const auto now = Clock::now();
    if (next_stroke < n && now >= start + std::chrono::duration<double, std::milli>(next_stroke * a.interval_ms)) {
      added[size_t(next_stroke)] = now;
      app.add_stroke(history.strokes[size_t(next_stroke)]);
      ++next_stroke;
    }
    const auto serial = app.surface_serial();
    const double f = frame(app);
    if (app.surface_serial() != serial)
      for (const auto& [phase, ms] : app.last_cycle())
        if (phase == "snapshot") snapshot_ms.push_back(ms);
    if (next_stroke > 0) windows[size_t(next_stroke - 1) / size_t(a.window)].frame_ms.push_back(f);
    const LiveAdaptation* live = app.live_adaptation();
    const size_t adapted = live ? live->adapted() : 0;
    const auto t = Clock::now();
    for (; checked < adapted && checked < size_t(next_stroke); ++checked) lag[checked] = ms_between(added[checked], t);
    if (next_stroke == n && (checked == size_t(n) || !live)) break;
    next_frame += frame_period;
    std::this_thread::sleep_until(next_frame);
  }
  const auto last = Clock::now();
  app.wait_idle(3600);
  const double settle_ms = ms_between(last, Clock::now());
  for (int k = 0; k < n; ++k) windows[size_t(k / a.window)].lag_ms.push_back(lag[size_t(k)]);
  const LiveAdaptation* live = app.live_adaptation();
  const int cycles = live ? live->cycles() : 0;

  std::printf("\n| strokes | UI frame median / p95 / max (ms) | adaptation lag median / max (ms) |\n|---|---|---|\n");
  for (size_t w = 0; w < windows.size(); ++w) {
    const Window& W = windows[w];
    std::printf("| %zu–%zu | %.2f / %.2f / %.2f | %.0f / %.0f |\n", w * a.window + 1,
                std::min<size_t>(size_t(n), (w + 1) * a.window), quantile(W.frame_ms, 0.5), quantile(W.frame_ms, 0.95),
                quantile(W.frame_ms, 1.0), quantile(W.lag_ms, 0.5), quantile(W.lag_ms, 1.0));
  }
  std::printf("\ncycles: %d for %d strokes (%.2f strokes per cycle, settles included); settled %.0f ms after the "
              "last stroke was adapted\n",
              cycles, n, cycles > 0 ? double(n) / cycles : 0.0, settle_ms);

  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  std::printf("peak RSS of the process: %.0f MB\n", double(ru.ru_maxrss) / 1024.0);
  std::printf("surfaces swapped in: %zu; their snapshot (canvas, picking, normals) median / max %.0f / %.0f ms\n",
              snapshot_ms.size(), quantile(snapshot_ms, 0.5), quantile(snapshot_ms, 1.0));
  std::printf("\nbefore (one paint_history() of the whole history per stroke, end mode from the initial layout):\n");
  for (int k : {std::min(10, n), n / 2, n}) {
    if (k <= 0) continue;
    StrokeFile part;
    part.background = history.background;
    part.strokes.assign(history.strokes.begin(), history.strokes.begin() + k);
    const auto t0 = Clock::now();
    (void)paint_history(mesh, initial, part, app.session_options(), {});
    std::printf("  stroke %d: %.0f ms\n", k, ms_between(t0, Clock::now()));
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string k = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", k.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    try {
      if (k == "--mesh") a.mesh = next();
      else if (k == "--strokes") a.strokes = std::stoi(next());
      else if (k == "--size") a.size = std::stoi(next());
      else if (k == "--interval-ms") a.interval_ms = std::stod(next());
      else if (k == "--seed") a.seed = std::stoi(next());
      else if (k == "--window") a.window = std::stoi(next());
      else {
        std::fprintf(stderr, "unknown option %s\n", k.c_str());
        return 2;
      }
    } catch (const std::logic_error&) {  // std::stoi / stod: not a number, or out of range
      std::fprintf(stderr, "%s: not a number: %s\n", k.c_str(), argv[i]);
      return 2;
    }
  }
  if (a.strokes < 1 || a.strokes > 100000 || a.window < 1 || a.size < 16 || a.size > 8192 ||
      !(a.interval_ms >= 0 && a.interval_ms <= 60000)) {
    std::fprintf(stderr, "--strokes in [1, 100000], --window >= 1, --size in [16, 8192], --interval-ms in [0, 60000]\n");
    return 2;
  }
  return run(a);
}
