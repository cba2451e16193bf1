// Writes a synthetic range scan (shapes::synthetic_scan: noisy height-field patches in many
// components, one-face holes, zero-area faces from collapsed edges, duplicate points) as an OFF file,
// for the issue 8 large-input check of `adaptex unwrap --repair` (docs/benchmarks.md):
//
//   build/bench/unwrap/bench_make_scan /tmp/scan.off [FACES=900000] [COMPONENTS=151] [ZERO_AREA=274]
//   /usr/bin/time -v build/apps/cli/adaptex unwrap /tmp/scan.off --repair -o /tmp/scan_uv.obj
//
// No mesh file is committed; the generator is deterministic.
#include <cstdio>
#include <cstdlib>

#include "adaptex/core/shapes.h"
#include "adaptex/core/topology.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s OUT.off [faces] [components] [zero_area_faces]\n", argv[0]);
    return 2;
  }
  const int faces = argc > 2 ? std::atoi(argv[2]) : 900000;
  const int comps = argc > 3 ? std::atoi(argv[3]) : 151;
  const int zero = argc > 4 ? std::atoi(argv[4]) : 274;
  try {
    const adaptex::TriMesh m = adaptex::shapes::synthetic_scan(faces, comps, zero);
    std::FILE* f = std::fopen(argv[1], "w");
    if (!f) {
      std::fprintf(stderr, "%s: cannot write\n", argv[1]);
      return 2;
    }
    std::fprintf(f, "OFF\n%d %d 0\n", m.num_vertices(), m.num_faces());
    for (const auto& p : m.positions) std::fprintf(f, "%.17g %.17g %.17g\n", p.x(), p.y(), p.z());
    for (const auto& t : m.faces) std::fprintf(f, "3 %d %d %d\n", t[0], t[1], t[2]);
    if (std::fclose(f) != 0) {
      std::fprintf(stderr, "%s: write failed\n", argv[1]);
      return 2;
    }
    const adaptex::MeshTopology topo = adaptex::analyze_topology(m);
    int zero_faces = 0;
    for (int i = 0; i < m.num_faces(); ++i) zero_faces += adaptex::face_area(m, i) == 0.0;
    std::printf("%s: %d vertices, %d faces, %d components, %d boundary loops, %d zero-area faces\n",
                argv[1], m.num_vertices(), m.num_faces(), topo.num_components, topo.total_loops(),
                zero_faces);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
