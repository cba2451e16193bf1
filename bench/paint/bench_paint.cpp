// Painting benchmarks (docs/bench_paint.md):
//  - BM_DabThroughput/<radius in texels>: single-thread texel updates per second of the interactive
//    path (begin_stroke/add_dab), plane with uv = xy at 2048^2. Counter "updates/s" = texels inside
//    the dab evaluated and stored per second, one core.
//  - BM_StrokeThroughput1T/<radius>: the same through paint_stroke() in a 1-thread TBB arena.
//  - BM_PainterSetup/<size>: texel map + texel grid + seam padding of a plane at size^2.
//  - BM_PaintLines/<mesh>/<size>: paint_all() of `strokes generate --kind lines --seed 1` on a shared
//    mesh unwrapped with unwrap() (not timed), at 1024^2 and 2048^2, all cores, wall time including
//    texture() (8-bit conversion + padding); "setup_s" is the painter construction (texel map,
//    texel grid, padding) for the same mesh and size, "updates" the texel evaluations per paint.
//  - BM_SurfaceCacheBuild / BM_SurfaceCacheStroke / BM_SurfaceCacheTexelColours/<size>: the surface
//    signal cache (paint/surface_cache.h) on a plane of 100,352 faces with uv = xy, sample spacing a
//    third of the texel spacing at 1024² (PaintSessionOptions::surface_cache = 3): building the lattice
//    and face index (counter "samples"), compositing one generated `mixed` stroke (40 in turn), and
//    the colours of every chart texel at size² (what replaces replaying the history), all cores.
// Env ADAPTEX_BENCH_MESHES="a.obj,b.off" picks the shared meshes (default: a set of 8).
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include "adaptex/core/allocator.h"
#include "adaptex/core/shapes.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/paint/generate.h"
#include "adaptex/paint/painter.h"
#include "adaptex/paint/signal.h"
#include "adaptex/paint/eval.h"
#include "adaptex/paint/surface_cache.h"
#include "adaptex/param/unwrap.h"

using namespace adaptex;

namespace {

Parameterization planar_param(const TriMesh& mesh) {
  Parameterization p;
  for (const Vec3& v : mesh.positions) p.uv.push_back(Vec2(v.x(), v.y()));
  p.uv_faces = mesh.faces;
  for (int v = 0; v < mesh.num_vertices(); ++v) p.wedge_vertex.push_back(v);
  p.face_chart.assign(mesh.faces.size(), 0);
  p.num_charts = 1;
  return p;
}

struct PlaneFixture {
  TriMesh mesh = shapes::plane(16);
  Parameterization param = planar_param(mesh);
};
PlaneFixture& plane() {
  static PlaneFixture f;
  return f;
}

/// Dabs along a zig-zag over the unit plane, spaced radius/4.
std::vector<Vec3> zigzag(double r, int n) {
  std::vector<Vec3> out;
  double x = 0.1, y = 0.1, dx = r / 4;
  for (int k = 0; k < n; ++k) {
    out.push_back(Vec3(x, y, 0));
    x += dx;
    if (x > 0.9 || x < 0.1) {
      dx = -dx;
      y += 2 * r;
      if (y > 0.9) y = 0.1;
    }
  }
  return out;
}

void BM_DabThroughput(benchmark::State& state) {
  const int size = 2048;
  const double r = state.range(0) / double(size);
  Painter painter(plane().mesh, plane().param, {size, size, 4});
  Stroke style;
  style.color = Vec3(0.8, 0.2, 0.1);
  style.radius = r;
  style.hardness = 0.7;
  const std::vector<Vec3> dabs = zigzag(r, 4096);
  size_t k = 0;
  const long long before = painter.texel_updates();
  for (auto _ : state) {
    painter.begin_stroke(style);
    for (int d = 0; d < 64; ++d) benchmark::DoNotOptimize(painter.add_dab(dabs[k++ % dabs.size()]));
    painter.end_stroke();
  }
  const double updates = static_cast<double>(painter.texel_updates() - before);
  state.counters["updates/s"] = benchmark::Counter(updates, benchmark::Counter::kIsRate);
  state.counters["us/dab"] = benchmark::Counter(64.0 * state.iterations() * 1e-6,
                                                benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_DabThroughput)->Arg(2)->Arg(4)->Arg(8)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond);

void BM_StrokeThroughput1T(benchmark::State& state) {
  const int size = 2048;
  const double r = state.range(0) / double(size);
  Painter painter(plane().mesh, plane().param, {size, size, 4});
  Stroke s;
  s.color = Vec3(0.1, 0.2, 0.8);
  s.radius = r;
  s.hardness = 0.7;
  s.dabs = zigzag(r, 256);
  tbb::task_arena one(1);
  const long long before = painter.texel_updates();
  for (auto _ : state) one.execute([&] { painter.paint_stroke(s); });
  state.counters["updates/s"] =
      benchmark::Counter(static_cast<double>(painter.texel_updates() - before), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_StrokeThroughput1T)->Arg(4)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond);

void BM_PainterSetup(benchmark::State& state) {
  const int size = static_cast<int>(state.range(0));
  for (auto _ : state) {
    Painter painter(plane().mesh, plane().param, {size, size, 4});
    benchmark::DoNotOptimize(painter.texel_map().inside.size());
  }
}
BENCHMARK(BM_PainterSetup)->Arg(1024)->Arg(2048)->Unit(benchmark::kMillisecond);

struct MeshCase {
  TriMesh mesh;
  Parameterization param;
  StrokeFile lines;
};

MeshCase& mesh_case(const std::string& name) {
  static std::map<std::string, std::unique_ptr<MeshCase>> cache;
  auto& slot = cache[name];
  if (!slot) {
    slot = std::make_unique<MeshCase>();
    slot->mesh = read_mesh(std::filesystem::path(ADAPTEX_SHARED_DIR) / "meshes" / name);
    slot->param = unwrap(slot->mesh).param;
    GenerateOptions g;
    g.kind = StrokeKind::Lines;
    g.seed = 1;
    slot->lines = generate_strokes(slot->mesh, g);
  }
  return *slot;
}

void BM_PaintLines(benchmark::State& state, std::string name, int size) {
  MeshCase& mc = mesh_case(name);
  const auto t0 = std::chrono::steady_clock::now();
  Painter setup(mc.mesh, mc.param, {size, size, 4});
  const double setup_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  long long updates = 0;
  std::optional<Painter> painter;
  for (auto _ : state) {
    state.PauseTiming();
    painter.reset();  // destruction (freeing ~100 MB) is not timed
    painter.emplace(mc.mesh, mc.param, PainterOptions{size, size, 4});
    state.ResumeTiming();
    painter->paint_all(mc.lines);
    benchmark::DoNotOptimize(painter->texture().data.data());
    updates += painter->texel_updates();
  }
  state.counters["setup_s"] = setup_s;
  state.counters["faces"] = mc.mesh.num_faces();
  state.counters["dabs"] = static_cast<double>(mc.lines.num_dabs());
  state.counters["updates"] = benchmark::Counter(static_cast<double>(updates), benchmark::Counter::kAvgIterations);
}

/// The safeguard's exact signal at 60,000 fixed surface samples (PointSignalCache), updated stroke
/// by stroke as a paint session does; the whole `lines` set, process CPU time.
void BM_PointCacheLines(benchmark::State& state, std::string name) {
  MeshCase& mc = mesh_case(name);
  const std::vector<SurfacePoint> pts = sample_surface(mc.mesh, 60000, 1);
  for (auto _ : state) {
    state.PauseTiming();
    PointSignalCache cache(mc.mesh, pts, mc.lines.background);
    state.ResumeTiming();
    for (const Stroke& s : mc.lines.strokes) cache.add_stroke(s);
    benchmark::DoNotOptimize(cache.values().data());
  }
  state.counters["strokes"] = static_cast<double>(mc.lines.strokes.size());
  state.counters["dabs"] = static_cast<double>(mc.lines.num_dabs());
}

const int registered = [] {
  std::string list = "venus.off,triceratops.off,spot.obj,dino.off,fandisk.off,kitten.obj,camelhead.off,bunny.ply";
  if (const char* env = std::getenv("ADAPTEX_BENCH_MESHES")) list = env;
  std::stringstream ss(list);
  std::string name;
  while (std::getline(ss, name, ','))
    for (int size : {1024, 2048})
      benchmark::RegisterBenchmark(("BM_PaintLines/" + name + "/" + std::to_string(size)).c_str(),
                                   [name, size](benchmark::State& st) { BM_PaintLines(st, name, size); })
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime()
          ->Iterations(3);
  std::stringstream again(list);
  while (std::getline(again, name, ','))
    benchmark::RegisterBenchmark(("BM_PointCacheLines/" + name).c_str(), [name](benchmark::State& st) { BM_PointCacheLines(st, name); })
        ->Unit(benchmark::kMillisecond)
        ->MeasureProcessCPUTime()
        ->Iterations(5);
  return 0;
}();


struct CacheFixture {
  TriMesh mesh = shapes::plane(224);
  Parameterization param;
  StrokeFile strokes;
  double spacing = 0;  // a third of the texel spacing at 1024²
  CacheFixture() {
    param = planar_param(mesh);
    GenerateOptions go;
    go.kind = StrokeKind::Mixed;
    go.count = 40;
    strokes = generate_strokes(mesh, go);
    spacing = 1.0 / 1024 / 3;
  }
};
CacheFixture& cache_fixture() {
  static CacheFixture f;
  return f;
}

void BM_SurfaceCacheBuild(benchmark::State& state) {
  CacheFixture& f = cache_fixture();
  long long samples = 0;
  for (auto _ : state) {
    SurfaceSignalCache cache(f.mesh, f.spacing, Vec3(1, 1, 1));
    samples = cache.num_samples();
    benchmark::DoNotOptimize(samples);
  }
  state.counters["samples"] = static_cast<double>(samples);
}
BENCHMARK(BM_SurfaceCacheBuild)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_SurfaceCacheStroke(benchmark::State& state) {
  CacheFixture& f = cache_fixture();
  SurfaceSignalCache cache(f.mesh, f.spacing, Vec3(1, 1, 1));
  size_t k = 0;
  for (auto _ : state) {
    cache.add_stroke(f.strokes.strokes[k]);
    k = (k + 1) % f.strokes.strokes.size();
  }
}
BENCHMARK(BM_SurfaceCacheStroke)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_SurfaceCacheTexelColours(benchmark::State& state) {
  CacheFixture& f = cache_fixture();
  SurfaceSignalCache cache(f.mesh, f.spacing, Vec3(1, 1, 1));
  cache.update(f.strokes);
  PainterOptions po;
  po.width = po.height = static_cast<int>(state.range(0));
  const Painter painter(f.mesh, f.param, po, Vec3(1, 1, 1));
  for (auto _ : state) {
    std::vector<Vec3f> c = cache.texel_colours(painter.texel_map(), f.mesh);
    benchmark::DoNotOptimize(c.data());
  }
  state.counters["texels"] = static_cast<double>(painter.texel_map().inside.size());
}
BENCHMARK(BM_SurfaceCacheTexelColours)->Arg(512)->Arg(1024)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  // As the adaptex programs run (core/allocator.h); ADAPTEX_DEFAULT_MALLOC=1 measures glibc's defaults.
  adaptex::keep_freed_memory_in_process_unless_disabled();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
