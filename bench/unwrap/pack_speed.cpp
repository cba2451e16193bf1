// Speed of pack_rectangles() (RectPackOptions, turning, gap of 8 texels at 4096) for 100 to 20000
// chart rectangles spread over three decades of size: the MaxRects strategies up to 200
// rectangles, FFDH and next-fit shelves above (O(n log n) per scale tried). docs/bench_unwrap.md.
// BM_PackShapes: pack_shapes() (horizon packing of rasterized charts, holes filled; 4,096 raster cells
// from 4,097 charts) for 1000 to 20000 irregular charts (fans of 3-11 triangles) of the same
// spread of sizes, gap of 2 texels at 1024.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "adaptex/param/pack.h"

namespace {

std::vector<adaptex::Vec2> spread(int n) {
  std::vector<adaptex::Vec2> s(n);
  for (int i = 0; i < n; ++i) {
    const double side = std::pow(10.0, -3.0 * ((i * 7919) % 1000) / 1000.0);
    const double aspect = std::pow(4.0, ((i * 31) % 17 - 8) / 8.0);
    s[i] = adaptex::Vec2(side * std::sqrt(aspect), side / std::sqrt(aspect));
  }
  return s;
}

void BM_PackRectangles(benchmark::State& state) {
  const std::vector<adaptex::Vec2> sizes = spread(static_cast<int>(state.range(0)));
  adaptex::RectPackOptions o;
  o.padding = 8.0 / 4096;
  o.min_side = o.padding;
  o.may_turn = true;
  for (auto _ : state) benchmark::DoNotOptimize(adaptex::pack_rectangles(sizes, o).data());
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_PackRectangles)->Arg(100)->Arg(200)->Arg(500)->Arg(501)->Arg(1000)->Arg(5000)->Arg(20000)
    ->Unit(benchmark::kMillisecond);

/// Irregular star-shaped fans of 3-11 triangles with the sizes of spread(n), deterministic.
std::vector<adaptex::ChartShape> spread_shapes(int n) {
  const std::vector<adaptex::Vec2> sizes = spread(n);
  std::vector<adaptex::ChartShape> charts(n);
  for (int i = 0; i < n; ++i) {
    adaptex::ChartShape& c = charts[i];
    const int k = 3 + (i * 13) % 9;
    c.uv.push_back(adaptex::Vec2::Zero());
    for (int j = 0; j < k; ++j) {
      const double a = 2 * M_PI * j / k, r = 0.5 + 0.5 * ((i * 7 + j * 3) % 5) / 4.0;
      c.uv.push_back(r * adaptex::Vec2(sizes[i].x() * std::cos(a), sizes[i].y() * std::sin(a)));
    }
    for (int j = 0; j < k; ++j) c.faces.push_back({0, 1 + j, 1 + (j + 1) % k});
  }
  return charts;
}

void BM_PackShapes(benchmark::State& state) {
  const std::vector<adaptex::ChartShape> charts = spread_shapes(static_cast<int>(state.range(0)));
  adaptex::ShapePackOptions o;
  o.padding = 2.0 / 1024;
  o.min_side = o.padding;
  for (auto _ : state) benchmark::DoNotOptimize(adaptex::pack_shapes(charts, o).data());
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_PackShapes)->Arg(1000)->Arg(3000)->Arg(10000)->Arg(20000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
