// Four painted channels against one (docs/benchmarks.md, "Four channels against one"): the cost of adapting a
// layout to a layered material (adapt/material_adapt.h) when every stroke paints base colour,
// roughness, metallic and height, against the same strokes painting base colour only, and against
// today's single-channel each-stroke cycle of a version 1 session (adapt/session.h).
//
// The history: the first K strokes of bench/common/session_history.h (`mixed`, seed 1) on the mesh.
//   BM_SessionCycle/K/W        PaintSession (each-stroke, v1, density-flow, its surface cache on as by
//                              default): K − 1 strokes and two cycles (untimed), then stroke K and its
//                              cycle (timed, the gain gate off): today's single-channel cycle.
//   BM_MaterialCycle/C/K/W     adapt_material() on the K strokes as one layer of a version 2 file,
//                              painting C channels (1: base colour = material_from_v1(); 4: also
//                              roughness, metallic and height, values varying per stroke): paint every
//                              channel on the unwrap's layout, the summed error model, the density-flow
//                              warp, paint again on the new layout, the never-worse check.
//   BM_MaterialPaint/C/K/W     paint_material() alone (the part of BM_MaterialCycle that runs twice).
//   BM_MaterialDensity/C/K/W   the material's summed error model alone (part of BM_MaterialCycle).
//   BM_MaterialSessionCycle/C/K/W/S/V  MaterialPaintSession (adapt/material_session.h), each-stroke: stroke K
//                              and one cycle, the gain gate off (see the function); S = 2 × the surface
//                              cache's samples per texel (0: off, every candidate replays the history),
//                              V = the coverage from which it is used (default 4; 0: from the start).
//
// Mesh: ADAPTEX_BENCH_MESH (a stem of ADAPTEX_SHARED_DIR/meshes or a path; default spot), unwrapped
// with the defaults; when absent, a message and the code-built fallback (a 20k-face curved height
// field, uv = xy). Each benchmark: one iteration per repetition (manual time, setup excluded);
// quote the median of the repetitions.
//   adaptex_bench_material --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// The comparison: --benchmark_filter='SessionCycle' (the version 1 cycle and the material session's).
// Counters: the phases (ms; flow_ms = flow + polish, polish_ms the polish alone), flow_steps and polish_sweeps
// (AdaptReport's), faults = the timed part's page faults (getrusage), cache = surface cache samples, session_MB = heap in use by the session
// after its setup (glibc mallinfo2), cpu_ms = the timed part's process CPU time; with the surface cache:
// psnr_db = the held textures (base colour, metallic-roughness; the lower) against exact replay on the
// held layout, loss_db = their error on the surface (evaluate_material_textures(), 200k samples)
// over exact replay's, in dB (untimed).
// Profiling the timed part only: ADAPTEX_PERF_CTL=CTL_FIFO,ACK_FIFO makes the SessionCycle benchmarks
// send perf's `enable` / `disable` around it (docs/benchmarks.md, "Where the four-channel cycle's time goes"):
//   mkfifo /tmp/ctl /tmp/ack; ADAPTEX_PERF_CTL=/tmp/ctl,/tmp/ack perf record -e cpu-clock --call-graph dwarf
//     --control fifo:/tmp/ctl,/tmp/ack -D -1 -- adaptex_bench_material --benchmark_filter=... (one line)
// Instructions of the timed part (deterministic, one core: TBB then runs it in the calling thread), e.g.
//   taskset -c 1 valgrind --tool=callgrind --collect-atstart=no
//     --toggle-collect='adaptex::MaterialPaintSession::add_stroke(*' adaptex_bench_material
//     --benchmark_filter='BM_MaterialSessionCycle/4/40/1024/3/4'   (version 1: 'adaptex::PaintSession::add_stroke(*')
#include <benchmark/benchmark.h>

#include <fcntl.h>
#include <malloc.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "../common/height_field.h"
#include "../common/session_history.h"
#include "adaptex/adapt/material_adapt.h"
#include "adaptex/adapt/material_session.h"
#include "adaptex/adapt/session.h"
#include "adaptex/core/allocator.h"
#include "adaptex/paint/material_eval.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/paint/texel_map.h"
#include "adaptex/param/unwrap.h"

using namespace adaptex;
namespace fs = std::filesystem;

namespace {

struct Scene {
  std::string name;
  TriMesh mesh;
  Parameterization param;
  StrokeFile history;  ///< The longest history any benchmark asked for.
};

/// The 20k-face height field (bench/common/height_field.h): the fallback when the shared mesh is absent.
void fallback_scene(Scene& s) {
  s.name = "plane20k";
  bench::height_field(100, s.mesh, s.param);
}

/// The benchmark's mesh (read, unwrapped and given a history once) with at least \p strokes strokes.
const Scene& scene(int strokes) {
  static std::unique_ptr<Scene> s;
  if (!s) {
    s = std::make_unique<Scene>();
    const char* env = std::getenv("ADAPTEX_BENCH_MESH");
    const std::string name = env && *env ? env : "spot";
    fs::path path = name;
    const fs::path dir = fs::path(ADAPTEX_SHARED_DIR) / "meshes";
    if (!fs::exists(path) && fs::is_directory(dir))
      for (const auto& e : fs::directory_iterator(dir))
        if (e.path().stem() == name || e.path().filename() == name) path = e.path();
    if (fs::exists(path)) {
      s->name = path.stem().string();
      s->mesh = read_mesh(path);
      s->param = unwrap(s->mesh).param;
    } else {
      std::fprintf(stderr, "adaptex_bench_material: mesh %s not found (nor in %s): the code-built fallback instead\n",
                   name.c_str(), dir.string().c_str());
      fallback_scene(*s);
    }
  }
  if (static_cast<int>(s->history.strokes.size()) < strokes) s->history = bench::session_history(s->mesh, strokes, 1);
  return *s;
}

/// The first \p k strokes of \p history as one layer painting \p channels (1 or 4) channels.
MaterialStrokeFile material_history(const StrokeFile& history, int k, int channels) {
  StrokeFile first = history;
  first.strokes.resize(k);
  MaterialStrokeFile file = material_from_v1(first);
  if (channels == 1) return file;
  const unsigned more =
      channel_bit(Channel::Roughness) | channel_bit(Channel::Metallic) | channel_bit(Channel::Height);
  int i = 0;
  for (MaterialStroke& s : file.layers[0].strokes) {
    s.channels |= more;
    s.value[channel_offset(Channel::Roughness)] = 0.15 + 0.7 * std::fmod(0.618034 * i, 1.0);
    s.value[channel_offset(Channel::Metallic)] = i % 3 == 0 ? 1.0 : 0.0;
    s.value[channel_offset(Channel::Height)] = i % 2 == 0 ? 0.25 : 0.7;
    ++i;
  }
  return file;
}

/// Heap bytes in use (glibc: small blocks and mmapped ones).
double heap_in_use() {
  const struct mallinfo2 m = mallinfo2();
  return static_cast<double>(m.uordblks + m.hblkhd);
}

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

/// PSNR of \p a against \p b over RGB, every texel (padding and background included).
double texture_psnr(const ImageRGBA8& a, const ImageRGBA8& b) {
  double s = 0;
  for (size_t k = 0; k < a.data.size(); ++k)
    if (k % 4 != 3) s += (a.data[k] - b.data[k]) * (a.data[k] - b.data[k]) / (255.0 * 255.0);
  return 10 * std::log10(0.75 * a.data.size() / std::max(s, 1e-30));
}

/// perf's control fifos named by ADAPTEX_PERF_CTL ("CTL_FIFO,ACK_FIFO"; unset: nothing is sent).
class PerfControl {
 public:
  PerfControl() {
    const char* env = std::getenv("ADAPTEX_PERF_CTL");
    if (!env || !*env) return;
    const std::string s = env;
    const size_t comma = s.find(',');
    ctl_ = open(s.substr(0, comma).c_str(), O_WRONLY);
    if (comma != std::string::npos) ack_ = open(s.substr(comma + 1).c_str(), O_RDONLY);
    if (ctl_ < 0) std::fprintf(stderr, "adaptex_bench_material: cannot open perf's control fifo in %s\n", env);
  }
  ~PerfControl() {
    for (int fd : {ctl_, ack_})
      if (fd >= 0) close(fd);
  }
  PerfControl(const PerfControl&) = delete;
  PerfControl& operator=(const PerfControl&) = delete;

  /// Sends \p command ("enable" or "disable") and waits for perf's acknowledgement when there is an ack fifo.
  void send(const char* command) const {
    if (ctl_ < 0) return;
    const std::string line = std::string(command) + "\n";
    if (write(ctl_, line.data(), line.size()) != static_cast<ssize_t>(line.size())) return;
    char buf[8];
    if (ack_ >= 0 && read(ack_, buf, sizeof buf) < 0) std::fprintf(stderr, "adaptex_bench_material: no ack from perf\n");
  }

 private:
  int ctl_ = -1, ack_ = -1;
};

/// The process's perf control (opened at first use).
const PerfControl& perf_control() {
  static const PerfControl p;
  return p;
}

/// Page faults of the process so far (minor + major).
double page_faults() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_minflt + u.ru_majflt);
}

/// The flow's and the polish's figures of \p r (the same code in both sessions' cycles).
void add_flow_counters(std::map<std::string, double>& acc, const AdaptReport& r) {
  acc["density_ms"] += 1e3 * r.time_density;
  acc["flow_ms"] += 1e3 * (r.time_flow + r.time_polish);
  acc["polish_ms"] += 1e3 * r.time_polish;
  acc["flow_steps"] += static_cast<double>(r.flow_steps);
  acc["polish_sweeps"] += r.polish_sweeps;
}

void set_counters(benchmark::State& state, const Scene& sc, const std::map<std::string, double>& acc, int iters) {
  for (const auto& [k, v] : acc) state.counters[k] = v / std::max(1, iters);
  state.counters["faces"] = sc.mesh.num_faces();
  state.SetLabel(sc.name);
}

void BM_SessionCycle(benchmark::State& state) {
  const int k = static_cast<int>(state.range(0)), W = static_cast<int>(state.range(1));
  const Scene& sc = scene(k);
  std::map<std::string, double> acc;
  int iters = 0;
  for (auto _ : state) {
    PaintSessionOptions o;
    o.texture_size = W;
    o.schedule = ReparamSchedule::EachStroke;
    o.min_gain_db = 0;  // every cycle computes
    const double heap0 = heap_in_use();
    PaintSession session(sc.mesh, sc.param, o, sc.history.background);
    session.add_strokes({sc.history.strokes.begin(), sc.history.strokes.begin() + (k - 1)});  // and one cycle
    session.reparameterize();  // as the material session's setup: a held layout after two cycles
    acc["session_MB"] += (heap_in_use() - heap0) / 1e6;
    perf_control().send("enable");
    const double c0 = cpu_seconds(), f0 = page_faults();
    const auto t0 = std::chrono::steady_clock::now();
    session.add_stroke(sc.history.strokes[k - 1]);
    state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    acc["cpu_ms"] += 1e3 * (cpu_seconds() - c0);
    acc["faults"] += page_faults() - f0;
    perf_control().send("disable");
    const AdaptReport& r = session.reports().back();
    add_flow_counters(acc, r);
    acc["texture_ms"] += 1e3 * r.time_texture_update;
    acc["safeguard_ms"] += 1e3 * r.time_safeguard;
    acc["cache"] += static_cast<double>(session.surface_cache_samples());
    ++iters;
  }
  set_counters(state, sc, acc, iters);
}

void BM_MaterialCycle(benchmark::State& state) {
  const int channels = static_cast<int>(state.range(0)), k = static_cast<int>(state.range(1));
  const int W = static_cast<int>(state.range(2));
  const Scene& sc = scene(k);
  const MaterialStrokeFile file = material_history(sc.history, k, channels);
  MaterialAdaptOptions o;
  o.paint.size = W;
  std::map<std::string, double> acc;
  int iters = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    const MaterialAdaptResult r = adapt_material(sc.mesh, sc.param, file, o);
    state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    benchmark::DoNotOptimize(r.textures.normal.data.data());
    acc["density_ms"] += 1e3 * r.report.time_density;
    acc["flow_ms"] += 1e3 * (r.report.time_flow + r.report.time_polish);
    acc["adapted"] += r.adapted;
    ++iters;
  }
  set_counters(state, sc, acc, iters);
}

/// MaterialPaintSession (adapt/material_session.h), each-stroke: the first K − 1 strokes in the file it
/// starts from and two cycles on them (untimed: they build the caches, and leave the session as at
/// stroke K of an each-stroke session, with a held and a spare layout), then stroke K added (timed):
/// the stroke into the caches and one full cycle (the gain gate off, so every timed cycle computes).
/// The surface cache is used from the coverage its options say (as the version 1 session's).
void BM_MaterialSessionCycle(benchmark::State& state) {
  const int channels = static_cast<int>(state.range(0)), k = static_cast<int>(state.range(1));
  const Scene& sc = scene(k);
  const MaterialStrokeFile file = material_history(sc.history, k, channels);
  MaterialStrokeFile start = file;
  start.layers[0].strokes.pop_back();
  MaterialSessionOptions o;
  o.paint.size = static_cast<int>(state.range(2));
  o.min_gain_db = 0;
  o.surface_cache = 0.5 * static_cast<double>(state.range(3));
  o.surface_cache_coverage = static_cast<double>(state.range(4));
  std::map<std::string, double> acc;
  int iters = 0;
  for (auto _ : state) {
    const double heap0 = heap_in_use();
    MaterialPaintSession session(sc.mesh, sc.param, start, o);
    session.reparameterize();  // builds the caches
    session.reparameterize();  // as at stroke K of a session: a held layout and a spare one
    acc["session_MB"] += (heap_in_use() - heap0) / 1e6;
    perf_control().send("enable");
    const double c0 = cpu_seconds(), f0 = page_faults();
    const auto t0 = std::chrono::steady_clock::now();
    session.add_stroke(0, file.layers[0].strokes.back());
    state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    acc["cpu_ms"] += 1e3 * (cpu_seconds() - c0);
    acc["faults"] += page_faults() - f0;
    perf_control().send("disable");
    acc["cache"] += static_cast<double>(session.surface_cache_samples());
    if (session.held_from_cache()) {  // the cached textures against exact replay on the held layout
      const MaterialTextures exact = paint_material(session.mesh(), session.param(), session.history(), o.paint);
      acc["psnr_db"] += std::min(texture_psnr(session.textures().base_color, exact.base_color),
                                 texture_psnr(session.textures().metallic_roughness, exact.metallic_roughness));
      // What the check measures (every channel, the height through its normal), cached over exact.
      MaterialEvalOptions eo;
      eo.data_weight = o.data_weight;
      const double e_cached =
          evaluate_material_textures(session.mesh(), session.param(), session.textures(), session.history(), eo).weighted;
      const double e_exact = evaluate_material_textures(session.mesh(), session.param(), exact, session.history(), eo).weighted;
      acc["loss_db"] += 10 * std::log10(e_cached / e_exact);
    }
    const AdaptReport& r = session.reports().back();
    add_flow_counters(acc, r);
    acc["texture_ms"] += 1e3 * r.time_texture_update;
    acc["check_ms"] += 1e3 * r.time_safeguard;
    acc["adapted"] += session.adapted();
    ++iters;
  }
  set_counters(state, sc, acc, iters);
}

/// paint_material() alone on the unwrap's layout: the part of BM_MaterialCycle that runs twice.
void BM_MaterialPaint(benchmark::State& state) {
  const int channels = static_cast<int>(state.range(0)), k = static_cast<int>(state.range(1));
  const Scene& sc = scene(k);
  const MaterialStrokeFile file = material_history(sc.history, k, channels);
  MaterialPaintOptions o;
  o.size = static_cast<int>(state.range(2));
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    const MaterialTextures t = paint_material(sc.mesh, sc.param, file, o);
    state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    benchmark::DoNotOptimize(t.normal.data.data());
  }
  set_counters(state, sc, {}, 1);
}

/// The material's error model alone (material_error_planes() + compute_error_density() on the
/// unwrap's layout, its textures painted untimed): the part of BM_MaterialCycle that sums the channels.
void BM_MaterialDensity(benchmark::State& state) {
  const int channels = static_cast<int>(state.range(0)), k = static_cast<int>(state.range(1));
  const int W = static_cast<int>(state.range(2));
  const Scene& sc = scene(k);
  const MaterialStrokeFile file = material_history(sc.history, k, channels);
  MaterialPaintOptions po;
  po.size = W;
  const MaterialTextures tex = paint_material(sc.mesh, sc.param, file, po);
  const TexelMap map = build_texel_map(sc.mesh, sc.param, W, W);
  const MaterialAdaptOptions mo;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    const ErrorDensity d = compute_error_density(sc.mesh, sc.param, map,
                                                 material_error_planes(sc.mesh, sc.param, map, file, tex, mo.data_weight),
                                                 mo.adapt.density_flow.density);
    state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    benchmark::DoNotOptimize(&d);
  }
  set_counters(state, sc, {}, 1);
}

}  // namespace

BENCHMARK(BM_SessionCycle)->Args({40, 1024})->Args({200, 1024})->UseManualTime()->Iterations(1)->Unit(benchmark::kMillisecond);
void material_args(benchmark::internal::Benchmark* b) {
  b->Args({1, 40, 1024})->Args({4, 40, 1024})->UseManualTime()->Iterations(1)->Unit(benchmark::kMillisecond);
}
BENCHMARK(BM_MaterialCycle)->Apply(material_args);
BENCHMARK(BM_MaterialSessionCycle)
    ->Args({1, 40, 1024, 3, 4})
    ->Args({4, 40, 1024, 3, 4})
    ->Args({4, 40, 1024, 3, 0})
    ->Args({4, 200, 1024, 3, 4})
    ->Args({4, 200, 1024, 2, 4})
    ->Args({4, 200, 1024, 0, 4})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MaterialPaint)->Apply(material_args);
BENCHMARK(BM_MaterialDensity)->Apply(material_args);

int main(int argc, char** argv) {
  // As the adaptex programs run (core/allocator.h); ADAPTEX_DEFAULT_MALLOC=1 measures glibc's defaults.
  adaptex::keep_freed_memory_in_process_unless_disabled();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
