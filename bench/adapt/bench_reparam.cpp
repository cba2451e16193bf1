// The whole end-mode re-parameterization (issue 12: "must not get slower than today's"): a PaintSession
// in end mode paints a generated `lines` set (seed 1) at 256², then reparameterize() runs once, timed:
// error model / relaxation, warp, refinement, remap, texel map, replay and safeguard (the report's
// time_ms.total). density-flow (the default) next to the thesis' two-stage on the same session.
//
// Meshes: the shared venus, spot, dino, kitten and bunny (skipped when ../shared is absent) and two built
// in code (a torus and a genus-3 surface), so the comparison does not depend on the shared files.
//
//   adaptex_bench_reparam --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//
// Time is the process CPU time (all threads) of reparameterize(); painting is not timed. The counters
// are the report's phases (wall ms per iteration): model (error model, or importance + relaxation),
// flow, refine, remap, texture (texel map + replay), safeguard, total.
//
// BM_ErrorDensity times density-flow's error model alone (compute_error_density from the history, as
// end mode calls it: 2N reference raster, levels, equidistribution) in process CPU time, the phase
// the wall-time counter "model" shows above for density-flow.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "adaptex/adapt/session.h"
#include "adaptex/core/shapes.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/paint/generate.h"
#include "adaptex/paint/painter.h"
#include "adaptex/param/unwrap.h"

namespace {
using namespace adaptex;
namespace fs = std::filesystem;

struct Scene {
  TriMesh mesh;
  Parameterization param;
  StrokeFile strokes;
};

const std::vector<std::string>& scene_names() {
  static const std::vector<std::string> names{"venus", "spot", "dino", "kitten", "bunny", "torus", "genus3"};
  return names;
}

/// The scene \p name (unwrapped with the default options, `lines` strokes of seed 1), or null when its
/// shared mesh is absent. Built once per process.
const Scene* scene(const std::string& name) {
  static std::map<std::string, std::unique_ptr<Scene>> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return it->second.get();
  std::unique_ptr<Scene> s;
  TriMesh mesh;
  bool found = true;
  if (name == "torus") {
    mesh = shapes::torus(96, 40);
  } else if (name == "genus3") {
    mesh = shapes::genus_surface(3, 8);
  } else {
    found = false;
    const fs::path dir = fs::path(ADAPTEX_SHARED_DIR) / "meshes";
    if (fs::is_directory(dir))
      for (const auto& e : fs::directory_iterator(dir))
        if (e.path().stem() == name) mesh = read_mesh(e.path()), found = true;
  }
  if (found) {
    s = std::make_unique<Scene>();
    s->mesh = std::move(mesh);
    s->param = unwrap(s->mesh).param;
    GenerateOptions go;
    go.kind = StrokeKind::Lines;
    go.seed = 1;
    s->strokes = generate_strokes(s->mesh, go);
  }
  return (cache[name] = std::move(s)).get();
}

void BM_EndModeReparam(benchmark::State& state) {
  const std::string& name = scene_names()[static_cast<size_t>(state.range(0))];
  const AdaptMode mode = state.range(1) ? AdaptMode::DensityFlow : AdaptMode::TwoStage;
  const Scene* s = scene(name);
  if (!s) {
    state.SkipWithError(("shared mesh '" + name + "' is absent").c_str());
    return;
  }
  state.SetLabel(name + " " + to_string(mode));
  PaintSessionOptions o;
  o.texture_size = 256;
  o.schedule = ReparamSchedule::End;
  o.adapt.mode = mode;
  // Phases of the report (wall ms, summed here, averaged over iterations by the counters).
  std::map<std::string, double> phase;
  for (auto _ : state) {
    state.PauseTiming();
    auto session = std::make_unique<PaintSession>(s->mesh, s->param, o, s->strokes.background);
    for (const Stroke& st : s->strokes.strokes) session->add_stroke(st);
    state.ResumeTiming();
    const AdaptReport& r = session->reparameterize();
    state.PauseTiming();
    const double relax = r.time_importance + r.time_stretch_map + r.time_ls2 + r.time_coarse + r.time_fine;
    phase["model"] += 1e3 * (r.time_density + relax);  // error model, or importance + relaxation
    phase["flow"] += 1e3 * r.time_flow;
    phase["polish"] += 1e3 * r.time_polish;
    phase["refine"] += 1e3 * r.time_refine;
    phase["remap"] += 1e3 * r.time_remap;
    phase["texture"] += 1e3 * (r.time_texel_map + r.time_texture_update);
    phase["safeguard"] += 1e3 * r.time_safeguard;
    phase["total"] += 1e3 * r.time_total;
    session.reset();
    state.ResumeTiming();
  }
  for (const auto& [k, v] : phase) state.counters[k] = benchmark::Counter(v, benchmark::Counter::kAvgIterations);
}

void BM_ErrorDensity(benchmark::State& state) {
  const std::string& name = scene_names()[static_cast<size_t>(state.range(0))];
  const Scene* s = scene(name);
  if (!s) {
    state.SkipWithError(("shared mesh '" + name + "' is absent").c_str());
    return;
  }
  state.SetLabel(name);
  Painter painter(s->mesh, s->param, PainterOptions{256, 256, PaintSessionOptions{}.padding}, s->strokes.background);
  painter.paint_all(s->strokes);
  const ErrorDensityOptions o = AdaptOptions{}.density_flow.density;
  double gain = 0;
  for (auto _ : state) {
    const ErrorDensity d = compute_error_density(s->mesh, s->param, painter.texture(), painter.texel_map(), s->strokes, o);
    gain = d.predicted_gain_db;  // read after the loop (DoNotOptimize on a double returned garbage here)
  }
  state.counters["gain_db"] = benchmark::Counter(gain);  // the model's predicted gain (equal before and after a speed-up)
}

void mesh_args(benchmark::internal::Benchmark* b) {
  for (int m = 0; m < static_cast<int>(scene_names().size()); ++m) b->Args({m});
}

void scene_args(benchmark::internal::Benchmark* b) {
  for (int m = 0; m < static_cast<int>(scene_names().size()); ++m)
    for (int mode = 0; mode < 2; ++mode) b->Args({m, mode});
}
}  // namespace

BENCHMARK(BM_EndModeReparam)->Apply(scene_args)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(3);
BENCHMARK(BM_ErrorDensity)->Apply(mesh_args)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(5);
BENCHMARK_MAIN();
