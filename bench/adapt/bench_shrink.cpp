// The shrink of a textured asset (adapt/shrink.h): 1024² -> 256² of a ~10k-face asset with two maps
// (base colour and normal), built in code like a game asset's atlas: 12 charts of 882 faces, two of
// them mirrored onto the same texels, detail that differs from chart to chart. docs/shrink.md.
#include <benchmark/benchmark.h>

#include <cmath>

#include "adaptex/adapt/shrink.h"

namespace {
using namespace adaptex;

struct Asset {
  TriMesh mesh;
  Parameterization param;
  std::vector<ShrinkMap> maps;
};

/// A curved patch of n x n quads at 3-D offset (x0, 0) with UV uv0 + (s·x, t·y), x, y in [0,1].
void patch(Asset& a, double x0, int n, Vec2 uv0, double s, double t) {
  const int v0 = a.mesh.num_vertices(), w0 = a.param.num_wedges();
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = double(i) / n, y = double(j) / n;
      a.mesh.positions.push_back(Vec3(x0 + x, y, 0.2 * std::sin(3 * x) * std::cos(2 * y)));
      a.param.uv.push_back(uv0 + Vec2(s * x, t * y));
      a.param.wedge_vertex.push_back(a.mesh.num_vertices() - 1);
    }
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      for (const Face& f : {Face{id(i, j), id(i + 1, j), id(i + 1, j + 1)}, Face{id(i, j), id(i + 1, j + 1), id(i, j + 1)}}) {
        a.mesh.faces.push_back({v0 + f[0], v0 + f[1], v0 + f[2]});
        a.param.uv_faces.push_back({w0 + f[0], w0 + f[1], w0 + f[2]});
        a.param.face_chart.push_back(a.param.num_charts);
      }
  ++a.param.num_charts;
}

Asset asset() {
  Asset a;
  int c = 0;
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 4; ++k, ++c) {
      const Vec2 uv0(0.02 + 0.245 * k, 0.02 + 0.33 * r);
      if (c == 11)
        patch(a, 2.0 * c, 21, Vec2(0.02 + 0.245 * 2 + 0.22, 0.02 + 0.33 * 2), -0.22, 0.3);  // mirrors chart 10
      else
        patch(a, 2.0 * c, 21, uv0, 0.22, 0.3);
    }
  ImageRGBA8 color(1024, 1024), normal(1024, 1024);
  for (int j = 0; j < 1024; ++j)
    for (int i = 0; i < 1024; ++i) {
      const double u = (i + 0.5) / 1024, v = (j + 0.5) / 1024;
      const double detail = u < 0.5 ? 1.0 : 0.15;  // the left charts carry the detail
      const double w = detail * std::sin(i * 0.9) * std::sin(j * 0.7) + 0.3 * std::sin(6 * u + 4 * v);
      std::uint8_t* t = color.texel(i, j);
      t[0] = static_cast<std::uint8_t>(128 + 90 * w);
      t[1] = static_cast<std::uint8_t>(100 + 60 * v);
      t[2] = static_cast<std::uint8_t>(128 - 80 * w);
      t[3] = 255;
      std::uint8_t* n = normal.texel(i, j);
      n[0] = static_cast<std::uint8_t>(128 + 40 * std::sin(j * 0.3));
      n[1] = 128;
      n[2] = 240;
      n[3] = 255;
    }
  a.maps = {{"base_color", color, MapKind::Color}, {"normal", normal, MapKind::Normal}};
  return a;
}

void BM_Shrink1024To256TwoMaps(benchmark::State& state) {
  static const Asset a = asset();
  ShrinkOptions o;
  o.size = 256;
  ShrinkResult r;
  for (auto _ : state) r = shrink_textured_mesh(a.mesh, a.param, a.maps, o);
  state.counters["faces"] = a.mesh.num_faces();
  state.counters["gain_dB"] = r.psnr - r.psnr_downsized;
}
// Wall time (the target is wall time on 2 cores) and the CPU time of every thread; median of 3.
BENCHMARK(BM_Shrink1024To256TwoMaps)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->Repetitions(3)
    ->ReportAggregatesOnly(true)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
