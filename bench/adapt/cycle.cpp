// Benchmark of the full re-parameterization cycle (docs/bench_adapt.md): importance map + stretch map
// + L_s² + two-stage relaxation + safe remap + texel map of the new layout + texture update
// (resample), on a curved height-field mesh of F faces with a W x W texture and a fine grid of G
// cells (coarse 16). Counters give each phase in ms (mean over the iterations).
//
//   adaptex_adapt_cycle [--benchmark_filter=...]   args: faces / texture size / fine grid
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <random>

#include "adaptex/adapt/adapt.h"
#include "adaptex/adapt/texture_update.h"
#include "adaptex/core/shapes.h"
#include "adaptex/paint/texel_map.h"

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
    const int n = static_cast<int>(std::lround(std::sqrt(faces / 2.0)));
    s->mesh = shapes::plane(n);
    for (Vec3& p : s->mesh.positions) p.z() = 0.25 * std::sin(3.0 * p.x()) * std::cos(2.0 * p.y());
    for (const Vec3& p : s->mesh.positions) s->param.uv.push_back(Vec2(p.x(), p.y()));
    s->param.uv_faces = s->mesh.faces;
    for (int k = 0; k < s->mesh.num_vertices(); ++k) s->param.wedge_vertex.push_back(k);
    s->param.face_chart.assign(s->mesh.faces.size(), 0);
    s->param.num_charts = 1;
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

void BM_Cycle(benchmark::State& state) {
  const int faces = static_cast<int>(state.range(0)), W = static_cast<int>(state.range(1));
  const int grid = static_cast<int>(state.range(2));
  const Scene& sc = scene(faces);
  const ImageRGBA8 tex = lines_texture(W);
  const TexelMap map = build_texel_map(sc.mesh, sc.param, W, W);
  AdaptOptions o;
  o.fine_grid = grid;
  o.coarse_grid = std::min(16, grid);
  std::map<std::string, double> acc;
  int iters = 0;
  for (auto _ : state) {
    AdaptResult r = adapt_parameterization(sc.mesh, sc.param, tex, map, o);
    auto t0 = std::chrono::steady_clock::now();
    const TexelMap nmap = build_texel_map(sc.mesh, r.param, W, W);
    auto t1 = std::chrono::steady_clock::now();
    ImageRGBA8 ntex = resample_texture(sc.param, tex, nmap, 4);
    auto t2 = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(ntex.data.data());
    const AdaptReport& rep = r.report;
    acc["importance_ms"] += 1e3 * rep.time_importance;
    acc["stretch_ms"] += 1e3 * rep.time_stretch_map;
    acc["ls2_ms"] += 1e3 * rep.time_ls2;
    acc["coarse_ms"] += 1e3 * rep.time_coarse;
    acc["fine_ms"] += 1e3 * rep.time_fine;
    acc["remap_ms"] += 1e3 * rep.time_remap;
    acc["texelmap_ms"] += 1e3 * std::chrono::duration<double>(t1 - t0).count();
    acc["resample_ms"] += 1e3 * std::chrono::duration<double>(t2 - t1).count();
    acc["fine_iters"] += rep.fine_iterations;
    ++iters;
  }
  for (auto& [k, v] : acc) state.counters[k] = v / std::max(1, iters);
  state.counters["faces"] = sc.mesh.num_faces();
}

void args(benchmark::internal::Benchmark* b) {
  for (int f : {10000, 100000, 1000000})
    for (int w : {512, 1024, 2048}) b->Args({f, w, 256});
  for (int g : {64, 1024}) b->Args({100000, 1024, g});
}

}  // namespace

BENCHMARK(BM_Cycle)->Apply(args)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(1.0);
BENCHMARK_MAIN();
