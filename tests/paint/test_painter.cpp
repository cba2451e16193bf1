// Texel map (fill rule), painter (contract at texel centres, per-stroke max, order, interactive ==
// whole stroke, rect), seam padding, stroke signal (fast == brute force), eval (PSNR vs size).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <string_view>

#include "adaptex/core/shapes.h"
#include "adaptex/paint/eval.h"
#include "adaptex/paint/padding.h"
#include "adaptex/paint/painter.h"
#include "adaptex/paint/signal.h"
#include "adaptex/paint/texel_map.h"
#include "brush_test_util.h"

using namespace adaptex;
using adaptex::test::make_stroke;
using adaptex::test::planar_param;
using adaptex::test::plane_strokes;
using adaptex::test::segment;

namespace {

Vec3 texel_point(const TriMesh& mesh, const TexelMap& map, int t) {
  return point_on_face(mesh, map.face[t], map.bary[t].x(), map.bary[t].y());
}

}  // namespace

TEST(TexelMap, PlaneCoversEveryCentreWithTheRightPoint) {
  const TriMesh mesh = shapes::plane(4);
  const Parameterization param = planar_param(mesh);
  for (auto [w, h] : {std::pair{8, 8}, std::pair{13, 7}, std::pair{1, 1}}) {
    const TexelMap map = build_texel_map(mesh, param, w, h);
    ASSERT_EQ(map.inside.size(), static_cast<size_t>(w * h)) << w << "x" << h;
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) {
        const int t = map.index(i, j);
        const Vec3 expect((i + 0.5) / w, (j + 0.5) / h, 0);
        EXPECT_LT((map.position[t].cast<double>() - expect).norm(), 1e-6);
        EXPECT_LT((texel_point(mesh, map, t) - expect).norm(), 1e-6);
      }
  }
}

TEST(TexelMap, SharedEdgesThroughCentresAreCoveredExactlyOnce) {
  // Two triangles whose shared diagonal passes through texel centres (i+.5)/8 = (j+.5)/8, and a
  // fan of 8 triangles around a vertex placed exactly on a texel centre.
  TriMesh quad;
  quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  quad.faces = {{0, 1, 2}, {0, 2, 3}};
  TriMesh fan;
  const Vec3 c(4.5 / 9, 4.5 / 9, 0);
  fan.positions.push_back(c);
  for (int k = 0; k < 8; ++k) {
    const double a = k * M_PI / 4;
    fan.positions.push_back(c + 0.4 * Vec3(std::cos(a), std::sin(a), 0));
  }
  for (int k = 0; k < 8; ++k) fan.faces.push_back({0, 1 + k, 1 + (k + 1) % 8});
  for (auto [mesh, n] : {std::pair{quad, 8}, std::pair{fan, 9}}) {
    const TexelMap all = build_texel_map(mesh, planar_param(mesh), n, n);
    std::vector<int> count(n * n, 0);
    for (int f = 0; f < mesh.num_faces(); ++f) {
      TriMesh one;
      one.positions = mesh.positions;
      one.faces = {mesh.faces[f]};
      const TexelMap m = build_texel_map(one, planar_param(one), n, n);
      for (int t : m.inside) ++count[t];
    }
    for (int t = 0; t < n * n; ++t) {
      EXPECT_LE(count[t], 1) << "texel " << t << " covered twice";
      EXPECT_EQ(count[t] == 1, all.face[t] >= 0);
    }
    if (n == 8) {
      EXPECT_EQ(all.inside.size(), 64u);  // the quad covers the whole square
    } else {
      EXPECT_GE(all.face[all.index(4, 4)], 0);  // the centre vertex's texel is not lost
    }
  }
}

namespace {
/// Two unit squares apart in z = 0 (x in [0,1] and [2,3]) on one chart of the unit square: the left
/// one with uv = (x, y), the right one mirrored (u = 3 - x), so every texel is shared. Plus a
/// degenerate UV triangle and one reaching outside [0,1]^2 (both must be harmless).
std::pair<TriMesh, Parameterization> mirrored_twins() {
  TriMesh mesh;
  Parameterization p;
  auto square = [&](double x0, bool mirror) {
    const int v = mesh.num_vertices();
    for (Vec2 c : {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)}) {
      mesh.positions.push_back(Vec3(x0 + c.x(), c.y(), 0));
      p.uv.push_back(Vec2(mirror ? 1 - c.x() : c.x(), c.y()));
      p.wedge_vertex.push_back(v + int(p.wedge_vertex.size()) - v);
    }
    for (Face f : {Face{v, v + 1, v + 2}, Face{v, v + 2, v + 3}}) {
      mesh.faces.push_back(f);
      p.uv_faces.push_back(f);
      p.face_chart.push_back(mirror ? 1 : 0);
    }
  };
  square(0, false);
  square(2, true);
  // A sliver below: one face with all three UVs equal, one reaching past u = 1.
  const int v = mesh.num_vertices();
  for (Vec3 q : {Vec3(0, -2, 0), Vec3(1, -2, 0), Vec3(1, -1, 0), Vec3(0, -1, 0)}) mesh.positions.push_back(q);
  for (Vec2 t : {Vec2(0.5, 0.5), Vec2(0.5, 0.5), Vec2(0.5, 0.5), Vec2(1.3, 0.2)}) p.uv.push_back(t);
  for (int k = 0; k < 4; ++k) p.wedge_vertex.push_back(v + k);
  mesh.faces.push_back({v, v + 1, v + 2});
  p.uv_faces.push_back({v, v + 1, v + 2});
  mesh.faces.push_back({v, v + 2, v + 3});
  p.uv_faces.push_back({v, v + 2, v + 3});
  p.face_chart.push_back(2);
  p.face_chart.push_back(2);
  p.num_charts = 3;
  for (size_t w = 0; w < p.wedge_vertex.size(); ++w) p.wedge_vertex[w] = int(w);
  return {mesh, p};
}

/// RGB of texel (i, j), 0..255.
Vec3 texel_rgb(const ImageRGBA8& tex, int i, int j) {
  const auto* px = tex.texel(i, j);
  return Vec3(px[0], px[1], px[2]);
}
}  // namespace

TEST(TexelMap, OverlappingChartsListTheirSharedTexelsAsAliases) {
  const auto [mesh, param] = mirrored_twins();
  const TexelMap map = build_texel_map(mesh, param, 16, 16, true);
  ASSERT_EQ(map.inside.size(), 256u);
  // Every texel: the later (mirrored, right) square owns it, the left one is its alias at the same
  // UV point; the sliver's faces add aliases where they cover centres too.
  int left = 0;
  for (const TexelAlias& a : map.aliases) {
    ASSERT_GE(a.texel, 0);
    ASSERT_LT(a.texel, 256);
    if (a.face > 1) continue;
    ++left;
    const int i = a.texel % 16, j = a.texel / 16;
    EXPECT_NEAR(a.position.x(), (i + 0.5) / 16, 1e-6);  // uv = (x, y) on the left square
    EXPECT_NEAR(a.position.y(), (j + 0.5) / 16, 1e-6);
    EXPECT_NEAR(map.position[a.texel].x(), 3 - (i + 0.5) / 16, 1e-5);  // mirrored on the right one
  }
  EXPECT_EQ(left, 256);
  EXPECT_TRUE(std::is_sorted(map.aliases.begin(), map.aliases.end(),
                             [](const TexelAlias& a, const TexelAlias& b) { return a.texel < b.texel; }));
  EXPECT_TRUE(build_texel_map(shapes::plane(4), planar_param(shapes::plane(4)), 16, 16, true).aliases.empty());
  const TexelMap plain = build_texel_map(mesh, param, 16, 16);  // not asked for: none, same texels
  EXPECT_TRUE(plain.aliases.empty());
  EXPECT_EQ(plain.face, map.face);
}

TEST(Painter, PaintingEitherSideOfASharedTexelPaintsIt) {
  const auto [mesh, param] = mirrored_twins();
  const Vec3 red(1, 0, 0), blue(0, 0, 1);
  for (bool interactive : {false, true}) {
    Painter painter(mesh, param, {32, 32, 2});
    // Left square at uv (0.25, 0.5) (an alias point); the right square at x = 2.25: uv (0.75, 0.5).
    const Stroke left = make_stroke(red, 0.06, 1.0, 1.0, segment({0.25, 0.45}, {0.25, 0.55}, 0.005));
    const Stroke right = make_stroke(blue, 0.06, 1.0, 1.0, segment({2.25, 0.45}, {2.25, 0.55}, 0.005));
    for (const Stroke& s : {left, right}) {
      if (!interactive) {
        painter.paint_stroke(s);
        continue;
      }
      painter.begin_stroke(s);
      for (const Vec3& d : s.dabs) painter.add_dab(d);
      painter.end_stroke();
    }
    const ImageRGBA8& tex = painter.texture();
    EXPECT_EQ(texel_rgb(tex, 8, 16), Vec3(255, 0, 0)) << interactive;   // uv (0.265, 0.515)
    EXPECT_EQ(texel_rgb(tex, 23, 16), Vec3(0, 0, 255)) << interactive;  // uv (0.734, 0.515)
    EXPECT_EQ(texel_rgb(tex, 16, 16), Vec3(255, 255, 255)) << interactive;  // between: untouched
    EXPECT_EQ(texel_rgb(tex, 8, 4), Vec3(255, 255, 255)) << interactive;
  }
}

TEST(Painter, TexelsEqualTheContractAtTheirCentres) {
  const TriMesh mesh = shapes::plane(8);
  const Parameterization param = planar_param(mesh);
  StrokeFile file = plane_strokes();
  file.background = Vec3(0.9, 0.95, 1.0);
  Painter painter(mesh, param, {300, 200, 4});
  painter.paint_all(file);
  const ImageRGBA8& tex = painter.texture();
  const TexelMap& map = painter.texel_map();
  EXPECT_GT(painter.texel_updates(), 0);
  std::mt19937 rng(5);
  int painted = 0;
  for (int k = 0; k < 4000; ++k) {
    const int t = map.inside[rng() % map.inside.size()];
    const Vec3 truth = evaluate_strokes_reference(file, texel_point(mesh, map, t));
    for (int c = 0; c < 3; ++c) {
      const double stored = tex.data[static_cast<size_t>(t) * 4 + c];
      EXPECT_LE(std::abs(stored - std::round(255 * truth[c])), 1.0) << "texel " << t;
    }
    EXPECT_EQ(tex.data[static_cast<size_t>(t) * 4 + 3], 255);
    painted += (truth - file.background).norm() > 0.05;
  }
  EXPECT_GT(painted, 500);  // the strokes cover a good part of the plane
}

TEST(Painter, PerStrokeMaxAndCompositingOrder) {
  const TriMesh mesh = shapes::plane(2);
  const Parameterization param = planar_param(mesh);
  const Vec3 c(0.5, 0.5, 0), red(1, 0, 0), blue(0, 0, 1);
  auto centre_colour = [&](const std::vector<Stroke>& strokes) {
    Painter p(mesh, param, {64, 64, 0});
    for (const Stroke& s : strokes) p.paint_stroke(s);
    const ImageRGBA8& tex = p.texture();
    return Vec3(tex.texel(32, 32)[0], tex.texel(32, 32)[1], tex.texel(32, 32)[2]);
  };
  const Stroke one = make_stroke(red, 0.2, 1.0, 0.5, {c});
  const Stroke twice = make_stroke(red, 0.2, 1.0, 0.5, {c, c, c + Vec3(0.01, 0, 0)});
  std::vector<Vec3> many(40, c);  // > 16 dabs: the parallel path
  const Stroke many_dabs = make_stroke(red, 0.2, 1.0, 0.5, many);
  const Vec3 half = centre_colour({one});
  EXPECT_EQ(half, Vec3(255, 128, 128));  // white * 0.5 + red * 0.5 = (1, .5, .5)
  EXPECT_EQ(centre_colour({twice}), half);
  EXPECT_EQ(centre_colour({many_dabs}), half);
  EXPECT_EQ(centre_colour({one, one}), Vec3(255, 64, 64));  // two strokes do build up: 0.25
  const Stroke r = make_stroke(red, 0.2, 1.0, 1.0, {c}), b = make_stroke(blue, 0.2, 1.0, 1.0, {c});
  EXPECT_EQ(centre_colour({r, b}), Vec3(0, 0, 255));
  EXPECT_EQ(centre_colour({b, r}), Vec3(255, 0, 0));
}

TEST(Painter, InteractiveEqualsWholeStrokeAndReportsTheTouchedRect) {
  const TriMesh mesh = shapes::plane(8);
  const Parameterization param = planar_param(mesh);
  const StrokeFile file = plane_strokes();
  Painter whole(mesh, param, {257, 190, 3}), live(mesh, param, {257, 190, 3});
  for (const Stroke& s : file.strokes) {
    whole.paint_stroke(s);
    live.begin_stroke(s);
    for (const Vec3& d : s.dabs) {
      const ImageRGBA8 before = live.texture();
      const auto rect = live.add_dab(d);
      const ImageRGBA8& after = live.texture();
      for (int j = 0; j < after.height; ++j)
        for (int i = 0; i < after.width; ++i)
          if (std::memcmp(before.texel(i, j), after.texel(i, j), 4) != 0) {
            ASSERT_TRUE(i >= rect[0] && i <= rect[2] && j >= rect[1] && j <= rect[3])
                << "texel " << i << "," << j << " changed outside the reported rect";
          }
    }
    live.end_stroke();
  }
  EXPECT_EQ(whole.texture().data, live.texture().data);
  EXPECT_GT(whole.texel_updates(), 0);
}

TEST(Painter, OutsideTheChartsIsBackgroundWithAlphaZeroUnlessPadded) {
  const TriMesh mesh = shapes::plane(4);
  const Parameterization param = planar_param(mesh, 0.5, 0.25);  // chart covers [0.25, 0.75]^2
  for (int P : {0, 2}) {
    Painter painter(mesh, param, {40, 40, P}, Vec3(0, 0.5, 1));
    painter.paint_stroke(make_stroke(Vec3(1, 0, 0), 0.3, 0.5, 1.0, {Vec3(0.2, 0.2, 0)}));
    const ImageRGBA8& tex = painter.texture();
    const TexelMap& map = painter.texel_map();
    for (int j = 0; j < 40; ++j)
      for (int i = 0; i < 40; ++i) {
        const bool in = map.face[map.index(i, j)] >= 0;
        EXPECT_EQ(in, i >= 10 && i < 30 && j >= 10 && j < 30);
        const bool padded = !in && i >= 10 - P && i < 30 + P && j >= 10 - P && j < 30 + P;
        if (in || padded) {
          EXPECT_EQ(tex.texel(i, j)[3], 255);
        } else {
          EXPECT_EQ(tex.texel(i, j)[0], 0);
          EXPECT_EQ(tex.texel(i, j)[1], 128);
          EXPECT_EQ(tex.texel(i, j)[2], 255);
          EXPECT_EQ(tex.texel(i, j)[3], 0);
        }
        if (padded) {  // a padded corner texel copies the chart's corner texel
          const int ci = std::clamp(i, 10, 29), cj = std::clamp(j, 10, 29);
          EXPECT_EQ(std::memcmp(tex.texel(i, j), tex.texel(ci, cj), 4), 0) << i << "," << j;
        }
      }
  }
}

TEST(Padding, SourcesAreNearestChartTexelsWithinP) {
  // An L-shaped chart region in a 30x30 mask.
  const int W = 30, H = 30, P = 4;
  std::vector<bool> inside(W * H, false);
  for (int j = 8; j < 22; ++j)
    for (int i = 8; i < 22; ++i)
      if (i < 14 || j < 14) inside[j * W + i] = true;
  const SeamPadding pad = build_seam_padding(inside, W, H, P);
  for (int t = 0; t < W * H; ++t) {
    const int i = t % W, j = t / W;
    int best = 1 << 30, cheb = 1 << 30;
    for (int s = 0; s < W * H; ++s)
      if (inside[s]) {
        const int di = s % W - i, dj = s / W - j;
        best = std::min(best, di * di + dj * dj);
        cheb = std::min(cheb, std::max(std::abs(di), std::abs(dj)));
      }
    if (inside[t] || cheb > P) {
      EXPECT_EQ(pad.source[t], -1) << i << "," << j;
      continue;
    }
    ASSERT_GE(pad.source[t], 0) << i << "," << j;
    EXPECT_TRUE(inside[pad.source[t]]);
    const int s = pad.source[t], di = s % W - i, dj = s / W - j;
    EXPECT_LE(std::max(std::abs(di), std::abs(dj)), P);
    EXPECT_LE(di * di + dj * dj, best + 2 * std::sqrt(double(best)) + 1) << "not (near) nearest";
  }
}

TEST(Padding, ReducesTheBilinearErrorAtChartBorders) {
  // Chart [0.1, 0.9]^2 in a 60^2 texture (borders on texel edges); the whole chart is painted dark.
  // Bilinear samples between the border and the first texel centres mix in the white background
  // unless the charts are padded.
  const TriMesh mesh = shapes::plane(4);
  const Parameterization param = planar_param(mesh, 0.8, 0.1);
  StrokeFile file;
  file.strokes.push_back(make_stroke(Vec3(0.2, 0.3, 0.4), 0.25, 0.2, 1.0,
                                     segment({0.0, 0.5}, {1.0, 0.5}, 0.05)));
  file.strokes.push_back(make_stroke(Vec3(0.1, 0.1, 0.5), 0.8, 1.0, 0.7, {Vec3(0.5, 0.5, 0)}));  // covers all
  const StrokeSignal signal(mesh, file);
  auto border_error = [&](int P) {
    Painter painter(mesh, param, {60, 60, P});
    painter.paint_all(file);
    const ImageRGBA8& tex = painter.texture();
    double sum = 0;
    int n = 0;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> U(0, 1);
    for (int k = 0; k < 4000; ++k) {
      // a point within half a texel (in uv) of the chart border
      const double along = U(rng), depth = U(rng) * (0.5 / 60) / 0.8;
      const int side = k % 4;
      Vec3 p = side == 0 ? Vec3(depth, along, 0) : side == 1 ? Vec3(1 - depth, along, 0)
             : side == 2 ? Vec3(along, depth, 0) : Vec3(along, 1 - depth, 0);
      const Vec3 rec = sample_bilinear(tex, 0.1 + 0.8 * p.x(), 0.1 + 0.8 * p.y());
      sum += (rec - signal.evaluate(p)).squaredNorm() / 3;
      ++n;
    }
    return sum / n;
  };
  const double without = border_error(0), with = border_error(4);
  RecordProperty("border_mse_without_padding", std::to_string(without));
  RecordProperty("border_mse_with_padding", std::to_string(with));
  EXPECT_GT(without, 0.01);
  EXPECT_LT(with, without / 20) << "with padding " << with << ", without " << without;
}

TEST(StrokeSignal, FastEqualsBruteForce) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(0, 1);
  StrokeFile file;
  file.background = Vec3(0.2, 0.4, 0.6);
  for (int s = 0; s < 30; ++s) {  // radii over 4 orders of magnitude: several grid levels
    const double r = 0.0005 * std::pow(10.0, 3.5 * U(rng));
    std::vector<Vec3> dabs;
    const Vec3 start(U(rng), U(rng), U(rng));
    for (int d = 0; d < 50; ++d) dabs.push_back(start + 0.3 * r * d * Vec3(1, 0.5, -0.2));
    file.strokes.push_back(make_stroke(Vec3(U(rng), U(rng), U(rng)), r, U(rng), U(rng), dabs));
  }
  const TriMesh dummy = shapes::plane(1);
  const StrokeSignal signal(dummy, file);
  int differs = 0;
  for (int k = 0; k < 20000; ++k) {
    // half of the points right next to dabs, half anywhere
    Vec3 p(U(rng), U(rng), U(rng));
    if (k % 2) {
      const Stroke& s = file.strokes[k % file.strokes.size()];
      p = s.dabs[k % s.dabs.size()] + s.radius * Vec3(U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5) * 2;
    }
    const Vec3 fast = signal.evaluate(p), slow = evaluate_strokes_reference(file, p);
    EXPECT_LT((fast - slow).norm(), 1e-12);
    differs += (slow - file.background).norm() > 1e-3;
  }
  EXPECT_GT(differs, 5000);
}

TEST(Eval, PsnrRisesWithTextureSizeAndExceeds45dBAt2048) {
  const TriMesh mesh = shapes::plane(8);
  const Parameterization param = planar_param(mesh);
  const StrokeFile file = plane_strokes();
  std::vector<double> psnr;
  for (int n : {128, 512, 2048}) {
    Painter painter(mesh, param, {n, n, 4});
    painter.paint_all(file);
    EvalOptions opt;
    opt.samples = 200000;
    opt.seed = 7;
    const EvalResult r = evaluate_texture(mesh, param, painter.texture(), file, opt);
    EXPECT_EQ(r.samples, 200000);
    EXPECT_NEAR(r.psnr, 10 * std::log10(1 / r.mse), 1e-9);
    psnr.push_back(r.psnr);
  }
  EXPECT_LT(psnr[0], psnr[1]);
  EXPECT_LT(psnr[1], psnr[2]);
  EXPECT_GT(psnr[2], 45.0) << psnr[0] << " " << psnr[1] << " " << psnr[2];
}

TEST(Eval, ProgressRisesToOneCancelsAndLeavesTheResultUnchanged) {
  const TriMesh mesh = shapes::plane(8);
  const Parameterization param = planar_param(mesh);
  const StrokeFile file = plane_strokes();
  Painter painter(mesh, param, {64, 64, 4});
  painter.paint_all(file);
  EvalOptions opt;
  opt.samples = 300000;
  const EvalResult quiet = evaluate_texture(mesh, param, painter.texture(), file, opt);
  std::vector<double> seen;
  opt.progress = [&](std::string_view phase, double f) {
    EXPECT_EQ(phase, "eval");
    seen.push_back(f);
    return true;
  };
  const EvalResult reported = evaluate_texture(mesh, param, painter.texture(), file, opt);
  EXPECT_EQ(reported.mse, quiet.mse);  // bit-identical: the same block sums in the same order
  ASSERT_GT(seen.size(), 10u);
  EXPECT_EQ(seen.front(), 0.0);
  EXPECT_EQ(seen.back(), 1.0);
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  int calls = 0;
  opt.progress = [&](std::string_view, double f) { return ++calls, f < 0.5; };
  EXPECT_THROW(evaluate_texture(mesh, param, painter.texture(), file, opt), CancelledError);
  EXPECT_LT(calls, static_cast<int>(seen.size()));
}

TEST(Eval, SamplesAreUniformByAreaAndReproducible) {
  // Two triangles of area 3/4 and 1/4: the samples split 3:1.
  TriMesh m;
  m.positions = {{0, 0, 0}, {3, 0, 0}, {0, 0.5, 0}, {3, 0.5, 0}, {4, 0.5, 0}};
  m.faces = {{0, 1, 2}, {1, 4, 3}};
  const auto a = sample_surface(m, 100000, 42), b = sample_surface(m, 100000, 42), c = sample_surface(m, 100000, 43);
  int first = 0;
  for (size_t k = 0; k < a.size(); ++k) {
    first += a[k].face == 0;
    EXPECT_EQ(a[k].face, b[k].face);
    EXPECT_EQ(a[k].b0, b[k].b0);
    EXPECT_GE(a[k].b0, 0);
    EXPECT_GE(a[k].b1, 0);
    EXPECT_LE(a[k].b0 + a[k].b1, 1);
  }
  EXPECT_NEAR(first / 100000.0, 0.75 / (0.75 + 0.25), 0.01);
  int same = 0;
  for (size_t k = 0; k < a.size(); ++k) same += a[k].b0 == c[k].b0;
  EXPECT_LT(same, 10);
}

TEST(Painter, DecalStrokesMatchTheSignalAtTexelCentres) {
  const TriMesh mesh = shapes::plane(8);
  const Parameterization param = planar_param(mesh);
  StrokeFile file = plane_strokes();
  Stroke decal;
  decal.type = Stroke::Type::Decal;
  decal.image = ImageRGBA8(4, 4);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      std::uint8_t* px = decal.image.texel(i, j);
      px[0] = static_cast<std::uint8_t>(60 * i);
      px[1] = static_cast<std::uint8_t>(60 * j);
      px[2] = 200;
      px[3] = static_cast<std::uint8_t>((i + j) % 3 == 0 ? 0 : 255);
    }
  decal.camera.eye = Vec3(0.4, 0.5, 2.0);
  decal.camera.target = Vec3(0.4, 0.5, 0.0);
  decal.camera.fov_y_degrees = 20;
  decal.opacity = 0.8;
  file.strokes.insert(file.strokes.begin() + 2, decal);  // between brush strokes
  Painter painter(mesh, param, {128, 128, 2});
  painter.paint_all(file);
  const StrokeSignal signal(mesh, file);
  ASSERT_TRUE(signal.has_decals());
  const ImageRGBA8& tex = painter.texture();
  const TexelMap& map = painter.texel_map();
  int decal_texels = 0;
  for (int t : map.inside) {
    const Vec3 truth = signal.evaluate(map.position[t].cast<double>(), map.face[t]);
    for (int c = 0; c < 3; ++c)
      EXPECT_LE(std::abs(tex.data[static_cast<size_t>(t) * 4 + c] - std::round(255 * truth[c])), 1.0) << t;
    const Vec3 without = evaluate_strokes_reference(plane_strokes(), map.position[t].cast<double>());
    decal_texels += (truth - without).norm() > 0.1;
  }
  EXPECT_GT(decal_texels, 500);  // the decal really changed a region
}
