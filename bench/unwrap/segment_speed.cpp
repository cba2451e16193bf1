// Speed of the chart segmentation (segment_charts(), charts.h) that every `--charts auto` attempt
// runs: the shared meshes that become several charts in the speed benchmark (triceratops: 4, 6, 8
// charts tried; dino: 4, 6, 8, 12), at the chart counts auto tries, and the sequence 4, 6, 8, 12
// with one ChartSegmenter kept across it (as unwrap() does) or without. docs/bench_unwrap.md.
//
//   build/bench/unwrap/bench_segment_speed --benchmark_repetitions=9
//       --benchmark_report_aggregates_only=true   (one line)
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>
#include <vector>

#include "adaptex/io/mesh_io.h"
#include "adaptex/param/charts.h"

using namespace adaptex;

namespace {

void run(benchmark::State& state, const std::string& file, int charts) {
  const std::filesystem::path path = std::filesystem::path(ADAPTEX_SHARED_DIR) / "meshes" / file;
  if (!std::filesystem::exists(path)) {
    state.SkipWithError("mesh not available (../shared/meshes absent)");
    return;
  }
  const TriMesh mesh = read_mesh(path);
  ChartSegmentOptions options;
  options.num_charts = charts;
  options.normal_weight = 0;  // UnwrapOptions::chart_normal_weight default
  for (auto _ : state) {
    std::vector<int> label = segment_charts(mesh, options);
    benchmark::DoNotOptimize(label.data());
  }
  state.counters["faces"] = mesh.num_faces();
}

/// The chart counts auto tries on dino (4, 6, 8, 12), with one ChartSegmenter kept across them
/// (\p reuse, as unwrap() does) or segment_charts() each time.
void run_sequence(benchmark::State& state, const std::string& file, bool reuse) {
  const std::filesystem::path path = std::filesystem::path(ADAPTEX_SHARED_DIR) / "meshes" / file;
  if (!std::filesystem::exists(path)) {
    state.SkipWithError("mesh not available (../shared/meshes absent)");
    return;
  }
  const TriMesh mesh = read_mesh(path);
  for (auto _ : state) {
    ChartSegmenter segmenter(mesh);
    for (int k : {4, 6, 8, 12}) {
      ChartSegmentOptions options;
      options.num_charts = k;
      options.normal_weight = 0;
      std::vector<int> label = reuse ? segmenter.segment(options) : segment_charts(mesh, options);
      benchmark::DoNotOptimize(label.data());
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  for (const char* file : {"triceratops.off", "dino.off"})
    for (int k : {4, 6, 8, 12, 64}) {
      const std::string label = std::string("Segment/") + file + "/" + std::to_string(k);
      benchmark::RegisterBenchmark(label.c_str(), [file, k](benchmark::State& s) { run(s, file, k); })
          ->Unit(benchmark::kMillisecond)
          ->MeasureProcessCPUTime()
          ->UseRealTime();
    }
  for (const char* file : {"triceratops.off", "dino.off"})
    for (bool reuse : {false, true}) {
      const std::string label = std::string("Sequence/") + file + (reuse ? "/reused" : "/fresh");
      benchmark::RegisterBenchmark(label.c_str(),
                                   [file, reuse](benchmark::State& s) { run_sequence(s, file, reuse); })
          ->Unit(benchmark::kMillisecond)
          ->MeasureProcessCPUTime()
          ->UseRealTime();
    }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
