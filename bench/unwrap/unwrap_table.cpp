// Acceptance table of the initial parameterization pipeline (unwrap(): §3.2 surgery, §2.2 Floater,
// §3.3 Yoshizawa, cut augmentation, packing): per shared mesh and for generated meshes of about
// 10k, 100k and 1M faces, printed as Markdown (docs/bench_unwrap.md).
//
//   bench_unwrap_table [--shared] [--generated] [--min-faces N] [--max-faces N] [MESH...]
//
// Without arguments both tables are printed. MESH arguments replace the shared-mesh list.
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "adaptex/core/shapes.h"
#include "adaptex/core/topology.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/param/stretch.h"
#include "adaptex/param/unwrap.h"

namespace {

using namespace adaptex;

/// User + system CPU seconds of this process (on a loaded machine this is closer to the
/// unloaded wall time than the wall clock is).
double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

void header() {
  std::printf(
      "| mesh | faces | genus | loops | charts | cut length (%% of bbox diag) | augm. | Floater L2 | "
      "final L2 | Floater L∞ | final L∞ | Yosh. it. | cut s | Floater s | Yoshizawa s | augment s "
      "| pack s | total s | total CPU s | flipped | overlaps |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
}

void row(const std::string& name, const TriMesh& mesh) {
  const double cpu0 = cpu_seconds();
  const UnwrapResult r = unwrap(mesh);
  const double cpu = cpu_seconds() - cpu0;
  const UnwrapReport& p = r.report;
  const StretchStats s = measure_stretch(mesh, r.param);
  const long overlaps = count_overlapping_triangles(r.param, 1000);
  const double diag = bounding_box(mesh).diagonal();
  std::printf(
      "| %s | %d | %d | %d | %d | %.3g (%.0f%%) | %d | %.4f | %.4f | %.3f | %.3f | %d | %.3f | %.3f | "
      "%.3f | %.3f | %.3f | %.3f | %.3f | %d | %ld |\n",
      name.c_str(), mesh.num_faces(), p.genus, p.boundary_loops, p.num_charts, p.cut_length,
      diag > 0 ? 100.0 * p.cut_length / diag : 0.0, p.augmentations, p.floater_l2, p.final_l2,
      p.floater_linf, p.final_linf, p.yoshizawa_iterations, p.time_cut, p.time_floater,
      p.time_yoshizawa, p.time_augment, p.time_pack, p.time_total, cpu, s.flipped, overlaps);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  bool shared = false, generated = false;
  long min_faces = 0, max_faces = 2000000;
  std::vector<std::filesystem::path> files;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--shared")) shared = true;
    else if (!std::strcmp(argv[i], "--generated")) generated = true;
    else if (!std::strcmp(argv[i], "--max-faces") && i + 1 < argc) max_faces = std::atol(argv[++i]);
    else if (!std::strcmp(argv[i], "--min-faces") && i + 1 < argc) min_faces = std::atol(argv[++i]);
    else files.emplace_back(argv[i]);
  }
  if (!shared && !generated && files.empty()) shared = generated = true;
  if (shared && files.empty()) {
    const std::filesystem::path dir = std::filesystem::path(ADAPTEX_SHARED_DIR) / "meshes";
    if (std::filesystem::is_directory(dir))
      for (const auto& e : std::filesystem::directory_iterator(dir)) {
        const std::string ext = e.path().extension().string();
        if (ext == ".obj" || ext == ".off" || ext == ".ply" || ext == ".stl") files.push_back(e.path());
      }
    std::sort(files.begin(), files.end());
    if (files.empty()) std::fprintf(stderr, "no shared meshes in %s\n", dir.c_str());
  }
  try {
    if (!files.empty()) {
      std::printf("### Shared meshes\n\n");
      header();
      for (const auto& f : files) {
        const TriMesh mesh = read_mesh(f);
        if (mesh.num_faces() >= min_faces && mesh.num_faces() <= max_faces)
          row(f.filename().string(), mesh);
      }
      std::printf("\n");
    }
    if (generated) {
      std::printf("### Generated meshes\n\n");
      header();
      struct Gen {
        const char* name;
        TriMesh (*make)();
      };
      const Gen gens[] = {
          {"icosphere(5)", [] { return shapes::icosphere(5); }},
          {"torus(200,25)", [] { return shapes::torus(200, 25); }},
          {"icosphere(7)", [] { return shapes::icosphere(7); }},
          {"torus(640,80)", [] { return shapes::torus(640, 80); }},
          {"torus(2000,250)", [] { return shapes::torus(2000, 250); }},
          {"icosphere(8)", [] { return shapes::icosphere(8); }},
      };
      for (const Gen& g : gens) {
        const TriMesh mesh = g.make();
        if (mesh.num_faces() >= min_faces && mesh.num_faces() <= max_faces) row(g.name, mesh);
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
