// Speed of the chart segmentation (segment_charts(), charts.h) that every `--charts auto` attempt
// runs: the shared meshes that become several charts in the speed benchmark (triceratops: 4, 6, 8
// charts tried; dino: 4, 6, 8, 12), at the chart counts auto tries, and the sequence 4, 6, 8, 12
// with one ChartSegmenter kept across it (as unwrap() does) or without. docs/bench_unwrap.md.
//
//   build/bench/unwrap/bench_segment_speed --benchmark_repetitions=9
//       --benchmark_report_aggregates_only=true   (one line)
#include <benchmark/benchmark.h>

#include <optional>
#include <string>
#include <vector>

#include "adaptex/param/charts.h"
#include "bench_shared_mesh.h"

using namespace adaptex;

namespace {

void run(benchmark::State& state, const std::string& file, int charts) {
  const std::optional<TriMesh> loaded = bench::shared_mesh_or_skip(state, file);
  if (!loaded) return;
  const TriMesh& mesh = *loaded;
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
  const std::optional<TriMesh> loaded = bench::shared_mesh_or_skip(state, file);
  if (!loaded) return;
  const TriMesh& mesh = *loaded;
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
    for (int k : {4, 6, 8, 12, 64})
      bench::register_ms(std::string("Segment/") + file + "/" + std::to_string(k),
                         [file, k](benchmark::State& s) { run(s, file, k); });
  for (const char* file : {"triceratops.off", "dino.off"})
    for (bool reuse : {false, true})
      bench::register_ms(std::string("Sequence/") + file + (reuse ? "/reused" : "/fresh"),
                         [file, reuse](benchmark::State& s) { run_sequence(s, file, reuse); });
  return bench::run_benchmarks(argc, argv);
}
