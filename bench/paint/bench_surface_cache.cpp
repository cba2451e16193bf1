// Surface signal cache benchmarks (paint/surface_cache.h; docs/bench_adapt.md, "Session 19"), on a
// plane of 100,352 faces with uv = xy, sample spacing a third of the texel spacing at 1024² (what
// PaintSession uses, PaintSessionOptions::surface_cache = 3):
//  - BM_SurfaceCacheBuild: the lattice and the face index (counter "samples").
//  - BM_SurfaceCacheStroke: compositing one generated `mixed` stroke (the 40 strokes in turn).
//  - BM_SurfaceCacheTexelColours/<size>: the colours of every chart texel of the plane's texel map at
//    size² (what replaces the replay of the history), all cores.
#include <benchmark/benchmark.h>

#include <cmath>

#include "adaptex/core/allocator.h"
#include "adaptex/core/shapes.h"
#include "adaptex/paint/generate.h"
#include "adaptex/paint/painter.h"
#include "adaptex/paint/surface_cache.h"

using namespace adaptex;

namespace {

struct Fixture {
  TriMesh mesh = shapes::plane(224);
  Parameterization param;
  StrokeFile strokes;
  double spacing = 0;  // a third of the texel spacing at 1024²
  Fixture() {
    for (const Vec3& v : mesh.positions) param.uv.push_back(Vec2(v.x(), v.y()));
    param.uv_faces = mesh.faces;
    for (int v = 0; v < mesh.num_vertices(); ++v) param.wedge_vertex.push_back(v);
    param.face_chart.assign(mesh.faces.size(), 0);
    param.num_charts = 1;
    GenerateOptions go;
    go.kind = StrokeKind::Mixed;
    go.count = 40;
    strokes = generate_strokes(mesh, go);
    spacing = 1.0 / 1024 / 3;
  }
};
Fixture& fixture() {
  static Fixture f;
  return f;
}

void BM_SurfaceCacheBuild(benchmark::State& state) {
  Fixture& f = fixture();
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
  Fixture& f = fixture();
  SurfaceSignalCache cache(f.mesh, f.spacing, Vec3(1, 1, 1));
  size_t k = 0;
  for (auto _ : state) {
    cache.add_stroke(f.strokes.strokes[k]);
    k = (k + 1) % f.strokes.strokes.size();
  }
}
BENCHMARK(BM_SurfaceCacheStroke)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_SurfaceCacheTexelColours(benchmark::State& state) {
  Fixture& f = fixture();
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
