// Speed of the read-time validation and non-manifold repair (validate_mesh with repair, as
// `adaptex unwrap --repair` runs it) on a scan-like mesh built in code with the traps of a merged
// depth-fusion scan: ~1000 components, zero-area faces, duplicate faces and non-manifold edges and
// vertices (fins: a third face on an existing edge). Arg: target face count. docs/bench_unwrap.md.
#include <benchmark/benchmark.h>

#include "adaptex/core/shapes.h"
#include "adaptex/io/mesh_io.h"

namespace {

using namespace adaptex;

/// synthetic_scan() plus \p fins fins and \p fins / 4 duplicate faces spread over the mesh.
TriMesh trapped_scan(int faces, int fins) {
  TriMesh m = shapes::synthetic_scan(faces, 966, 1458);
  const int nf = m.num_faces();
  const int step = std::max(1, nf / (fins + 1));
  for (int i = 1; i <= fins; ++i) {
    const Face t = m.faces[static_cast<size_t>(i) * step % nf];
    const Vec3 apex = m.positions[t[0]] + Vec3(0.0, 0.0, 0.01) + 0.5 * (m.positions[t[1]] - m.positions[t[0]]);
    m.positions.push_back(apex);
    m.faces.push_back({t[0], t[1], m.num_vertices() - 1});
    if (i % 4 == 0) m.faces.push_back(t);
  }
  return m;
}

void BM_ValidateRepair(benchmark::State& state) {
  const TriMesh mesh = trapped_scan(static_cast<int>(state.range(0)), 654);
  ReadOptions options;
  options.repair = true;
  ReadReport report;
  for (auto _ : state) {
    report = ReadReport();
    benchmark::DoNotOptimize(validate_mesh(mesh, "scan", options, &report));
  }
  state.counters["split_vertices"] = report.split_nonmanifold_vertices;
  state.counters["faces"] = mesh.num_faces();
}
BENCHMARK(BM_ValidateRepair)->Arg(250000)->Arg(1000000)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
