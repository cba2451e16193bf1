// Repacks the charts of an existing layout (e.g. xatlas's or ours on the scans of
// docs/bench_unwrap.md) with pack_shapes() and with pack_rectangles() (their bounding boxes), each
// chart rescaled to its own 3-D area (one texel density for all, as xatlas packs), and prints the
// coverage and CPU time of both: how much of the square each packer fills with the same charts.
//
//   bench_repack LAYOUT.obj [PADDING] [OUT.obj [OUT.png]]
//
// PADDING: gap as a fraction of the square (default 0). OUT.obj: the shape packing, for
// bench_uv_stats (flips, overlaps, bounds).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "adaptex/io/image_io.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/param/layout_image.h"
#include "adaptex/param/pack.h"

int main(int argc, char** argv) {
  using namespace adaptex;
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s LAYOUT.obj [PADDING] [OUT.obj]\n", argv[0]);
    return 2;
  }
  try {
    ReadOptions ro;
    ro.repair = true;
    TexturedMesh t = read_textured_obj(argv[1], ro);
    const double padding = argc > 2 ? std::stod(argv[2]) : 0.0;
    Parameterization& p = t.param;
    const int nc = p.num_charts;
    std::vector<double> a2(nc, 0.0), a3(nc, 0.0);
    for (int f = 0; f < t.mesh.num_faces(); ++f) {
      a2[p.face_chart[f]] += std::abs(uv_signed_area(p, f));
      const Face& v = t.mesh.faces[f];
      const Vec3& x = t.mesh.positions[v[0]];
      a3[p.face_chart[f]] += 0.5 * (t.mesh.positions[v[1]] - x).cross(t.mesh.positions[v[2]] - x).norm();
    }
    // Every chart's wedges and triangles, at UV area = 3-D area.
    std::vector<ChartShape> shapes(nc);
    std::vector<int> local(p.uv.size(), -1);
    for (int f = 0; f < t.mesh.num_faces(); ++f) {
      const int c = p.face_chart[f];
      const double k = a2[c] > 0 ? std::sqrt(a3[c] / a2[c]) : 1.0;
      Face lf;
      for (int i = 0; i < 3; ++i) {
        int& l = local[p.uv_faces[f][i]];
        if (l < 0) l = static_cast<int>(shapes[c].uv.size()), shapes[c].uv.push_back(k * p.uv[p.uv_faces[f][i]]);
        lf[i] = l;
      }
      shapes[c].faces.push_back(lf);
    }
    double total = 0;
    for (int c = 0; c < nc; ++c) total += a3[c];
    using Clock = std::chrono::steady_clock;
    ShapePackOptions so;
    so.padding = padding;
    const auto t0 = Clock::now();
    const std::vector<ShapePlacement> sp = pack_shapes(shapes, so);
    const double ts = std::chrono::duration<double>(Clock::now() - t0).count();
    double cov_s = 0;
    for (int c = 0; c < nc; ++c) cov_s += a3[c] * sp[c].scale * sp[c].scale;
    // Rectangles: the bounding boxes.
    std::vector<Vec2> sizes(nc), lo(nc);
    for (int c = 0; c < nc; ++c) {
      Vec2 l = Vec2::Constant(1e300), h = -l;
      for (const Vec2& q : shapes[c].uv) l = l.cwiseMin(q), h = h.cwiseMax(q);
      sizes[c] = (h - l).cwiseMax(1e-12);
      lo[c] = l;
    }
    RectPackOptions ro2;
    ro2.padding = padding;
    ro2.may_turn = true;
    std::vector<char> turned;
    const auto t1 = Clock::now();
    const std::vector<RectPlacement> rp = pack_rectangles(sizes, ro2, &turned);
    const double tr = std::chrono::duration<double>(Clock::now() - t1).count();
    double cov_r = 0;
    for (int c = 0; c < nc; ++c) cov_r += a3[c] * rp[c].size.prod() / sizes[c].prod();
    std::printf("| %s | %d | %.3f | %.3f | %.3f | %.3f |\n", argv[1], nc, cov_s, ts, cov_r, tr);
    (void)total;
    if (argc > 3) {
      for (int f = 0; f < t.mesh.num_faces(); ++f) {
        const int c = p.face_chart[f];
        for (int i = 0; i < 3; ++i) local[p.uv_faces[f][i]] = -1;
        (void)c;
      }
      std::vector<Vec2> uv(p.uv.size());
      std::vector<int> seen(p.uv.size(), 0);
      for (int f = 0; f < t.mesh.num_faces(); ++f) {
        const int c = p.face_chart[f];
        const double k = a2[c] > 0 ? std::sqrt(a3[c] / a2[c]) : 1.0;
        for (int i = 0; i < 3; ++i) {
          const int w = p.uv_faces[f][i];
          if (!seen[w]) seen[w] = 1, uv[w] = sp[c].apply(k * p.uv[w]);
        }
      }
      p.uv = uv;
      write_obj(argv[3], t.mesh, &p);
      if (argc > 4) {
        LayoutImageOptions io;
        io.size = 1024;
        io.wireframe = false;
        write_png(argv[4], render_layout(p, std::vector<double>(p.uv_faces.size(), 0.0), io));
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
