// Benchmark of the full re-parameterization cycle (docs/bench_adapt.md): importance map + stretch map
// + L_s² + two-stage relaxation + safe remap + texel map of the new layout + texture update
// (resample), on a curved height-field mesh of F faces with a W x W texture and a fine grid of G
// cells (coarse 16). Counters: each phase's CPU time of the calling thread in ms (mean over the
// iterations); Time = wall clock.
//
//   adaptex_adapt_cycle [--benchmark_filter=...]        args: faces / texture size / fine grid
//   ADAPTEX_BENCH_SERIAL=1 adaptex_adapt_cycle          single thread: cpu_* = the whole cost
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <ctime>
#include <cstdlib>
#include <string>

#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <random>

#include "adaptex/core/allocator.h"
#include "adaptex/adapt/adapt.h"
#include "adaptex/adapt/session.h"
#include "adaptex/adapt/stretch_map.h"
#include "adaptex/adapt/texture_update.h"
#include "adaptex/core/shapes.h"
#include "adaptex/paint/generate.h"
#include "adaptex/paint/texel_map.h"
#include "../common/height_field.h"

using namespace adaptex;

namespace {

struct Scene {
  TriMesh mesh;
  Parameterization param;
};

// n x n quad height field (2 n^2 faces) with uv = xy: one chart filling the square.
const Scene& scene(int faces) {
  static std::map<int, std::unique_ptr<Scene>> cache;
  auto& s = cache[faces];
  if (!s) {
    s = std::make_unique<Scene>();
    bench::height_field(static_cast<int>(std::lround(std::sqrt(faces / 2.0))), s->mesh, s->param);
  }
  return *s;
}

// White texture with 60 dark 2-texel lines in one quarter of the domain (concentrated detail).
ImageRGBA8 lines_texture(int W) {
  ImageRGBA8 img(W, W, {255, 255, 255, 255});
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(0.05, 0.45);
  for (int k = 0; k < 60; ++k) {
    const double x0 = U(rng), y0 = U(rng), x1 = U(rng), y1 = U(rng);
    const int steps = 4 * W;
    for (int s = 0; s <= steps; ++s) {
      const double t = double(s) / steps;
      const int i = static_cast<int>((x0 + t * (x1 - x0)) * W), j = static_cast<int>((y0 + t * (y1 - y0)) * W);
      for (int dj = 0; dj < 2; ++dj)
        for (int di = 0; di < 2; ++di) {
          auto* p = img.texel(std::min(W - 1, i + di), std::min(W - 1, j + dj));
          p[0] = 40;
          p[1] = 40;
          p[2] = 140;
        }
    }
  }
  return img;
}

// CPU time of the calling thread (immune to other processes on a loaded machine); with
// ADAPTEX_BENCH_SERIAL=1 TBB runs on this thread only, so it is the whole single-core cost.
double thread_cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e3 * ts.tv_sec + 1e-6 * ts.tv_nsec;
}

void BM_Cycle(benchmark::State& state) {
  const int faces = static_cast<int>(state.range(0)), W = static_cast<int>(state.range(1));
  const int grid = static_cast<int>(state.range(2));
  const Scene& sc = scene(faces);
  const ImageRGBA8 tex = lines_texture(W);
  const TexelMap map = build_texel_map(sc.mesh, sc.param, W, W);
  AdaptOptions o;
  o.thesis.fine_grid = grid;
  o.thesis.coarse_grid = std::min(16, grid);
  std::map<std::string, double> acc;
  int iters = 0;
  for (auto _ : state) {
    // The phases of adapt_parameterization(), timed one by one (same calls, same order).
    double t = thread_cpu_ms(), t1;
    auto lap = [&](const char* name) {
      t1 = thread_cpu_ms();
      acc[name] += t1 - t;
      t = t1;
    };
    const ImageF imp = compute_importance(tex, &map, o.thesis.importance);
    lap("cpu_importance_ms");
    const ImageF str = compute_stretch_map(sc.mesh, sc.param, map);
    lap("cpu_stretch_ms");
    Ls2Options lo;
    lo.alpha = o.thesis.alpha;
    lo.beta = o.thesis.beta;
    lo.min_weight = o.thesis.min_weight;
    lo.geometry_scale = o.thesis.geometry_scale;
    const ImageF ls2 = compute_ls2(imp, str, lo);
    lap("cpu_ls2_ms");
    RelaxOptions ro;
    ro.epsilon = o.thesis.epsilon_texels / W;
    ro.max_iterations = o.thesis.max_iterations;
    GridWarp coarse = GridWarp::uniform(o.thesis.coarse_grid);
    relax_grid(coarse, pool_for_grid(ls2, o.thesis.coarse_grid, o.thesis.pool), ro);
    lap("cpu_coarse_ms");
    const ImageF pooled = pool_for_grid(ls2, o.thesis.fine_grid, o.thesis.pool);
    const ImageF field = pull_back_field(pooled, coarse, std::max(pooled.width, pooled.height));
    GridWarp fine = GridWarp::uniform(o.thesis.fine_grid);
    ro.max_iterations = o.thesis.fine_max_iterations;
    const RelaxStats fs = relax_grid(fine, field, ro);
    lap("cpu_fine_ms");
    const SafeRemapResult sr = safe_remap(sc.param, {&coarse, &fine}, o.remap);
    lap("cpu_remap_ms");
    const TexelMap nmap = build_texel_map(sc.mesh, sr.param, W, W);
    lap("cpu_texelmap_ms");
    ImageRGBA8 ntex = resample_texture(sc.param, tex, nmap, 4);
    lap("cpu_resample_ms");
    benchmark::DoNotOptimize(ntex.data.data());
    acc["fine_iters"] += fs.iterations;
    acc["damping"] += sr.mean_damping;
    ++iters;
  }
  double total = 0;
  for (auto& [k, v] : acc) {
    state.counters[k] = v / std::max(1, iters);
    if (k.rfind("cpu_", 0) == 0) total += v / std::max(1, iters);
  }
  state.counters["cpu_total_ms"] = total;
  state.counters["faces"] = sc.mesh.num_faces();
}

/// The same cycle with the default method (density-flow, issue 10): adapt_parameterization() on the
/// texture alone (no stroke history, as `adaptex reparam`), then the texel map of the new layout (on
/// the refined mesh when refinement ran) and the texture resampled onto it. Counters: the report's
/// phases (wall ms of the calling process) and the thread CPU of the whole cycle.
void BM_DensityFlowCycle(benchmark::State& state) {
  const int faces = static_cast<int>(state.range(0)), W = static_cast<int>(state.range(1));
  const Scene& sc = scene(faces);
  const ImageRGBA8 tex = lines_texture(W);
  const TexelMap map = build_texel_map(sc.mesh, sc.param, W, W);
  AdaptOptions o;  // the defaults: density-flow
  std::map<std::string, double> acc;
  int iters = 0;
  for (auto _ : state) {
    const double t0 = thread_cpu_ms();
    const AdaptResult res = adapt_parameterization(sc.mesh, sc.param, tex, map, o);
    const TriMesh& mesh = res.refined_mesh ? *res.refined_mesh : sc.mesh;
    const Parameterization& old_layout = res.refined_layout ? *res.refined_layout : sc.param;
    auto t = std::chrono::steady_clock::now();
    const TexelMap nmap = build_texel_map(mesh, res.param, W, W);
    const double texel_map_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
    t = std::chrono::steady_clock::now();
    ImageRGBA8 ntex = resample_texture(old_layout, tex, nmap, 4);
    const double resample_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
    benchmark::DoNotOptimize(ntex.data.data());
    const AdaptReport& r = res.report;
    acc["density_ms"] += 1e3 * r.time_density;
    acc["flow_ms"] += 1e3 * r.time_flow;
    acc["polish_ms"] += 1e3 * r.time_polish;
    acc["refine_ms"] += 1e3 * r.time_refine;
    acc["remap_ms"] += 1e3 * r.time_remap;
    acc["texelmap_ms"] += texel_map_ms;
    acc["resample_ms"] += resample_ms;
    acc["cpu_total_ms"] += thread_cpu_ms() - t0;
    acc["faces_after"] += mesh.num_faces();
    acc["flow_points"] += static_cast<double>(r.flow_advected_points);
    ++iters;
  }
  for (auto& [k, v] : acc) state.counters[k] = v / std::max(1, iters);
}
BENCHMARK(BM_DensityFlowCycle)->Args({10000, 512})->Args({100000, 1024})->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(1.0);

/// The each-stroke cycle that stops after the error model (PaintSessionOptions::min_gain_db, session.h):
/// a session on the 100k-face height field at W x W with min_gain_db so high that every cycle is
/// skipped, and generated `mixed` strokes added one per iteration (after a warm-up history of 40 and
/// one full cycle, so that the gate uses the measured estimate, as in a real session).
/// Time = add_stroke(): painting the stroke, the per-stroke caches (the surface cache included, as in a
/// long session: surface_cache_coverage 0 builds it during the warm-up), the error model and the error
/// estimate of the held layout. Counter density_ms: the report's time_density (the gate itself).
void BM_SkippedEachStrokeCycle(benchmark::State& state) {
  const int W = static_cast<int>(state.range(0));
  const Scene& sc = scene(100000);
  GenerateOptions go;
  go.kind = StrokeKind::Mixed;
  go.count = 400;
  go.seed = 2;
  const StrokeFile strokes = generate_strokes(sc.mesh, go);
  PaintSessionOptions so;
  so.texture_size = W;
  so.schedule = ReparamSchedule::EachStroke;
  so.min_gain_db = 1e9;
  so.surface_cache_coverage = 0;
  PaintSession session(sc.mesh, sc.param, so, strokes.background);
  size_t next = 0;
  for (; next < 40; ++next) session.add_stroke(strokes.strokes[next]);
  session.reparameterize();  // one full cycle: the held layout's error is known, the gate measures
  double density = 0;
  int iters = 0;
  for (auto _ : state) {
    session.add_stroke(strokes.strokes[next]);
    next = (next + 1) % strokes.strokes.size();
    density += 1e3 * session.reports().back().time_density;
    ++iters;
  }
  state.counters["density_ms"] = density / std::max(1, iters);
  state.counters["skipped"] = session.reports().back().skipped;
}
BENCHMARK(BM_SkippedEachStrokeCycle)->Arg(1024)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);

void args(benchmark::internal::Benchmark* b) {
  for (int f : {10000, 100000, 1000000})
    for (int w : {512, 1024, 2048}) b->Args({f, w, 256});
  for (int g : {64, 1024}) b->Args({100000, 1024, g});
}

}  // namespace

BENCHMARK(BM_Cycle)->Apply(args)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(1.0);

int main(int argc, char** argv) {
  // As the adaptex programs run (core/allocator.h); ADAPTEX_DEFAULT_MALLOC=1 measures glibc's defaults.
  adaptex::keep_freed_memory_in_process_unless_disabled();
  std::unique_ptr<tbb::global_control> serial;
  if (const char* e = std::getenv("ADAPTEX_BENCH_SERIAL"); e && std::string(e) == "1")
    serial = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, 1);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
