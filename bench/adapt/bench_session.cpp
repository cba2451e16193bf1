// A real painting session as a benchmark (issue 10, deliverable 4; docs/bench_adapt.md): a generated
// `mixed` history of 1,000 strokes (paint/generate.h) painted in each-stroke mode (the studio's
// schedule) with the library's default re-parameterization (AdaptOptions{}.mode, density-flow), and the
// time of the re-parameterization cycle at strokes 10, 100 and 1,000 by phase: the AdaptReport's
// time_* fields (density, flow, refine, remap, texel map, texture update = replay of the history,
// safeguard = exact-signal evaluation + reconstruction errors) and the session's own clock.
//
// The history is `mixed`, generated in batches of 40 strokes (5 blobs, then 35 lines in one region)
// with seeds 1, 2, ... (bench/common/session_history.h; --seed S starts at S).
//
// Running 1,000 each-stroke cycles takes hours on 2 cores, so the cycle at stroke k is measured as
// follows: a PaintSession in each-stroke mode with adaptation *off* (AdaptMode::None: it only paints)
// receives the first k - 1 strokes; then stroke k is painted (timed: "paint stroke", which includes
// the session's per-stroke bookkeeping) and reparameterize() runs one cycle with adaptation on. That
// is the work each-stroke mode does for stroke k (same initial layout, same history, same painter), minus
// the return to the initial layout after a rejection (see --full), which replays the history too.
//
//   adaptex_bench_session [--meshes spot,plane] [--strokes 10,100,1000] [--size 512] [--reps 1]
//                         [--full N] [--cache Q] [--cache-coverage C] [--min-gain G] [--psnr-every K] [--seed S]
//                         [--polish-cells K]
//
// --meshes: names/stems of ADAPTEX_SHARED_DIR/meshes or paths, and "plane" (a generated 100k-face height
// field, one chart, uv = xy, as in cycle.cpp); a shared mesh that is absent is skipped with a message.
// --cache Q: PaintSessionOptions::surface_cache = Q (the replay reads a surface signal cache of Q
// samples per texel spacing once the strokes cover the surface --cache-coverage C times; 0: exact
// replay of every dab; default: the library's, 3 from 4 covers). Only the --full sessions use it: the
// stroke-k rows paint without adaptation (no initial layout kept), so they replay exactly.
// --full N: also paint the first N strokes with a true each-stroke session and print every cycle
// ("skip" in the accepted column: the cycle stopped after the error model, PaintSessionOptions::min_gain_db;
// the number after it: the model's predicted gain over the held layout in dB, AdaptReport::gain_over_held_db).
// --min-gain G: that session's min_gain_db (default: the library's). --psnr-every K: after every K-th
// stroke of that session, the PSNR of its texture against the exact history (400,000 samples).
// --polish-cells K: that session's adapt.density_flow.polish.cells (ErrorPolishOptions::cells).
// Prints one markdown row per (mesh, stroke index, repetition), times in ms (wall clock; the last
// column: CPU time of the process, all threads, for stroke + cycle).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <string>
#include <vector>

#include "adaptex/core/allocator.h"
#include "adaptex/adapt/session.h"
#include "adaptex/core/shapes.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/paint/eval.h"
#include "adaptex/paint/generate.h"
#include "adaptex/param/unwrap.h"
#include "../common/height_field.h"
#include "../common/session_history.h"

using namespace adaptex;
namespace fs = std::filesystem;

namespace {

struct Args {
  std::vector<std::string> meshes{"spot", "plane"};
  std::vector<int> strokes{10, 100, 1000};
  int size = 512;
  int reps = 1;
  int full = 0;
  int seed = 1;  ///< Seed of the history's first batch (the next batches: seed + 1, ...)
  double cache = PaintSessionOptions{}.surface_cache;  ///< PaintSessionOptions::surface_cache (0: exact replay)
  double cache_coverage = PaintSessionOptions{}.surface_cache_coverage;  ///< ...::surface_cache_coverage
  double min_gain = PaintSessionOptions{}.min_gain_db;  ///< --full's PaintSessionOptions::min_gain_db
  int psnr_every = 0;  ///< --full: PSNR after every this many strokes (0: none)
  int polish_cells = ErrorPolishOptions{}.cells;       ///< --full's adapt.polish.cells
};

// Comma-separated items of \p s, each passed to \p add.
template <class F>
void for_each_item(const std::string& s, F add) {
  size_t from = 0;
  while (from <= s.size()) {
    const size_t to = std::min(s.find(',', from), s.size());
    if (to > from) add(s.substr(from, to - from));
    from = to + 1;
  }
}

// A whole number or a number of \p v, or std::invalid_argument naming \p k ("--size: not a number: x").
int whole(const std::string& k, const std::string& v) {
  size_t used = 0;
  try {
    const int x = std::stoi(v, &used);
    if (used == v.size()) return x;
  } catch (const std::logic_error&) {
  }
  throw std::invalid_argument(k + ": not a whole number: " + v);
}
double number(const std::string& k, const std::string& v) {
  size_t used = 0;
  try {
    const double x = std::stod(v, &used);
    if (used == v.size()) return x;
  } catch (const std::logic_error&) {
  }
  throw std::invalid_argument(k + ": not a number: " + v);
}

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string k = argv[i];
    if (i + 1 >= argc) throw std::invalid_argument("missing value after " + k);
    const std::string v = argv[++i];
    if (k == "--meshes") {
      a.meshes.clear();
      for_each_item(v, [&](const std::string& x) { a.meshes.push_back(x); });
    } else if (k == "--strokes") {
      a.strokes.clear();
      for_each_item(v, [&](const std::string& x) { a.strokes.push_back(whole(k, x)); });
    } else if (k == "--size") {
      a.size = whole(k, v);
    } else if (k == "--reps") {
      a.reps = whole(k, v);
    } else if (k == "--cache") {
      a.cache = number(k, v);
    } else if (k == "--cache-coverage") {
      a.cache_coverage = number(k, v);
    } else if (k == "--min-gain") {
      a.min_gain = number(k, v);
    } else if (k == "--seed") {
      a.seed = whole(k, v);
    } else if (k == "--psnr-every") {
      a.psnr_every = whole(k, v);
    } else if (k == "--polish-cells") {
      a.polish_cells = whole(k, v);
    } else if (k == "--full") {
      a.full = whole(k, v);
    } else {
      throw std::invalid_argument("unknown option " + k);
    }
  }
  if (a.polish_cells < 0) throw std::invalid_argument("--polish-cells must be >= 0");
  return a;
}

struct Scene {
  std::string name;
  TriMesh mesh;
  Parameterization param;
};

// The 224 x 224 height field (100,352 faces; bench/common/height_field.h).
Scene plane_scene() {
  Scene s;
  s.name = "plane100k";
  bench::height_field(224, s.mesh, s.param);
  return s;
}

// A shared mesh by stem or path, unwrapped with the default options; false when absent.
bool shared_scene(const std::string& name, Scene& s) {
  fs::path path = name;
  if (!fs::exists(path)) {
    const fs::path dir = fs::path(ADAPTEX_SHARED_DIR) / "meshes";
    path.clear();
    if (fs::is_directory(dir))
      for (const auto& e : fs::directory_iterator(dir))
        if (e.path().stem() == name || e.path().filename() == name) path = e.path();
  }
  if (path.empty()) return false;
  s.name = path.stem().string();
  s.mesh = read_mesh(path);
  s.param = unwrap(s.mesh).param;
  return true;
}

double ms(double seconds) { return 1000.0 * seconds; }

// CPU time of this process, all threads (s): less sensitive than the wall clock to other processes
// on a shared machine.
double process_cpu() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

void print_header() {
  std::printf("| mesh | faces | stroke | dabs so far | accepted | paint stroke | density | flow + polish | refine | remap |"
              " texel map | replay | safeguard | other | **stroke + cycle** | CPU |\n");
  std::printf("|---|---:|---:|---:|:-:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
}

// \p paint: painting stroke k and recording it (the session's signal cache included); \p wall: that and
// the cycle; \p cpu: the process CPU time of both (all threads).
void print_row(const Scene& s, int k, long long dabs, const AdaptReport& r, double paint, double wall, double cpu) {
  const double known = paint + r.time_density + r.time_flow + r.time_polish + r.time_refine + r.time_remap +
                       r.time_texel_map + r.time_texture_update + r.time_safeguard;
  char acc[64];
  std::snprintf(acc, sizeof acc, "%s %+.2f", r.skipped ? "skip" : r.accepted ? "yes" : "no", r.gain_over_held_db);
  std::printf("| %s | %d | %d | %lld | %s | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | **%.0f** | %.0f |\n",
              s.name.c_str(), s.mesh.num_faces(), k, dabs, acc, ms(paint), ms(r.time_density),
              ms(r.time_flow + r.time_polish), ms(r.time_refine), ms(r.time_remap), ms(r.time_texel_map),
              ms(r.time_texture_update), ms(r.time_safeguard), ms(std::max(0.0, wall - known)), ms(wall), ms(cpu));
  std::fflush(stdout);
}

using bench::session_history;  // the history (bench/common/session_history.h)

long long dab_count(const StrokeFile& f, int k) {
  long long n = 0;
  for (int i = 0; i < k; ++i) n += static_cast<long long>(f.strokes[i].dabs.size());
  return n;
}

// The cycle after stroke k: paint k strokes without adaptation, then one re-parameterization.
void cycle_at(const Scene& s, const StrokeFile& history, int k, int size, double cache) {
  PaintSessionOptions o;
  o.surface_cache = cache;
  o.texture_size = size;
  o.schedule = ReparamSchedule::EachStroke;
  o.adapt.mode = AdaptMode::None;  // paint only; reparameterize() uses the default method (session.h)
  PaintSession session(s.mesh, s.param, o, history.background);
  for (int i = 0; i + 1 < k; ++i) session.add_stroke(history.strokes[i]);
  const double c0 = process_cpu();
  const auto t0 = std::chrono::steady_clock::now();
  session.add_stroke(history.strokes[k - 1]);
  const double paint = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const AdaptReport& r = session.reparameterize();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  print_row(s, k, dab_count(history, k), r, paint, wall, process_cpu() - c0);
}

// A true each-stroke session over the first n strokes: every cycle.
void full_session(const Scene& s, const StrokeFile& history, const Args& a) {
  const int n = a.full, psnr_every = a.psnr_every;
  const double min_gain = a.min_gain;
  PaintSessionOptions o;
  o.surface_cache = a.cache;
  o.surface_cache_coverage = a.cache_coverage;
  o.min_gain_db = min_gain;
  o.adapt.density_flow.polish.cells = a.polish_cells;
  o.texture_size = a.size;
  o.schedule = ReparamSchedule::EachStroke;  // adapt.mode: the library default
  PaintSession session(s.mesh, s.param, o, history.background);
  for (int i = 0; i < n; ++i) {
    const double c0 = process_cpu();
    const auto t0 = std::chrono::steady_clock::now();
    session.add_stroke(history.strokes[i]);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const AdaptReport& r = session.reports().back();
    print_row(s, i + 1, dab_count(history, i + 1), r, std::max(0.0, wall - r.time_total), wall, process_cpu() - c0);
    if (psnr_every > 0 && (i + 1) % psnr_every == 0) {
      EvalOptions eo;
      eo.samples = 400000;
      const double psnr = evaluate_texture(session.mesh(), session.param(), session.texture(), session.history(), eo).psnr;
      std::printf("\n%s after stroke %d, min_gain %g dB: PSNR %.3f dB\n\n", s.name.c_str(), i + 1, min_gain, psnr);
    }
  }
  std::printf("\n%s: surface cache %lld samples\n\n", s.name.c_str(), session.surface_cache_samples());
}

}  // namespace

int main(int argc, char** argv) {
  // As the adaptex programs run (core/allocator.h); ADAPTEX_DEFAULT_MALLOC=1 measures glibc's defaults.
  adaptex::keep_freed_memory_in_process_unless_disabled();
  try {
    const Args a = parse(argc, argv);
    const int max_k = std::max(a.full, *std::max_element(a.strokes.begin(), a.strokes.end()));
    std::printf(
        "texture %d², default adapt mode %s, each-stroke, replay, safeguard on, surface cache %g from %g covers\n\n",
        a.size, to_string(AdaptOptions{}.mode), a.cache, a.cache_coverage);
    print_header();
    for (const auto& name : a.meshes) {
      Scene s;
      if (name == "plane") {
        s = plane_scene();
      } else if (!shared_scene(name, s)) {
        std::printf("(skipped %s: not found in %s/meshes)\n", name.c_str(), ADAPTEX_SHARED_DIR);
        continue;
      }
      const StrokeFile history = session_history(s.mesh, max_k, a.seed);
      for (int k : a.strokes)
        for (int r = 0; r < a.reps; ++r) cycle_at(s, history, k, a.size, a.cache);
      if (a.full > 0) full_session(s, history, a);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "adaptex_bench_session: %s\n", e.what());
    return 2;
  }
  return 0;
}
