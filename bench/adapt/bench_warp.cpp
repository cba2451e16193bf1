// Warp methods at the same grid size (issue 12): the flow-based density-equalizing map
// (density_flow.h) next to the thesis relaxation (relax.h), on the same field: thin dense lines on a
// low floor (density-flow's density; the relaxation gets the matching L_s² = 1 / density, clamped).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>

#include "adaptex/adapt/density_flow.h"
#include "adaptex/adapt/relax.h"

namespace {
using namespace adaptex;

ImageF lines_density(int L) {
  ImageF d(L, L, 0.15f);
  for (int j = 0; j < L; ++j)
    for (int i = 0; i < L; ++i) {
      const double x = (i + 0.5) / L, y = (j + 0.5) / L;
      const double r = std::min(std::abs(y - 0.3 - 0.2 * x), std::abs(x - 0.6 + 0.1 * y));
      d.at(i, j) = static_cast<float>(0.15 + 6.0 * std::exp(-0.5 * std::pow(r / 0.03, 2)));
    }
  return d;
}

void BM_DensityFlow(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const ImageF d = lines_density(n);
  DensityFlowOptions o;
  o.cells = n;
  for (auto _ : state) benchmark::DoNotOptimize(density_equalizing_warp(d, o));
}

void BM_ThesisRelaxation(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  ImageF w = lines_density(n);
  for (float& v : w.data) v = std::clamp(1.0f / v, 0.02f, 1.0f);
  RelaxOptions o;
  o.epsilon = 0.05 / 1024;
  o.max_iterations = 300;
  for (auto _ : state) {
    GridWarp g = GridWarp::uniform(n);
    benchmark::DoNotOptimize(relax_grid(g, w, o));
  }
}
}  // namespace

BENCHMARK(BM_DensityFlow)->Arg(64)->Arg(256)->Arg(1024)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ThesisRelaxation)->Arg(64)->Arg(256)->Arg(1024)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
