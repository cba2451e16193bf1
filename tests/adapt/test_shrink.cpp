// Tests of the atlas-preserving shrink (adapt/shrink.h) on small textured assets built in code with
// the traps of real atlases: mirrored charts that share texels, overlapping charts, UVs outside
// [0,1], degenerate UV triangles, and islands whose textures differ in detail.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "adaptex/adapt/shrink.h"
#include "adaptex/core/errors.h"
#include "adaptex/io/image_io.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/paint/asset_eval.h"
#include "test_support.h"

namespace adaptex {
namespace {

/// A textured asset under construction: patches of n x n quads, each its own chart.
struct Asset {
  TriMesh mesh;
  Parameterization param;

  /// A flat patch at 3-D offset (x0, y0, z) of size w x h, with UV (u0,v0) + (s·x, t·y) for its local
  /// (x, y) in [0,w] x [0,h] (s < 0: mirrored); returns its first face.
  int patch(double x0, double y0, double z, double w, double h, int n, Vec2 uv0, double s, double t) {
    const int v0 = mesh.num_vertices(), w0 = param.num_wedges(), f0 = mesh.num_faces();
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const double x = w * i / n, y = h * j / n;
        mesh.positions.push_back(Vec3(x0 + x, y0 + y, z));
        param.uv.push_back(uv0 + Vec2(s * x, t * y));
        param.wedge_vertex.push_back(mesh.num_vertices() - 1);
      }
    auto id = [n](int i, int j) { return j * (n + 1) + i; };
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Face a{id(i, j), id(i + 1, j), id(i + 1, j + 1)}, b{id(i, j), id(i + 1, j + 1), id(i, j + 1)};
        for (const Face& f : {a, b}) {
          mesh.faces.push_back({v0 + f[0], v0 + f[1], v0 + f[2]});
          param.uv_faces.push_back({w0 + f[0], w0 + f[1], w0 + f[2]});
          param.face_chart.push_back(param.num_charts);
        }
      }
    ++param.num_charts;
    return f0;
  }
};

/// Waves of periods 10 and 14 texels (of a 256² map) inside [x0,x1] x [y0,y1] of the square, a smooth ramp
/// elsewhere.
ImageRGBA8 texture(int size, double x0, double x1, double y0, double y1) {
  ImageRGBA8 img(size, size, {0, 0, 0, 255});
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const double u = (i + 0.5) / size, v = (j + 0.5) / size;
      std::uint8_t* t = img.texel(i, j);
      if (u >= x0 && u <= x1 && v >= y0 && v <= y1) {
        const double w = std::sin(2 * M_PI * i / 10.0) * std::sin(2 * M_PI * j / 14.0);
        t[0] = static_cast<std::uint8_t>(128 + 100 * w);
        t[1] = static_cast<std::uint8_t>(128 - 90 * w);
        t[2] = static_cast<std::uint8_t>(100 + 100 * u);
      } else {
        t[0] = static_cast<std::uint8_t>(60 + 80 * u);
        t[1] = static_cast<std::uint8_t>(90 + 60 * v);
        t[2] = 120;
      }
    }
  return img;
}

/// The measure (paint/asset_eval.h) on other samples than the shrink's own.
double psnr(const TriMesh& mesh, const Parameterization& ref_param, const ImageRGBA8& original,
            const Parameterization& param, const ImageRGBA8& out) {
  SurfacePsnrOptions o;
  o.samples = 60000;
  o.seed = 12345;
  return surface_psnr(mesh, ref_param, original, mesh, param, out, {}, o).psnr;
}

/// Every trap at once: two mirrored halves sharing their texels, a chart overlapping another in part,
/// a chart whose UVs lie in the tile [1,2] x [0,1], a degenerate UV triangle.
struct Traps : ::testing::Test {
  Asset a;
  int left = 0, right = 0, shifted = 0, partial = 0, flat = 0;
  ImageRGBA8 tex = texture(256, 0.05, 0.45, 0.05, 0.45);

  void SetUp() override {
    // Left and right halves of a "face": the right one is mirrored onto the same texels.
    left = a.patch(0, 0, 0, 1, 1, 6, Vec2(0.05, 0.05), 0.4, 0.4);
    right = a.patch(1.2, 0, 0, 1, 1, 6, Vec2(0.45, 0.05), -0.4, 0.4);
    // A chart in the next UV tile (wraps onto [0.55, 0.95] x [0.05, 0.35]).
    shifted = a.patch(0, 2, 0, 1, 0.75, 4, Vec2(1.55, 0.05), 0.4, 0.4);
    // Two charts overlapping in part (half of the second lies on the first).
    flat = a.patch(0, 4, 0, 1, 1, 4, Vec2(0.05, 0.55), 0.35, 0.35);
    partial = a.patch(2, 4, 0, 1, 1, 4, Vec2(0.225, 0.55), 0.35, 0.35);
    // A degenerate UV triangle: collapse one corner of the last chart onto its neighbour's line.
    const Face& t = a.param.uv_faces[partial];
    a.param.uv[t[1]] = 0.5 * (a.param.uv[t[0]] + a.param.uv[t[2]]);
  }
};

TEST_F(Traps, IslandsGroupSharedCharts) {
  const UvIslands isl = find_uv_islands(a.param, 256, 0.02);
  EXPECT_EQ(isl.num_charts, 5);
  const auto island = [&](int face) { return isl.chart_island[isl.face_chart[face]]; };
  EXPECT_EQ(island(left), island(right));      // mirrored, fully shared
  EXPECT_EQ(island(flat), island(partial));    // half overlapping
  EXPECT_NE(island(left), island(shifted));    // disjoint after wrapping
  EXPECT_NE(island(left), island(flat));
  EXPECT_EQ(isl.num_islands, 3);
  EXPECT_EQ(isl.chart_shift[isl.face_chart[shifted]], Vec2(-1, 0));
}

TEST_F(Traps, ShrinkKeepsSharingOrientationAndBeatsDownsizing) {
  ShrinkOptions opt;
  opt.size = 64;
  opt.error_samples = 20000;
  opt.eval_samples = 40000;
  const ShrinkResult r = shrink_textured_mesh(a.mesh, a.param, {{"base_color", tex, MapKind::Color}}, opt);
  ASSERT_EQ(r.maps.size(), 1u);
  ASSERT_EQ(r.maps[0].width, 64);
  // Topology kept exactly: the mesh is the input's; only the degenerate face may get a wedge of its own.
  ASSERT_EQ(r.param.uv_faces.size(), a.param.uv_faces.size());
  std::vector<Face> expected = a.param.uv_faces;
  expected[partial] = r.param.uv_faces[partial];
  EXPECT_EQ(r.param.uv_faces, expected);
  for (size_t f = 0; f < a.param.uv_faces.size(); ++f)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(r.param.wedge_vertex[r.param.uv_faces[f][k]], a.mesh.faces[f][k]);
  EXPECT_EQ(r.faces_after, r.faces_before);
  // Every output UV is finite and inside the square.
  for (const Vec2& p : r.param.uv) {
    ASSERT_TRUE(std::isfinite(p.x()) && std::isfinite(p.y()));
    EXPECT_GE(p.minCoeff(), 0.0);
    EXPECT_LE(p.maxCoeff(), 1.0);
  }
  // No face changed orientation (the mirrored half stays mirrored); the degenerate one got an area.
  int flipped = 0, degenerate = 0;
  for (int f = 0; f < a.mesh.num_faces(); ++f) {
    const double a0 = uv_signed_area(a.param, f), a1 = uv_signed_area(r.param, f);
    degenerate += std::abs(a1) * 64 * 64 < 1e-6;
    flipped += (a0 > 0 && a1 < 0) || (a0 < 0 && a1 > 0);
  }
  EXPECT_EQ(flipped, 0);
  EXPECT_EQ(degenerate, 0);
  // The degenerate face is lifted, unless the chosen warp (a nonlinear map) already opened it.
  EXPECT_LE(r.lifted_faces, 1) << r.chosen;
  EXPECT_EQ(r.before.degenerate, 1);
  EXPECT_EQ(r.after.degenerate, 0);
  EXPECT_EQ(r.after.flipped, 0);
  EXPECT_LT(uv_signed_area(r.param, right + 3), 0.0);
  // Shared texels still shared, in the same mirror relation: wedges that had one UV keep one UV.
  const int n = 7 * 7;
  for (int k = 0; k < n; ++k) {
    const int wl = a.param.uv_faces[left][0] + k, wr = a.param.uv_faces[right][0] + k;
    const int i = k % 7, j = k / 7, kr = j * 7 + (6 - i);  // the mirrored partner of wedge k
    (void)wr;
    EXPECT_NEAR((r.param.uv[wl] - r.param.uv[a.param.uv_faces[right][0] + kr]).norm(), 0.0, 1e-12) << k;
  }
  EXPECT_GT(r.before.shared_fraction, 0.3);
  EXPECT_GT(r.after.shared_fraction, r.before.shared_fraction - 0.05);
  // Never worse than plain downsizing (measured on other samples than the shrink's own).
  const ImageRGBA8 down = box_downsize(tex, 64, 64);
  const double p_down = psnr(a.mesh, a.param, tex, a.param, down);
  const double p_out = psnr(a.mesh, a.param, tex, r.param, r.maps[0]);
  EXPECT_GE(p_out, p_down - 0.1) << r.chosen;
  EXPECT_GE(r.psnr, r.psnr_downsized);
}

TEST(Shrink, BudgetMovesTexelsToTheDetailedIsland) {
  // Two charts of equal 3-D and UV area: the left holds fine stripes, the right a smooth ramp.
  Asset a;
  const int detailed = a.patch(0, 0, 0, 1, 1, 4, Vec2(0.05, 0.3), 0.4, 0.4);
  const int smooth = a.patch(2, 0, 0, 1, 1, 4, Vec2(0.55, 0.3), 0.4, 0.4);
  const ImageRGBA8 tex = texture(256, 0.0, 0.5, 0.0, 1.0);
  ShrinkOptions opt;
  opt.size = 64;
  opt.error_samples = 20000;
  opt.eval_samples = 40000;
  opt.island_warp = false;  // the rigid budget alone
  const ShrinkResult r = shrink_textured_mesh(a.mesh, a.param, {{"base_color", tex, MapKind::Color}}, opt);
  auto uv_area = [&](int f0) {
    double s = 0;
    for (int f = f0; f < f0 + 32; ++f) s += std::abs(uv_signed_area(r.param, f));
    return s;
  };
  EXPECT_EQ(r.chosen, "budget");
  EXPECT_GT(uv_area(detailed), 3.0 * uv_area(smooth));
  EXPECT_GT(r.psnr, r.psnr_downsized + 1.0);
  const double p_down = psnr(a.mesh, a.param, tex, a.param, box_downsize(tex, 64, 64));
  EXPECT_GT(psnr(a.mesh, a.param, tex, r.param, r.maps[0]), p_down + 1.0);
}

/// Share of the UV area of faces [f0, f0 + count) that faces whose input UV centroid lies in
/// [lo, hi]² hold, on \p p.
double corner_share(const Parameterization& input, const Parameterization& p, int f0, int count, double lo, double hi) {
  double in = 0, all = 0;
  for (int f = f0; f < f0 + count; ++f) {
    const Face& t = input.uv_faces[f];
    const Vec2 c = (input.uv[t[0]] + input.uv[t[1]] + input.uv[t[2]]) / 3.0;
    const double area = std::abs(uv_signed_area(p, f));
    all += area;
    if (c.x() > lo && c.x() < hi && c.y() > lo && c.y() < hi) in += area;
  }
  return in / all;
}

double candidate_psnr(const ShrinkResult& r, const std::string& name) {
  for (const ShrinkCandidate& c : r.candidates)
    if (c.name == name && c.valid) return c.psnr;
  return -1;
}

ShrinkOptions island_warp_options() {
  ShrinkOptions opt;
  opt.size = 64;
  opt.error_samples = 20000;
  opt.eval_samples = 40000;
  opt.force_candidate = "island_warp";
  return opt;
}

TEST(Shrink, IslandWarpGivesTheDetailedCornerMoreArea) {
  // One chart, fine waves in its corner [0.1, 0.34]² of the square (9 % of its area), a ramp elsewhere.
  Asset a;
  const int f0 = a.patch(0, 0, 0, 1, 1, 10, Vec2(0.1, 0.1), 0.8, 0.8);
  const ImageRGBA8 tex = texture(256, 0.1, 0.34, 0.1, 0.34);
  const ShrinkResult r = shrink_textured_mesh(a.mesh, a.param, {{"base_color", tex, MapKind::Color}},
                                              island_warp_options());
  ASSERT_EQ(r.chosen, "island_warp");
  const double before = corner_share(a.param, a.param, f0, 200, 0.1, 0.34);
  EXPECT_NEAR(before, 0.09, 1e-9);
  EXPECT_GT(corner_share(a.param, r.param, f0, 200, 0.1, 0.34), 2.0 * before);
  EXPECT_EQ(r.after.flipped, 0);
  EXPECT_EQ(r.after.degenerate, 0);
  // The warp pays: the warped island beats the same island moved rigidly.
  EXPECT_GT(candidate_psnr(r, "island_warp"), candidate_psnr(r, "budget") + 0.5);
}

TEST(Shrink, IslandWarpKeepsMirroredTexelsShared) {
  // Two halves mirrored onto the same texels [0.05, 0.45]², detail in the corner [0.05, 0.17]² of them.
  Asset a;
  const int left = a.patch(0, 0, 0, 1, 1, 10, Vec2(0.05, 0.05), 0.4, 0.4);
  const int right = a.patch(1.2, 0, 0, 1, 1, 10, Vec2(0.45, 0.05), -0.4, 0.4);
  const ImageRGBA8 tex = texture(256, 0.05, 0.17, 0.05, 0.17);
  const ShrinkResult r = shrink_textured_mesh(a.mesh, a.param, {{"base_color", tex, MapKind::Color}},
                                              island_warp_options());
  ASSERT_EQ(r.chosen, "island_warp");
  EXPECT_EQ(r.islands, 1);
  // Every wedge of the left half still has its mirrored partner's UV: the texels stay shared.
  for (int k = 0; k < 11 * 11; ++k) {
    const int i = k % 11, j = k / 11, kr = j * 11 + (10 - i);
    EXPECT_NEAR((r.param.uv[a.param.uv_faces[left][0] + k] - r.param.uv[a.param.uv_faces[right][0] + kr]).norm(),
                0.0, 1e-12)
        << k;
  }
  // Not the identity: the corner got area; no face flipped (the right half stays mirrored) or degenerated.
  const double corner_before = corner_share(a.param, a.param, left, 200, 0.05, 0.17);
  EXPECT_GT(corner_share(a.param, r.param, left, 200, 0.05, 0.17), 1.1 * corner_before);
  int flipped = 0;
  for (int f = 0; f < a.mesh.num_faces(); ++f) {
    const double a0 = uv_signed_area(a.param, f), a1 = uv_signed_area(r.param, f);
    flipped += (a0 > 0) != (a1 > 0);
  }
  EXPECT_EQ(flipped, 0);
  EXPECT_LT(uv_signed_area(r.param, right + 5), 0.0);
  EXPECT_EQ(r.after.degenerate, 0);
  EXPECT_GT(r.after.shared_fraction, 0.9);
}

TEST(Shrink, IslandWarpIsTheIdentityWithoutDetail) {
  // A flat colour: no error anywhere, so the warped layout is exactly the rigid layout it warps (the
  // budget's or the uniform repack's, whichever ranked higher).
  Asset a;
  a.patch(0, 0, 0, 1, 1, 6, Vec2(0.1, 0.1), 0.3, 0.5);
  a.patch(2, 0, 0, 1, 1, 6, Vec2(0.6, 0.1), 0.3, 0.3);
  const ImageRGBA8 flat(128, 128, {90, 140, 200, 255});
  ShrinkOptions opt = island_warp_options();
  const ShrinkResult warped = shrink_textured_mesh(a.mesh, a.param, {{"base_color", flat, MapKind::Color}}, opt);
  ASSERT_EQ(warped.chosen, "island_warp");
  double nearest = 1e300;
  for (const std::string rigid : {"budget", "repacked"}) {
    opt.force_candidate = rigid;
    const ShrinkResult r = shrink_textured_mesh(a.mesh, a.param, {{"base_color", flat, MapKind::Color}}, opt);
    ASSERT_EQ(r.chosen, rigid);
    ASSERT_EQ(r.param.uv.size(), warped.param.uv.size());
    double d = 0;
    for (size_t w = 0; w < r.param.uv.size(); ++w) d = std::max(d, (warped.param.uv[w] - r.param.uv[w]).norm());
    nearest = std::min(nearest, d);
  }
  EXPECT_LT(nearest, 1e-12);
}

TEST(Shrink, WarpedIslandsRefinesTheWholeLayoutWarpInPlace) {
  // Two charts sharing no texels (so the whole-layout warp is tried), detail in a corner of the first.
  Asset a;
  const int first = a.patch(0, 0, 0, 1, 1, 10, Vec2(0.05, 0.1), 0.4, 0.8);
  const int second = a.patch(2, 0, 0, 1, 1, 10, Vec2(0.55, 0.1), 0.4, 0.8);
  const ImageRGBA8 tex = texture(256, 0.05, 0.2, 0.1, 0.3);
  const std::vector<ShrinkMap> maps{{"base_color", tex, MapKind::Color}};
  ShrinkOptions opt = island_warp_options();
  opt.force_candidate = "warped";
  const ShrinkResult whole = shrink_textured_mesh(a.mesh, a.param, maps, opt);
  ASSERT_EQ(whole.chosen, "warped");
  opt.force_candidate = "warped_islands";
  const ShrinkResult r = shrink_textured_mesh(a.mesh, a.param, maps, opt);
  ASSERT_EQ(r.chosen, "warped_islands");
  ASSERT_EQ(r.param.uv_faces.size(), a.param.uv_faces.size());
  EXPECT_EQ(r.after.flipped, 0);
  EXPECT_EQ(r.after.degenerate, 0);
  EXPECT_EQ(r.faces_after, r.faces_before);
  // In place: every chart stays inside its bounding box of the whole-layout warp, and something moved.
  double moved = 0;
  for (int f0 : {first, second}) {
    Vec2 lo = Vec2::Constant(1e300), hi = Vec2::Constant(-1e300);
    for (int f = f0; f < f0 + 200; ++f)
      for (int w : whole.param.uv_faces[f]) lo = lo.cwiseMin(whole.param.uv[w]), hi = hi.cwiseMax(whole.param.uv[w]);
    for (int f = f0; f < f0 + 200; ++f)
      for (int w : r.param.uv_faces[f]) {
        const Vec2& p = r.param.uv[w];
        EXPECT_TRUE(p.x() >= lo.x() - 1e-9 && p.x() <= hi.x() + 1e-9 && p.y() >= lo.y() - 1e-9 &&
                    p.y() <= hi.y() + 1e-9)
            << f << ": (" << p.x() << ", " << p.y() << ")";
        moved = std::max(moved, (p - whole.param.uv[w]).norm() * opt.size);
      }
  }
  EXPECT_GT(moved, 0.5);  // texels
}

TEST(Shrink, IslandWarpMeasuredRungsOnlyAdd) {
  // The measured-curve warps are further rungs of the ladder: ranked on the same samples, the island
  // warp with them is never below the one without.
  Asset a;
  a.patch(0, 0, 0, 1, 1, 10, Vec2(0.1, 0.1), 0.8, 0.8);
  const ImageRGBA8 tex = texture(256, 0.1, 0.34, 0.1, 0.34);
  const std::vector<ShrinkMap> maps{{"base_color", tex, MapKind::Color}};
  ShrinkOptions opt = island_warp_options();
  opt.island_warp_measured = false;
  const ShrinkResult power = shrink_textured_mesh(a.mesh, a.param, maps, opt);
  opt.island_warp_measured = true;
  const ShrinkResult both = shrink_textured_mesh(a.mesh, a.param, maps, opt);
  ASSERT_EQ(power.chosen, "island_warp");
  ASSERT_EQ(both.chosen, "island_warp");
  EXPECT_GE(candidate_psnr(both, "island_warp"), candidate_psnr(power, "island_warp"));
  EXPECT_EQ(both.after.flipped, 0);
  EXPECT_EQ(both.after.degenerate, 0);
}

TEST(Shrink, EveryMapFollowsTheLayout) {
  Asset a;
  a.patch(0, 0, 0, 1, 1, 4, Vec2(0.1, 0.1), 0.3, 0.3);
  a.patch(2, 0, 0, 1, 1, 4, Vec2(0.6, 0.6), 0.3, 0.3);
  const ImageRGBA8 tex = texture(128, 0.0, 0.5, 0.0, 0.5);
  ImageRGBA8 normal(64, 64, {128, 128, 255, 255});
  ShrinkOptions opt;
  opt.size = 32;
  opt.error_samples = 10000;
  opt.eval_samples = 20000;
  const ShrinkResult r = shrink_textured_mesh(
      a.mesh, a.param, {{"base_color", tex, MapKind::Color}, {"normal", normal, MapKind::Normal}}, opt);
  ASSERT_EQ(r.maps.size(), 2u);
  EXPECT_EQ(r.maps[1].width, 32);
  // A flat normal map stays flat wherever a chart reads it.
  EXPECT_GT(r.map_psnr[1], 45.0);
  ASSERT_EQ(r.map_psnr.size(), 2u);
}

TEST(Shrink, NoDegenerateOutputFaceWhateverTheCandidate) {
  // A plain and a mirrored chart, each with degenerate UV faces: one collapsed onto a line, one onto a
  // point (which also squeezes its neighbours), and UVs outside [0,1].
  Asset a;
  const int plain = a.patch(0, 0, 0, 1, 1, 4, Vec2(1.05, 0.05), 0.4, 0.4);
  const int mirrored = a.patch(2, 0, 0, 1, 1, 4, Vec2(0.95, 0.55), -0.4, 0.4);
  {
    const Face& t = a.param.uv_faces[plain + 10];
    a.param.uv[t[1]] = 0.25 * a.param.uv[t[0]] + 0.75 * a.param.uv[t[2]];
    const Face& p = a.param.uv_faces[mirrored + 12];
    a.param.uv[p[1]] = a.param.uv[p[2]] = a.param.uv[p[0]];
  }
  const int F = a.mesh.num_faces();
  auto degenerate = [&](const Parameterization& p, int n) {
    int d = 0;
    for (int f = 0; f < F; ++f) d += std::abs(uv_signed_area(p, f)) * n * n < 1e-6;
    return d;
  };
  ASSERT_GE(degenerate(a.param, 64), 2);
  const ImageRGBA8 tex = texture(128, 0.0, 0.5, 0.0, 1.0);
  for (const std::string candidate :
       {"", "downsized", "artist", "repacked", "budget", "island_warp", "warped", "warped_islands"}) {
    ShrinkOptions opt;
    opt.size = 64;
    opt.error_samples = 10000;
    opt.eval_samples = 20000;
    opt.force_candidate = candidate;
    const ShrinkResult r = shrink_textured_mesh(a.mesh, a.param, {{"base_color", tex, MapKind::Color}}, opt);
    EXPECT_TRUE(candidate.empty() || r.chosen == candidate) << r.chosen;
    EXPECT_EQ(degenerate(r.param, 64), 0) << candidate;
    EXPECT_EQ(r.after.degenerate, 0) << candidate;
    EXPECT_GE(r.lifted_faces, 2) << candidate;
    int flipped = 0;
    for (int f = 0; f < F; ++f) {
      const double a0 = uv_signed_area(a.param, f), a1 = uv_signed_area(r.param, f);
      flipped += (a0 > 0 && a1 < 0) || (a0 < 0 && a1 > 0);
    }
    EXPECT_EQ(flipped, 0) << candidate;
    // The 3-D mesh is untouched: every face's wedges still name its vertices.
    ASSERT_EQ(static_cast<int>(r.param.uv_faces.size()), F);
    for (int f = 0; f < F; ++f)
      for (int k = 0; k < 3; ++k) EXPECT_EQ(r.param.wedge_vertex[r.param.uv_faces[f][k]], a.mesh.faces[f][k]);
    // Lifted faces stay tiny (well under a texel), where they were. The warps, nonlinear maps, open a
    // face collapsed onto a line (not onto a point) a little: under a tenth of its chart's mean face.
    double mean = 0;
    for (int f = plain; f < plain + 32; ++f) mean += std::abs(uv_signed_area(r.param, f)) * 64 * 64 / 32;
    const bool nonlinear = r.chosen == "island_warp" || r.chosen == "warped" || r.chosen == "warped_islands";
    const double most = nonlinear ? 0.1 * mean : 0.05;
    for (int f = 0; f < F; ++f)
      EXPECT_TRUE(std::abs(uv_signed_area(a.param, f)) * 64 * 64 >= 1e-6 ||
                  std::abs(uv_signed_area(r.param, f)) * 64 * 64 < most)
          << candidate << " " << f << ": " << std::abs(uv_signed_area(r.param, f)) * 64 * 64 << " texels";
  }
}

TEST(Shrink, RejectsBadInput) {
  Asset a;
  a.patch(0, 0, 0, 1, 1, 2, Vec2(0.1, 0.1), 0.3, 0.3);
  const ImageRGBA8 tex = texture(64, 0, 1, 0, 1);
  EXPECT_THROW(shrink_textured_mesh(a.mesh, a.param, {}), InvalidInputError);
  ShrinkOptions opt;
  opt.size = 4;
  EXPECT_THROW(shrink_textured_mesh(a.mesh, a.param, {{"c", tex, MapKind::Color}}, opt), InvalidInputError);
  Asset nan = a;
  nan.param.uv[0].x() = std::nan("");
  EXPECT_THROW(shrink_textured_mesh(nan.mesh, nan.param, {{"c", tex, MapKind::Color}}), InvalidInputError);
  EXPECT_THROW(shrink_textured_mesh(a.mesh, a.param, {{"c", ImageRGBA8(), MapKind::Color}}), InvalidInputError);
  for (const char* bad : {"best", "Budget"}) {
    opt.size = 32;
    opt.force_candidate = bad;
    EXPECT_THROW(shrink_textured_mesh(a.mesh, a.param, {{"c", tex, MapKind::Color}}, opt), InvalidInputError) << bad;
  }
  opt.force_candidate = "";
  opt.island_warp_ratio = 0.5;
  EXPECT_THROW(shrink_textured_mesh(a.mesh, a.param, {{"c", tex, MapKind::Color}}, opt), InvalidInputError);
}

TEST(Shrink, ProgressCanCancel) {
  Asset a;
  a.patch(0, 0, 0, 1, 1, 2, Vec2(0.1, 0.1), 0.3, 0.3);
  ShrinkOptions opt;
  opt.size = 32;
  int calls = 0;
  opt.progress = [&](std::string_view, double) { return ++calls < 3; };
  EXPECT_THROW(shrink_textured_mesh(a.mesh, a.param, {{"c", texture(64, 0, 1, 0, 1), MapKind::Color}}, opt),
               CancelledError);
  EXPECT_EQ(calls, 3);
}

TEST(ShrinkCli, WritesEveryMapAndTheReportOrNothing) {
  test::TempDir dir;
  Asset a;
  a.patch(0, 0, 0, 1, 1, 4, Vec2(0.05, 0.3), 0.4, 0.4);
  a.patch(2, 0, 0, 1, 1, 4, Vec2(0.55, 0.3), -0.4, 0.4);
  write_obj(dir.path / "m.obj", a.mesh, &a.param, std::string("m.mtl"), "skin");
  std::ofstream(dir.path / "m.mtl") << "newmtl skin\nmap_Kd m.png\nnorm m_n.png\n";
  write_png(dir.path / "m.png", texture(128, 0.0, 0.5, 0.0, 1.0));
  write_png(dir.path / "m_n.png", ImageRGBA8(64, 64, {128, 128, 255, 255}));
  const auto out = dir.path / "out";
  auto r = test::run_cli("shrink " + (dir.path / "m.obj").string() + " --size 32 -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"m.obj", "m.mtl", "m.png", "m_normal.png", "m.glb", "report.json"})
    EXPECT_TRUE(std::filesystem::exists(out / f)) << f;
  EXPECT_NE(r.out.find("base_color: psnr"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("normal: psnr"), std::string::npos) << r.out;
  const TexturedMesh back = read_textured_obj(out / "m.obj");
  EXPECT_EQ(back.mesh.num_faces(), a.mesh.num_faces());
  EXPECT_EQ(read_image(out / "m_normal.png").width, 32);
  // A map that is missing: exit 2, one line, no output.
  std::ofstream(dir.path / "m.mtl") << "newmtl skin\nmap_Kd gone.png\n";
  const auto bad = dir.path / "bad";
  r = test::run_cli("shrink " + (dir.path / "m.obj").string() + " --size 32 -o " + bad.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(std::filesystem::exists(bad));
  r = test::run_cli("shrink " + (dir.path / "m.obj").string() + " -o " + bad.string());  // no size
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(bad));
  // A --size above every base colour map would enlarge, not shrink: exit 2, one line, no output.
  std::ofstream(dir.path / "m.mtl") << "newmtl skin\nmap_Kd m.png\n";
  r = test::run_cli("shrink " + (dir.path / "m.obj").string() + " --size 256 -o " + bad.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("--size 256 is larger than every base colour map"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(bad));
  r = test::run_cli("shrink " + (dir.path / "m.obj").string() + " --size 128 -o " + bad.string());  // equal: a re-layout
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("enlarges"), std::string::npos) << r.err;
}

TEST(ShrinkCli, ReportsFacesAndBoundsTheirGrowth) {
  test::TempDir dir;
  Asset a;
  a.patch(0, 0, 0, 1, 1, 4, Vec2(0.05, 0.05), 0.9, 0.9);
  write_obj(dir.path / "m.obj", a.mesh, &a.param, std::string("m.mtl"), "skin");
  std::ofstream(dir.path / "m.mtl") << "newmtl skin\nmap_Kd m.png\n";
  write_png(dir.path / "m.png", texture(256, 0.05, 0.5, 0.05, 0.5));
  const std::string mesh = (dir.path / "m.obj").string(), tex = (dir.path / "m.png").string();
  const int F = a.mesh.num_faces();
  // shrink --no-refine: the input's faces exactly, said on stdout and in report.json.
  auto r = test::run_cli("shrink " + mesh + " --size 64 --no-refine -o " + (dir.path / "s").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string n = std::to_string(F);
  EXPECT_NE(r.out.find("faces: " + n + " -> " + n + " (+0.0 %)"), std::string::npos) << r.out;
  const auto report = nlohmann::json::parse(std::ifstream(dir.path / "s" / "report.json"));
  EXPECT_EQ(report["shrink"]["faces_before"], F);
  EXPECT_EQ(report["shrink"]["faces_after"], F);
  EXPECT_EQ(report["shrink"]["face_growth"], 0.0);
  EXPECT_EQ(read_textured_obj(dir.path / "s" / "m.obj").mesh.faces, a.mesh.faces);
  // A negative or non-finite bound: exit 2, one line naming the flag, no output.
  for (const char* bad : {"-0.5", "nan", "inf"}) {
    r = test::run_cli("shrink " + mesh + " --size 64 --max-face-growth " + bad + " -o " + (dir.path / "bad").string());
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("--max-face-growth"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.path / "bad")) << bad;
  }
  // density-flow refines this coarse patch under fine detail; --max-face-growth 0.1 bounds it.
  r = test::run_cli("reparam " + mesh + " " + tex + " --adapt density-flow -o " + (dir.path / "free").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const int free_faces = read_textured_obj(dir.path / "free" / "m.obj").mesh.num_faces();
  EXPECT_GT(free_faces, F + F / 10);
  r = test::run_cli("reparam " + mesh + " " + tex + " --adapt density-flow --max-face-growth 0.1 -o " +
                    (dir.path / "bounded").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const int bounded = read_textured_obj(dir.path / "bounded" / "m.obj").mesh.num_faces();
  EXPECT_LE(bounded, F + F / 10);
  EXPECT_GE(bounded, F);
}

}  // namespace
}  // namespace adaptex
