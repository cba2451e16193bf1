// SurfaceSignalCache (paint/surface_cache.h): the texture resampled from the cache against exact
// replay, on meshes built in code: the error bound, and exactness where the signal is linear.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <utility>

#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/paint/eval.h"
#include "adaptex/paint/generate.h"
#include "adaptex/paint/painter.h"
#include "adaptex/paint/signal.h"
#include "adaptex/paint/surface_cache.h"
#include "adaptex/param/unwrap.h"
#include "test_scene.h"

namespace adaptex {
namespace {

/// Mean squared difference (RGB, [0,1]) of two textures over the chart texels of \p map.
double texel_mse(const ImageRGBA8& a, const ImageRGBA8& b, const TexelMap& map) {
  double s = 0;
  for (int t : map.inside)
    for (int c = 0; c < 3; ++c) {
      const double d = (a.data[size_t(t) * 4 + c] - b.data[size_t(t) * 4 + c]) / 255.0;
      s += d * d;
    }
  return s / (3.0 * map.inside.size());
}

double psnr(double mse) { return 10 * std::log10(1.0 / mse); }

TEST(SurfaceSignalCache, TextureFromTheCacheIsWithinBoundOfExactReplay) {
  const test::Scene sc = test::torus_scene(48, 24, StrokeKind::Mixed, 40, 4);
  const TriMesh& mesh = sc.mesh;
  const Parameterization& param = sc.param;
  const StrokeFile& strokes = sc.strokes;
  const int N = 256;
  PainterOptions po;
  po.width = po.height = N;
  Painter exact(mesh, param, po, strokes.background);
  exact.paint_all(strokes);
  const TexelMap& map = exact.texel_map();
  const double texel = std::sqrt(surface_area(mesh) / map.inside.size());
  SurfaceSignalCache cache(mesh, texel / 3, strokes.background);
  cache.update(strokes);
  EXPECT_EQ(cache.strokes(), 40);
  EXPECT_GT(cache.num_samples(), 5 * static_cast<long long>(map.inside.size()));
  Painter cached(mesh, param, po, strokes.background);
  cached.fill_colours(cache.texel_colours(map, mesh));
  const double diff = texel_mse(cached.texture(), exact.texture(), map);
  // Reconstruction error of both textures against the exact signal (the quality measure).
  const std::vector<SurfacePoint> pts = sample_surface(mesh, 100000, 9);
  const std::vector<Vec3> truth = StrokeSignal(mesh, strokes).evaluate(pts);
  const double e_exact = reconstruction_mse(param, exact.texture(), pts, truth);
  const double e_cached = reconstruction_mse(param, cached.texture(), pts, truth);
  std::printf("texel PSNR cache vs replay %.1f dB; reconstruction PSNR replay %.2f dB, cache %.2f dB\n", psnr(diff),
              psnr(e_exact), psnr(e_cached));
  EXPECT_GT(psnr(diff), 35.0);                         // texel values close to exact replay
  EXPECT_LT(std::abs(psnr(e_cached) - psnr(e_exact)), 0.3);  // the quality measure barely moves
  EXPECT_GT(diff, 0.0);  // not vacuous: the cache does interpolate
}

TEST(SurfaceSignalCache, ExactWithoutStrokesAndAtLatticePoints) {
  const TriMesh mesh = shapes::icosphere(2);
  SurfaceSignalCache cache(mesh, 0.05, Vec3(0.2, 0.4, 0.6));
  EXPECT_NEAR(cache.colour(3, 0.2, 0.3).y(), 0.4f, 1e-6f);
  GenerateOptions go;
  go.kind = StrokeKind::Blobs;
  go.count = 3;
  const StrokeFile strokes = [&] {
    StrokeFile f = generate_strokes(mesh, go);
    f.background = Vec3(0.2, 0.4, 0.6);
    return f;
  }();
  cache.update(strokes);
  const StrokeSignal signal(mesh, strokes);
  double worst = 0;
  int painted = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) {  // the corners are lattice points: exact there
    const Vec3 want = signal.evaluate(SurfacePoint{f, 1.0, 0.0});
    worst = std::max(worst, (cache.colour(f, 1.0, 0.0).cast<double>() - want).cwiseAbs().maxCoeff());
    painted += (want - strokes.background).norm() > 0.05;
  }
  EXPECT_LT(worst, 3.0 / 65535);  // 16-bit fixed point, one rounding per stroke (3 blobs)
  EXPECT_GT(painted, 20);  // not vacuous: the blobs cover corners (a cache left at the background fails)
}

TEST(SurfaceSignalCache, HardBrushesFarFromTheOriginReachEverySampleInTheirBall) {
  // Far from the origin single precision cannot tell 1e-5 apart (its step there is ~2e-3): the face
  // index (floats) must not drop a face whose corner lies just inside a hard dab. 40 separate
  // triangles; each gets a dab whose ball reaches 1e-5 past the triangle's corner that lies farthest
  // from its centroid, on the line through both (where the bound |p - centroid| < r + R is tight).
  const Vec3 far(1e4, -2e4, 3e3);
  const double r = 0.13;
  TriMesh mesh;
  StrokeFile strokes;
  strokes.background = Vec3(1, 1, 1);
  for (int k = 0; k < 40; ++k) {
    const double ang = 0.157 * k;
    const Vec3 dir(std::cos(ang), std::sin(ang), 0), side(-std::sin(ang), std::cos(ang), 0);
    const Vec3 a = far + Vec3(2.0 * (k % 8), 2.0 * (k / 8), 0.001 * k);
    const int v = mesh.num_vertices();
    mesh.positions.push_back(a);
    mesh.positions.push_back(a + 0.3 * dir + 0.15 * side);
    mesh.positions.push_back(a + 0.3 * dir - 0.15 * side);
    mesh.faces.push_back({v, v + 1, v + 2});
    Stroke st;
    st.radius = r;
    st.hardness = 1;
    st.opacity = 1;
    st.color = Vec3(0, 0, 0);
    st.dabs.push_back(a - (r - 1e-5) * dir);  // the corner at r - 1e-5: painted
    strokes.strokes.push_back(st);
  }
  SurfaceSignalCache cache(mesh, 0.01, strokes.background);
  cache.update(strokes);
  const StrokeSignal signal(mesh, strokes);
  int painted = 0;
  double worst = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Vec3 want = signal.evaluate(SurfacePoint{f, 1.0, 0.0});  // corner a
    worst = std::max(worst, (cache.colour(f, 1.0, 0.0).cast<double>() - want).cwiseAbs().maxCoeff());
    painted += want.x() < 0.5;
  }
  EXPECT_EQ(painted, 40);  // the exact signal paints every corner a
  EXPECT_LT(worst, 3.0 / 65535);
}

/// A 2x2 decal projected straight down onto the unit square around (0.4, 0.5), between two brush
/// strokes, over a grey background.
StrokeFile decal_history() {
  StrokeFile f;
  f.background = Vec3(0.5, 0.5, 0.5);
  Stroke brush;
  brush.radius = 0.2;
  brush.color = Vec3(0.9, 0.1, 0.1);
  brush.dabs = {Vec3(0.3, 0.3, 0), Vec3(0.5, 0.4, 0)};
  Stroke decal;
  decal.type = Stroke::Type::Decal;
  decal.image = ImageRGBA8(2, 2, {0, 40, 200, 255});  // blue, one transparent texel
  decal.image.texel(1, 1)[3] = 0;
  decal.camera = DecalCamera{Vec3(0.4, 0.5, 2.0), Vec3(0.4, 0.5, 0.0), Vec3(0, 1, 0), 20, 1.0};
  decal.opacity = 0.8;
  f.strokes = {brush, decal, brush};
  f.strokes[2].color = Vec3(0.1, 0.2, 0.9);
  f.strokes[2].dabs = {Vec3(0.6, 0.6, 0)};
  return f;
}

TEST(SurfaceSignalCache, DecalsAreExactAtLatticePointsAndInThePointCache) {
  const TriMesh mesh = shapes::plane(8);
  const StrokeFile history = decal_history();
  const StrokeSignal signal(mesh, history);
  ASSERT_TRUE(signal.has_decals());
  SurfaceSignalCache cache(mesh, 0.02, history.background);
  cache.update(history);
  const std::vector<SurfacePoint> pts = sample_surface(mesh, 4000, 2);
  PointSignalCache points(mesh, pts, history.background);
  points.update(history);
  EXPECT_TRUE(points.has_decals());
  const std::vector<Vec3> exact = signal.evaluate(pts);
  double worst_points = 0, worst_corners = 0;
  int decal_points = 0;
  for (size_t k = 0; k < pts.size(); ++k) {
    worst_points = std::max(worst_points, (points.values()[k] - exact[k]).cwiseAbs().maxCoeff());
    decal_points += std::abs(exact[k].z() - 200.0 / 255 * 0.8 - 0.5 * 0.2) < 0.05;
  }
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Vec3 want = signal.evaluate(SurfacePoint{f, 0.0, 1.0});
    worst_corners = std::max(worst_corners, (cache.colour(f, 0.0, 1.0).cast<double>() - want).cwiseAbs().maxCoeff());
  }
  EXPECT_LE(worst_points, 1e-12);
  // The cache stores 16-bit fixed point: one rounding of at most 0.5 / 65535 per composite (3 here).
  EXPECT_LT(worst_corners, 3.0 / 65535);
  EXPECT_GT(decal_points, 50);  // the decal is really there
}

TEST(SurfaceSignalCache, RejectsBadInput) {
  const TriMesh mesh = shapes::icosphere(1);
  EXPECT_THROW(SurfaceSignalCache(mesh, 0.0, Vec3(1, 1, 1)), InvalidInputError);
  EXPECT_THROW(SurfaceSignalCache(mesh, 0.1, Vec3(2, 1, 1)), InvalidInputError);
  EXPECT_THROW(SurfaceSignalCache(mesh, 1e-4, Vec3(1, 1, 1), 1000), InvalidInputError);
  SurfaceSignalCache cache(mesh, 0.1, Vec3(1, 1, 1));
  TexelMap map;
  EXPECT_THROW(cache.texel_colours(map, shapes::icosphere(2)), InvalidInputError);
}

TEST(SurfaceSignalCache, FillColoursRejectsBadColoursAndKeepsTheTexture) {
  const TriMesh mesh = shapes::icosphere(1);
  const Parameterization param = unwrap(mesh).param;
  PainterOptions po;
  po.width = po.height = 32;
  Painter painter(mesh, param, po, Vec3(1, 1, 1));
  const size_t n = painter.texel_map().inside.size();
  const ImageRGBA8 before = painter.texture();
  EXPECT_THROW(painter.fill_colours(std::vector<Vec3f>(n + 1, Vec3f(0, 0, 0))), InvalidInputError);
  std::vector<Vec3f> bad(n, Vec3f(0, 0, 0));
  bad[n / 2].y() = std::nanf("");
  EXPECT_THROW(painter.fill_colours(bad), InvalidInputError);
  EXPECT_EQ(painter.texture().data, before.data);  // nothing was written
  painter.fill_colours(std::vector<Vec3f>(n, Vec3f(0, 2, -1)));  // clamped to [0, 1]
  const int t = painter.texel_map().inside[0];
  EXPECT_EQ(painter.texture().data[size_t(t) * 4 + 0], 0);
  EXPECT_EQ(painter.texture().data[size_t(t) * 4 + 1], 255);
  EXPECT_EQ(painter.texture().data[size_t(t) * 4 + 2], 0);
  painter.begin_stroke(Stroke{});
  EXPECT_THROW(painter.fill_colours(std::vector<Vec3f>(n, Vec3f(0, 0, 0))), Error);
}

TEST(SurfaceSignalCache, ColoursHandOverAPaintersStateExactly) {
  const TriMesh mesh = shapes::torus(24, 12);
  const Parameterization param = unwrap(mesh).param;
  GenerateOptions go;
  go.kind = StrokeKind::Mixed;
  go.count = 6;
  go.seed = 5;
  const StrokeFile f = generate_strokes(mesh, go);
  PainterOptions po;
  po.width = po.height = 64;
  po.padding = 2;
  Painter a(mesh, param, po, f.background);
  for (size_t k = 0; k + 1 < f.strokes.size(); ++k) a.paint_stroke(f.strokes[k]);
  Painter b(mesh, param, po, f.background);
  const std::vector<Vec3f> c = a.colours();
  ASSERT_EQ(c.size(), a.texel_map().inside.size());
  b.fill_colours(c);
  EXPECT_EQ(b.texture().data, a.texture().data);
  // Painting on goes on exactly alike (colours are floats, not the texture's bytes).
  a.paint_stroke(f.strokes.back());
  b.paint_stroke(f.strokes.back());
  EXPECT_EQ(b.texture().data, a.texture().data);
  EXPECT_EQ(b.colours(), a.colours());
  // A copy on copies of the mesh and layout paints on alike, and outlives them.
  auto mesh2 = std::make_unique<TriMesh>(mesh);
  auto param2 = std::make_unique<Parameterization>(param);
  auto copy = std::make_unique<Painter>(a, *mesh2, *param2);
  EXPECT_EQ(copy->texture().data, a.texture().data);
  EXPECT_EQ(copy->texel_map().inside, a.texel_map().inside);
  a.paint_stroke(f.strokes.front());
  copy->paint_stroke(f.strokes.front());
  EXPECT_EQ(copy->texture().data, a.texture().data);
  Parameterization moved = param;
  moved.uv[0].x() += 1e-3;
  EXPECT_THROW(Painter(a, mesh, moved), InvalidInputError);
  a.begin_stroke(f.strokes.back());
  EXPECT_THROW(a.colours(), Error);
  EXPECT_THROW(Painter(a, mesh, param), Error);
}

}  // namespace
}  // namespace adaptex
