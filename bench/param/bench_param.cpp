// Floater and Floater + Yoshizawa (parameterize_disk) on generated disks of ~10k, 100k and 1M faces
// and on the open shared meshes. Counters: mesh L2 stretch before/after Yoshizawa, iterations.
// Overlaps/*: the overlap checks (count_overlapping_triangles, invalid_uv_faces) of a Floater layout.
// Run: build/bench/param/bench_param --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include "adaptex/param/disk_param.h"
#include "adaptex/param/stretch.h"
#include "bench_disks.h"

using namespace adaptex;

static void run(benchmark::State& state, const std::string& name, bool yoshizawa,
                TutteSolver::Backend backend) {
  const TriMesh& m = bench::disk(name);
  if (m.num_faces() == 0) {
    state.SkipWithError("mesh not available (../shared/meshes absent)");
    return;
  }
  DiskParamOptions opt;
  opt.yoshizawa = yoshizawa;
  opt.backend = backend;
  DiskParamResult r;
  for (auto _ : state) {
    r = parameterize_disk(m, {}, opt);
    benchmark::DoNotOptimize(r.uv.data());
  }
  state.counters["faces"] = m.num_faces();
  state.counters["L2_floater"] = r.floater_l2;
  state.counters["L2_final"] = r.final_l2;
  state.counters["Linf_final"] = r.final_linf;
  state.counters["yoshizawa_its"] = r.iterations;
  state.counters["t_floater_s"] = r.time_floater;
  state.counters["t_yoshizawa_s"] = r.time_yoshizawa;
}

// The overlap checks of a packed layout: the Floater layout of a generated disk, whose neighbours
// share edges and vertices (the pairs the grid hands to the separating-axis test).
static void overlaps(benchmark::State& state, const std::string& name, bool invalid_faces) {
  const TriMesh& m = bench::disk(name);
  DiskParamOptions opt;
  opt.yoshizawa = false;
  Parameterization p;
  p.uv = parameterize_disk(m, {}, opt).uv;
  p.uv_faces = m.faces;
  long found = 0;
  for (auto _ : state) {
    found = invalid_faces ? static_cast<long>(invalid_uv_faces(p).size())
                          : count_overlapping_triangles(p, 1);
    benchmark::DoNotOptimize(found);
  }
  state.counters["faces"] = m.num_faces();
  state.counters["found"] = static_cast<double>(found);
}

int main(int argc, char** argv) {
  using B = TutteSolver::Backend;
  struct Case {
    const char* name;
    int iterations;
  };
  for (const Case& c : {Case{"bump10k", 5}, Case{"bump100k", 2}, Case{"bump1M", 1},
                        Case{"face", 2}, Case{"camelhead", 2}}) {
    for (bool y : {false, true}) {
      const std::string label = std::string(y ? "FloaterYoshizawa/" : "Floater/") + c.name;
      benchmark::RegisterBenchmark(label.c_str(), [=](benchmark::State& s) { run(s, c.name, y, B::Auto); })
          ->Unit(benchmark::kMillisecond)->Iterations(c.iterations)->UseRealTime();
    }
  }
  // Solver backends on the 100k disk (Floater + Yoshizawa).
  for (auto [b, n] : {std::pair{B::Klu, "Klu"}, std::pair{B::Umfpack, "Umfpack"},
                      std::pair{B::SparseLU, "SparseLU"}, std::pair{B::Multigrid, "Multigrid"}}) {
    const std::string label = std::string("Backend/") + n + "/bump100k";
    benchmark::RegisterBenchmark(label.c_str(), [b = b](benchmark::State& s) { run(s, "bump100k", true, b); })
        ->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();
  }
  for (const char* name : {"bump10k", "bump100k"}) {
    benchmark::RegisterBenchmark((std::string("Overlaps/count/") + name).c_str(),
                                 [=](benchmark::State& s) { overlaps(s, name, false); })
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark((std::string("Overlaps/invalid_faces/") + name).c_str(),
                                 [=](benchmark::State& s) { overlaps(s, name, true); })
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
