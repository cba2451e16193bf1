// Texel-fit benchmarks (docs/texel_fit.md): a 10,000-face torus with its unwrap() atlas and two
// 1024² maps built in code (texel_fit_fixture.h), all cores, wall time.
//  - BM_FitTexels/<size>: fit_resize() of one map onto the same atlas at size² (the artist's-layout
//    case of a shrink): quadrature, matrix, solve, pull-push. Counters: samples, CG iterations.
//  - BM_FitTwoMaps/<size>: one TexelFitter and fit() of both maps (what a shrink with two maps pays).
//  - BM_PointResample/<size>: build_texel_map() + resample_texture() of one map (today's reparam path).
#include <benchmark/benchmark.h>

#include "adaptex/adapt/texture_update.h"
#include "adaptex/paint/texel_fit.h"
#include "texel_fit_fixture.h"

using namespace adaptex;

namespace {

const bench::TexturedFixture& fixture() {
  static const bench::TexturedFixture f = bench::textured_torus(100, 50, 1024);
  return f;
}

void BM_FitTexels(benchmark::State& state) {
  const auto& f = fixture();
  const int size = static_cast<int>(state.range(0));
  TexelFitResult r;
  for (auto _ : state) {
    r = fit_resize(f.mesh, f.param, f.diffuse, size, size);
    benchmark::DoNotOptimize(r.texture.data.data());
  }
  state.counters["faces"] = f.mesh.num_faces();
  state.counters["samples"] = static_cast<double>(r.samples);
  state.counters["iterations"] = r.iterations;
}
BENCHMARK(BM_FitTexels)->Arg(256)->Arg(128)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_FitTwoMaps(benchmark::State& state) {
  const auto& f = fixture();
  const int size = static_cast<int>(state.range(0));
  for (auto _ : state) {
    const TexelFitter fitter(f.mesh, f.param, f.diffuse.width, f.diffuse.height, f.param, size, size);
    const TexelFitResult a = fitter.fit(f.diffuse), b = fitter.fit(f.data);
    benchmark::DoNotOptimize(a.texture.data.data());
    benchmark::DoNotOptimize(b.texture.data.data());
  }
}
BENCHMARK(BM_FitTwoMaps)->Arg(256)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_PointResample(benchmark::State& state) {
  const auto& f = fixture();
  const int size = static_cast<int>(state.range(0));
  for (auto _ : state) {
    const ImageRGBA8 out = resample_texture(f.param, f.diffuse, build_texel_map(f.mesh, f.param, size, size), 4);
    benchmark::DoNotOptimize(out.data.data());
  }
}
BENCHMARK(BM_PointResample)->Arg(256)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
