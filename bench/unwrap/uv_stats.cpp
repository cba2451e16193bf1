// Layout figures of an OBJ with texture coordinates, measured as unwrap() measures its own
// (docs/bench_unwrap.md, "Scans"): for the side-by-side with xatlas on the same scans.
//
//   bench_uv_stats [--mirror-ok] LAYOUT.obj [REFERENCE_MESH]
//
// --mirror-ok: for layouts that lay some charts out mirrored (xatlas: a light map does not care):
// a UV triangle of negative area counts with its absolute area (its corners and the face's are
// swapped), and UV triangles of zero area are left out of the L2 (their number is still printed
// with the flipped ones).
//
// Prints one Markdown row: faces, components, genus, boundary loops, charts (UV components), L2
// stretch, coverage, effective texel share = coverage / L2², flipped + degenerate UV triangles,
// overlapping UV triangle pairs (up to 1000), UVs outside [0,1]². REFERENCE_MESH (optional): the
// mesh the layout was made from; its face count is printed beside, to show that no face was lost.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <utility>

#include "adaptex/core/topology.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/param/stretch.h"

int main(int argc, char** argv) {
  using namespace adaptex;
  const bool mirror_ok = argc > 1 && std::string(argv[1]) == "--mirror-ok";
  if (mirror_ok) --argc, ++argv;
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s [--mirror-ok] LAYOUT.obj [REFERENCE_MESH]\n", argv[0]);
    return 2;
  }
  try {
    ReadOptions ro;
    ro.repair = true;
    TexturedMesh t = read_textured_obj(argv[1], ro);
    const MeshTopology topo = analyze_topology(t.mesh);
    StretchStats s = measure_stretch(t.mesh, t.param);
    if (mirror_ok) {
      const long bad = s.flipped + s.degenerate;
      TexturedMesh kept = t;
      kept.mesh.faces.clear();
      kept.param.uv_faces.clear();
      kept.param.face_chart.clear();
      for (int f = 0; f < t.mesh.num_faces(); ++f) {
        const double a = uv_signed_area(t.param, f);
        if (a == 0.0 || !std::isfinite(a)) continue;
        Face m = t.mesh.faces[f];
        auto u = t.param.uv_faces[f];
        if (a < 0) std::swap(m[1], m[2]), std::swap(u[1], u[2]);
        kept.mesh.faces.push_back(m);
        kept.param.uv_faces.push_back(u);
        kept.param.face_chart.push_back(t.param.face_chart[f]);
      }
      t = std::move(kept);
      s = measure_stretch(t.mesh, t.param);
      s.flipped = static_cast<int>(bad);
      s.degenerate = 0;
    }
    double coverage = 0;
    for (int f = 0; f < t.mesh.num_faces(); ++f) coverage += std::max(0.0, uv_signed_area(t.param, f));
    coverage = std::min(1.0, coverage);
    const double share = s.l2 > 0 && std::isfinite(s.l2) ? coverage / (s.l2 * s.l2) : 0.0;
    long outside = 0;
    for (const Vec2& uv : t.param.uv) outside += !(uv.x() >= 0 && uv.x() <= 1 && uv.y() >= 0 && uv.y() <= 1);
    const long overlaps = count_overlapping_triangles(t.param, 1000);
    int reference_faces = -1;
    if (argc > 2) reference_faces = read_mesh(argv[2], ro).num_faces();
    std::printf("| %s | %d | %d | %d | %d | %d | %.3f | %.3f | %.3f | %d | %ld | %ld | %d |\n", argv[1],
                t.mesh.num_faces(), topo.num_components, topo.total_genus(), topo.total_loops(),
                t.param.num_charts, s.l2, coverage, share, s.flipped + s.degenerate, overlaps, outside,
                reference_faces);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", argv[1], e.what());
    return 2;
  }
  return 0;
}
