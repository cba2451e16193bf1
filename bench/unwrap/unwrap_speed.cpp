// Speed of the whole unwrap() (cut + Floater + Yoshizawa + augmentation + packing) against thesis
// Table 4.1 ("Init-param." column, 2005 hardware), issue 8 target: >= 100x the thesis speed at the
// same face count. Each benchmark reports the median wall time (ms) over its repetitions and the
// counters target_ms = thesis_s * 1000 / 100, thesis_s, L2 (final mesh L2 stretch), faces, augm
// (cut augmentations), charts and share (effective texel share = coverage / L2²). Each mesh runs
// with the default `ChartMode::Auto` ("auto/") and with one chart per component ("single/", the
// thesis' layout, the like-for-like comparison with Table 4.1), and "auto-spec2/": auto with
// UnwrapOptions::speculative_attempts = 2. "Time" is wall time, "CPU" the process CPU time (all
// threads).
//
//   build/bench/unwrap/bench_unwrap_speed --benchmark_repetitions=15
//       --benchmark_report_aggregates_only=true --benchmark_counters_tabular=true   (one line)
//
// The shared meshes stand in for the thesis models of (about) the same face count: venus.off for
// venus (1396 faces), triceratops.off for triceratops (5660), dino.off (7828) for horse (7500).
// Results: docs/benchmarks.md.
#include <benchmark/benchmark.h>

#include <optional>
#include <string>

#include "adaptex/param/unwrap.h"
#include "bench_shared_mesh.h"

using namespace adaptex;

namespace {

struct ThesisRow {
  const char* thesis_model;  ///< Model name in thesis Table 4.1.
  int thesis_faces;          ///< Face count in Table 4.1.
  double thesis_seconds;     ///< "Init-param." time in Table 4.1 (s).
  const char* file;          ///< Stand-in mesh in ../shared/meshes.
};

constexpr ThesisRow kRows[] = {
    {"venus", 1396, 0.625, "venus.off"},
    {"triceratops", 5660, 3.234, "triceratops.off"},
    {"horse", 7500, 4.906, "dino.off"},
};

void run(benchmark::State& state, const ThesisRow& row, ChartMode mode, int speculative) {
  const std::optional<TriMesh> loaded = bench::shared_mesh_or_skip(state, row.file);
  if (!loaded) return;
  const TriMesh& mesh = *loaded;
  UnwrapOptions options;
  options.charts = mode;
  options.speculative_attempts = speculative;
  UnwrapResult r;
  for (auto _ : state) {
    r = unwrap(mesh, options);
    benchmark::DoNotOptimize(r.param.uv.data());
  }
  state.counters["faces"] = mesh.num_faces();
  state.counters["thesis_s"] = row.thesis_seconds;
  state.counters["target_ms"] = row.thesis_seconds * 1000.0 / 100.0;
  state.counters["L2"] = r.report.final_l2;
  state.counters["augm"] = r.report.augmentations;
  state.counters["charts"] = r.report.num_charts;
  state.counters["share"] = r.report.effective_texel_share;
}

}  // namespace

int main(int argc, char** argv) {
  for (const ChartMode mode : {ChartMode::Auto, ChartMode::Single})
    for (const ThesisRow& row : kRows)
      bench::register_ms(std::string("Unwrap/") + (mode == ChartMode::Auto ? "auto/" : "single/") +
                             row.thesis_model + "/" + row.file,
                         [&row, mode](benchmark::State& s) { run(s, row, mode, 1); });
  // auto with UnwrapOptions::speculative_attempts = 2 (the next chart count built while one is
  // decided; the same layout).
  for (const ThesisRow& row : kRows)
    bench::register_ms(std::string("Unwrap/auto-spec2/") + row.thesis_model + "/" + row.file,
                       [&row](benchmark::State& s) { run(s, row, ChartMode::Auto, 2); });
  return bench::run_benchmarks(argc, argv);
}
