// adaptex (Floater + Yoshizawa) next to CGAL 5.5 Iterative_authalic_parameterizer_3 with
// Square_border_arc_length_parameterizer_3 on the same disks, in one run: time (wall) and the mesh L2
// stretch (Sander 2001, normalized, 1 = ideal) of both, measured by the same adaptex::measure_stretch().
// CGAL is a benchmark-only dependency. Run: build/bench/param/bench_param_cgal --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/Iterative_authalic_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Square_border_parameterizer_3.h>

#include "adaptex/param/disk_param.h"
#include "adaptex/param/stretch.h"
#include "bench_disks.h"

using namespace adaptex;
using Kernel = CGAL::Simple_cartesian<double>;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using VertexDesc = SurfaceMesh::Vertex_index;
namespace SMP = CGAL::Surface_mesh_parameterization;

static void adaptex_case(benchmark::State& state, const std::string& name, EmbeddingWeights w) {
  const TriMesh& m = bench::disk(name);
  if (m.num_faces() == 0) return state.SkipWithError("mesh not available");
  DiskParamOptions opt;
  opt.weights = w;
  DiskParamResult r;
  for (auto _ : state) r = parameterize_disk(m, {}, opt);
  const StretchStats st = measure_stretch(m, r.uv);
  state.counters["faces"] = m.num_faces();
  state.counters["L2"] = st.l2;
  state.counters["Linf"] = st.linf;
  state.counters["flipped"] = st.flipped;
  state.counters["L2_floater"] = r.floater_l2;
}

static void cgal_case(benchmark::State& state, const std::string& name, unsigned iterations) {
  const TriMesh& m = bench::disk(name);
  if (m.num_faces() == 0) return state.SkipWithError("mesh not available");
  std::vector<Vec2> uv(m.positions.size());
  SMP::Error_code err = SMP::OK;
  for (auto _ : state) {
    state.PauseTiming();  // building the Surface_mesh is not part of the parameterization
    SurfaceMesh sm;
    for (const Vec3& p : m.positions) sm.add_vertex(Kernel::Point_3(p.x(), p.y(), p.z()));
    for (const Face& f : m.faces) sm.add_face(VertexDesc(f[0]), VertexDesc(f[1]), VertexDesc(f[2]));
    auto uvmap = sm.add_property_map<VertexDesc, Kernel::Point_2>("v:uv").first;
    const auto bhd = CGAL::Polygon_mesh_processing::longest_border(sm).first;
    state.ResumeTiming();
    using Border = SMP::Square_border_arc_length_parameterizer_3<SurfaceMesh>;
    SMP::Iterative_authalic_parameterizer_3<SurfaceMesh, Border> param;
    err = param.parameterize(sm, bhd, uvmap, iterations);
    state.PauseTiming();
    for (VertexDesc v : sm.vertices()) uv[v.idx()] = Vec2(uvmap[v].x(), uvmap[v].y());
    state.ResumeTiming();
  }
  if (err != SMP::OK) return state.SkipWithError(SMP::get_error_message(err));
  StretchStats st = measure_stretch(m, uv);
  if (st.flipped * 2 > m.num_faces()) {  // CGAL's square runs the other way round: mirror to compare
    for (Vec2& t : uv) t.x() = 1 - t.x();
    st = measure_stretch(m, uv);
  }
  state.counters["faces"] = m.num_faces();
  state.counters["L2"] = st.l2;
  state.counters["Linf"] = st.linf;
  state.counters["flipped"] = st.flipped;
}

int main(int argc, char** argv) {
  for (const char* name : {"bump10k", "bump100k", "face", "camelhead"}) {
    const int its = std::string(name) == "bump100k" ? 1 : 2;
    benchmark::RegisterBenchmark((std::string("adaptex/") + name).c_str(),
                                 [n = std::string(name)](benchmark::State& s) {
                                   adaptex_case(s, n, EmbeddingWeights::ShapePreserving);
                                 })
        ->Unit(benchmark::kMillisecond)->Iterations(its)->UseRealTime();
    benchmark::RegisterBenchmark((std::string("adaptex_meanvalue/") + name).c_str(),
                                 [n = std::string(name)](benchmark::State& s) {
                                   adaptex_case(s, n, EmbeddingWeights::MeanValue);
                                 })
        ->Unit(benchmark::kMillisecond)->Iterations(its)->UseRealTime();
    benchmark::RegisterBenchmark((std::string("CGAL_iterative_authalic/") + name).c_str(),
                                 [n = std::string(name)](benchmark::State& s) { cgal_case(s, n, 15); })
        ->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
