// Benchmark of refine_for_warp() (issue 12 item 3, docs/adaptive.md "Refinement under the warp"):
// an n x n quad height field (2 n^2 faces, uv = xy) under a radial magnifier warp of the square
// (ten lenses, about 11 % of the faces lie under one, magnification 3.8 at their centres), refined to
// half a texel of a 4096² texture in at most 3 rounds. The warp is either the analytic map or a 256-cell
// GridWarp sampled from it (the form adaptex's warps take; called through GridWarp::apply).
// Counters: added faces, rounds, share of input faces split, max deviation after refinement (texels).
//
//   adaptex_bench_refine [--benchmark_filter=...]        args: faces / grid warp (0 analytic, 1 grid)
#include <benchmark/benchmark.h>

#include <cmath>
#include <functional>
#include <utility>

#include "adaptex/adapt/grid.h"
#include "adaptex/adapt/refine.h"
#include "adaptex/core/shapes.h"

using namespace adaptex;

namespace {

constexpr double kTexels = 4096;  // texture size N: tolerance = half a texel

// Height field over the unit square, 2 n^2 faces; its UV layout is the xy projection (one chart).
std::pair<TriMesh, Parameterization> height_field(long faces) {
  std::pair<TriMesh, Parameterization> s;
  auto& [mesh, param] = s;
  mesh = shapes::plane(static_cast<int>(std::lround(std::sqrt(faces / 2.0))));
  param.uv_faces = mesh.faces;
  for (Vec3& p : mesh.positions) {
    param.uv.push_back(p.head<2>());
    param.wedge_vertex.push_back(param.num_wedges() - 1);
    p.z() = 0.25 * std::sin(3.0 * p.x()) * std::cos(2.0 * p.y());
  }
  param.face_chart.assign(mesh.faces.size(), 0);
  param.num_charts = 1;
  return s;
}

// Ten disjoint radial magnifiers ("lenses") of radius 0.06 on a 4 x 3 lattice minus two: each maps
// its disk onto itself, x -> c + (x - c)(1 + k (1 - r/R)^2), so their union is a diffeomorphism of the
// square; magnification 1 + k = 3.8 at the centres. About 11 % of the square is under a lens.
Vec2 magnify(const Vec2& p) {
  const double R = 0.06, k = 2.8;
  for (int l = 0; l < 10; ++l) {
    const Vec2 c(0.15 + 0.233 * (l % 4), 0.2 + 0.3 * (l / 4));
    const Vec2 d = p - c;
    const double t = d.norm() / R;
    if (t < 1) return c + d * (1 + k * (1 - t) * (1 - t));
  }
  return p;
}

void BM_Refine(benchmark::State& state) {
  const auto [mesh, param] = height_field(state.range(0));
  GridWarp grid = GridWarp::uniform(256);
  for (Vec2& p : grid.points) p = magnify(p);
  std::function<Vec2(const Vec2&)> warp = magnify;
  if (state.range(1) == 1) warp = [&grid](const Vec2& p) { return grid.apply(p); };
  RefineOptions o;
  o.tolerance = 0.5 / kTexels;
  o.max_levels = 3;
  RefineResult r;
  for (auto _ : state) {
    r = refine_for_warp(mesh, param, warp, o);
    benchmark::DoNotOptimize(r.mesh.faces.data());
  }
  std::vector<char> split(mesh.num_faces(), 0);
  for (int f = 0; f < r.mesh.num_faces(); ++f)
    if (f >= mesh.num_faces() || r.mesh.faces[f] != mesh.faces[f]) split[r.parent_face[f]] = 1;
  long n_split = 0;
  for (char c : split) n_split += c;
  state.counters["faces_in"] = mesh.num_faces();
  state.counters["added_faces"] = r.added_faces;
  state.counters["levels"] = r.levels;
  state.counters["split_share"] = static_cast<double>(n_split) / mesh.num_faces();
  state.counters["max_dev_texels"] = r.max_deviation * kTexels;
}

}  // namespace

BENCHMARK(BM_Refine)
    ->ArgsProduct({{100000, 400000}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK_MAIN();
