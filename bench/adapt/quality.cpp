// Quality study of the signal-adaptive re-parameterization (docs/quality.md): for every mesh x stroke
// kind x texture size N, the PSNR (adaptex eval metric) of a fixed parameterization ("none") at N and
// 2N against the adapted one (default two-stage, end mode, replay) at N. One table row per case.
//
//   adaptex_adapt_quality [--meshes a.obj,b.off] [--kinds lines,blobs,mixed] [--sizes 128,256,512]
//                         [--mode two-stage|single] [--alpha A] [--beta B] [--grid 16,256]
//                         [--pool mean|min|none] [--ring 4|8] [--no-safeguard] [--norm edge|pct]
//                         [--schedule end|each-stroke] [--update replay|resample] [--count N]
// GCC 12 reports a false -Wrestrict inside std::string copies at -O3 (GCC bug 105329).
#pragma GCC diagnostic ignored "-Wrestrict"
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "adaptex/adapt/session.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/paint/eval.h"
#include "adaptex/paint/generate.h"
#include "adaptex/param/stretch.h"
#include "adaptex/param/unwrap.h"

using namespace adaptex;

namespace {
std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string x;
  while (std::getline(ss, x, ',')) out.push_back(x);
  return out;
}
}  // namespace

int main(int argc, char** argv) {
  std::map<std::string, std::string> a;
  for (int i = 1; i < argc; ++i) {
    std::string k = argv[i];
    if (k == "--no-safeguard" || k == "--verbose" || k == "--no-geometry" || k == "--slide") a[k] = "1";
    else if (i + 1 < argc) a[k] = argv[++i];
  }
  auto get = [&](const std::string& k, const std::string& d) { return a.count(k) ? a[k] : d; };
  std::vector<std::string> meshes;
  if (a.count("--meshes")) meshes = split(a["--meshes"]);
  else
    for (auto& e : std::filesystem::directory_iterator(std::string(ADAPTEX_SHARED_DIR) + "/meshes"))
      if (e.path().extension() != ".md") meshes.push_back(e.path().string());
  std::sort(meshes.begin(), meshes.end());
  const auto kinds = split(get("--kinds", "lines,blobs,mixed"));
  std::vector<int> sizes;
  for (auto& s : split(get("--sizes", "128,256,512"))) sizes.push_back(std::stoi(s));
  PaintSessionOptions so;
  so.adapt.mode = parse_adapt_mode(get("--mode", "two-stage"));
  if (a.count("--alpha")) so.adapt.alpha = std::stod(a["--alpha"]);
  if (a.count("--beta")) so.adapt.beta = std::stod(a["--beta"]);
  if (a.count("--grid")) {
    auto g = split(a["--grid"]);
    so.adapt.coarse_grid = std::stoi(g[0]);
    so.adapt.fine_grid = std::stoi(g.back());
  }
  const std::string pool = get("--pool", "mean");
  so.adapt.pool = pool == "min" ? PoolMode::Min : pool == "none" ? PoolMode::None : PoolMode::Mean;
  so.adapt.ring = get("--ring", "8") == "4" ? GridRing::Four : GridRing::Eight;
  if (get("--norm", "edge") == "pct") so.adapt.importance.normalization = ImportanceNormalization::Percentile;
  if (a.count("--eps")) so.adapt.epsilon_texels = std::stod(a["--eps"]);
  if (a.count("--iters")) so.adapt.max_iterations = std::stoi(a["--iters"]);
  if (a.count("--slide")) so.adapt.slide_boundary = true;
  if (a.count("--fine-iters")) so.adapt.fine_max_iterations = std::stoi(a["--fine-iters"]);
  if (a.count("--min-weight")) so.adapt.min_weight = std::stod(a["--min-weight"]);
  so.safeguard = !a.count("--no-safeguard");
  so.schedule = parse_reparam_schedule(get("--schedule", "end"));
  so.update = parse_texture_update(get("--update", "replay"));
  const int count = std::stoi(get("--count", "-1"));
  if (a.count("--debug")) so.debug_dir = a["--debug"];
  if (a.count("--gscale")) so.adapt.geometry_scale = std::stod(a["--gscale"]);
  if (a.count("--no-geometry")) so.adapt.use_geometry_stretch = false;
  EvalOptions eo;
  eo.samples = std::stoll(get("--samples", "400000"));

  std::printf("| mesh | faces | strokes | N | none N | none 2N | %s N | gain dB | to 2N | damping | accepted | t_reparam ms |\n",
              to_string(so.adapt.mode));
  std::printf("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  std::fflush(stdout);
  for (const auto& path : meshes) {
    TriMesh mesh;
    Parameterization param;
    try {
      mesh = read_mesh(path);
      param = unwrap(mesh).param;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", path.c_str(), e.what());
      continue;
    }
    const std::string name = std::filesystem::path(path).stem().string();
    for (const auto& kind : kinds) {
      GenerateOptions go;
      go.kind = parse_stroke_kind(kind);
      go.count = count;
      const StrokeFile strokes = generate_strokes(mesh, go);
      for (int N : sizes) {
        auto psnr_none = [&](int size) {
          PainterOptions po;
          po.width = po.height = size;
          Painter p(mesh, param, po, strokes.background);
          p.paint_all(strokes);
          return evaluate_texture(mesh, param, p.texture(), strokes, eo).psnr;
        };
        const double none = psnr_none(N), none2 = psnr_none(2 * N);
        PaintSessionOptions o = so;
        o.texture_size = N;
        PaintSession s(mesh, param, o, strokes.background);
        const auto t0 = std::chrono::steady_clock::now();
        for (const auto& st : strokes.strokes) s.add_stroke(st);
        s.finish();
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const double ad = evaluate_texture(mesh, s.param(), s.texture(), strokes, eo).psnr;
        const auto st = measure_stretch(mesh, s.param());
        double damping = 0, reparam_ms = 0;
        int accepted = 0;
        for (const auto& r : s.reports()) {
          damping += r.damping;
          accepted += r.accepted;
          reparam_ms += 1e3 * r.time_total;
        }
        const int nr = static_cast<int>(s.reports().size());
        std::printf("| %s | %d | %s | %d | %.2f | %.2f | %.2f | %+.2f | %.0f%% | %.2f | %d/%d | %.0f |%s\n", name.c_str(),
                    mesh.num_faces(), kind.c_str(), N, none, none2, ad, ad - none,
                    none2 > none ? 100.0 * (ad - none) / (none2 - none) : 0.0, nr ? damping / nr : 0.0, accepted, nr,
                    nr ? reparam_ms / nr : 0.0, (st.flipped || st.degenerate) ? " FLIPS" : "");
        std::fflush(stdout);
        (void)secs;
        if (a.count("--verbose"))
          for (const auto& r : s.reports()) std::fprintf(stderr, "%s\n", nlohmann::json(r).dump().c_str());
      }
    }
  }
  return 0;
}
