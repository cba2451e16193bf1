// Error-model density (error_density.h): the history signal cached per layout (ErrorDensityReference)
// gives the same density as evaluating the whole history, stroke after stroke; the uncached path, which
// evaluates the history only where a dab may reach, gives the same rasters as the cache, which
// composites every stroke at every texel.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "adaptex/adapt/error_density.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/paint/generate.h"
#include "adaptex/paint/material_paint.h"
#include "adaptex/paint/painter.h"
#include "adaptex/paint/signal.h"
#include "adaptex/param/unwrap.h"
#include "test_scene.h"

namespace adaptex {
namespace {

/// A mesh and how many generated strokes of which kind to paint on it.
struct Case {
  TriMesh mesh;
  StrokeKind kind;
  int count;
};

TEST(ErrorDensity, CachedHistoryGivesTheSameDensityAfterEveryStroke) {
  const test::Scene sc = test::torus_scene(48, 24, StrokeKind::Mixed, 6);
  const TriMesh& mesh = sc.mesh;
  const Parameterization& param = sc.param;
  const StrokeFile& all = sc.strokes;
  ASSERT_EQ(all.strokes.size(), 6u);
  const int N = 64;
  Painter painter(mesh, param, PainterOptions{N, N, 4}, all.background);
  ErrorDensityReference reference(mesh, param, N, all.background);
  StrokeFile history;
  history.background = all.background;
  for (const Stroke& s : all.strokes) {
    history.strokes.push_back(s);
    painter.paint_stroke(s);
    const ErrorDensity full = compute_error_density(mesh, param, painter.texture(), painter.texel_map(), history);
    const ErrorDensity cached =
        compute_error_density(mesh, param, painter.texture(), painter.texel_map(), history, reference);
    ASSERT_EQ(full.density.data.size(), cached.density.data.size());
    double worst = 0;
    for (size_t k = 0; k < full.density.data.size(); ++k)
      worst = std::max(worst, std::abs(double(full.density.data[k]) - cached.density.data[k]));
    EXPECT_LT(worst, 1e-4) << "after stroke " << history.strokes.size();
    EXPECT_NEAR(full.predicted_gain_db, cached.predicted_gain_db, 1e-6);
    EXPECT_EQ(full.reference_size, cached.reference_size);
  }
  EXPECT_GT(compute_error_density(mesh, param, painter.texture(), painter.texel_map(), history).predicted_gain_db, 0.5);
}

TEST(ErrorDensity, AReferenceReusedStrokeAfterStrokeSumsOnlyTheChangedRowsAndGivesTheSameBits) {
  // A reference used after every stroke keeps its last rasters and cell sums and sums again only the
  // cell rows whose inputs changed. A fresh reference (every row summed) must give the same bits, on
  // a one-chart torus and on a multi-chart genus-3 surface, with local strokes (lines, dots) and broad
  // ones (blobs), including strokes that repeat (nothing changes) and a texture with padding.
  const std::vector<Case> cases{{shapes::torus(48, 24), StrokeKind::Mixed, 10},
                                {shapes::genus_surface(3, 6), StrokeKind::Dots, 12}};
  for (const Case& cs : cases) {
    const Parameterization param = unwrap(cs.mesh).param;
    GenerateOptions go;
    go.kind = cs.kind;
    go.count = cs.count;
    go.seed = 4;
    StrokeFile all = generate_strokes(cs.mesh, go);
    all.strokes.push_back(all.strokes[2]);  // a repeat: changes nothing in the signal if opaque and hard
    const int N = 128;
    Painter painter(cs.mesh, param, PainterOptions{N, N, 4}, all.background);
    ErrorDensityReference reused(cs.mesh, param, N, all.background);
    StrokeFile history;
    history.background = all.background;
    for (const Stroke& s : all.strokes) {
      history.strokes.push_back(s);
      painter.paint_stroke(s);
      ErrorDensityReference fresh(cs.mesh, param, N, all.background);
      const ErrorDensity a = compute_error_density(cs.mesh, param, painter.texture(), painter.texel_map(), history, reused);
      const ErrorDensity b = compute_error_density(cs.mesh, param, painter.texture(), painter.texel_map(), history, fresh);
      EXPECT_EQ(a.density.data, b.density.data) << "after stroke " << history.strokes.size();
      EXPECT_EQ(a.error.data, b.error.data) << "after stroke " << history.strokes.size();
      EXPECT_EQ(a.exponent.data, b.exponent.data) << "after stroke " << history.strokes.size();
      EXPECT_EQ(a.predicted_gain_db, b.predicted_gain_db);
    }
    EXPECT_GT(compute_error_density(cs.mesh, param, painter.texture(), painter.texel_map(), history, reused)
                  .predicted_gain_db,
              0.1);
  }
}

TEST(ErrorDensity, PlanesWithAMemoryGiveTheSameBitsAsAfreshAfterEveryStroke) {
  // ErrorPlanesMemory keeps each plane's rasters and cell sums and sums again only the changed cell
  // rows: after every stroke (and a repeated one), the same bits as without it, with two planes of
  // different weights, and again when the number of planes changes (the memory starts afresh).
  const test::Scene sc = test::torus_scene(48, 24, StrokeKind::Mixed, 8);
  const TriMesh& mesh = sc.mesh;
  const Parameterization& param = sc.param;
  StrokeFile all = sc.strokes;
  all.strokes.push_back(all.strokes[1]);
  const int N = 64;
  Painter painter(mesh, param, PainterOptions{N, N, 4}, all.background);
  const ErrorPlaneMaps maps = error_plane_maps(mesh, param, N);
  StrokeFile history;
  history.background = all.background;
  std::vector<Vec3f> out;  // the planes' values, valid until the next call (as ErrorPlane::exact's)
  auto exact = [&](const TexelMap& at, bool invert) -> const std::vector<Vec3f>& {
    out.assign(static_cast<size_t>(at.width) * at.height, Vec3f::Zero());
    const std::vector<SurfacePoint> pts = texel_points(at);
    for (size_t k = 0; k < pts.size(); ++k) {
      const Face& f = mesh.faces[pts[k].face];
      const Vec3 p = pts[k].b0 * mesh.positions[f[0]] + pts[k].b1 * mesh.positions[f[1]] +
                     (1 - pts[k].b0 - pts[k].b1) * mesh.positions[f[2]];
      const Vec3 c = evaluate_strokes_reference(history, p);
      out[at.inside[k]] = (invert ? Vec3(Vec3::Ones() - c) : c).cast<float>();
    }
    return out;
  };
  ErrorPlanesMemory memory;
  for (const Stroke& s : all.strokes) {
    history.strokes.push_back(s);
    painter.paint_stroke(s);
    std::vector<ErrorPlane> planes(2);
    planes[0].texture = painter.texture();
    planes[0].exact = [&](const TexelMap& at) -> const std::vector<Vec3f>& { return exact(at, false); };
    planes[1].weight = 0.3;
    planes[1].texture = painter.texture();
    planes[1].exact = [&](const TexelMap& at) -> const std::vector<Vec3f>& { return exact(at, true); };
    if (history.strokes.size() == 5) planes.pop_back();
    const ErrorDensity a = compute_error_density(mesh, param, painter.texel_map(), planes, maps, memory);
    const ErrorDensity b = compute_error_density(mesh, param, painter.texel_map(), planes, maps);
    EXPECT_EQ(a.density.data, b.density.data) << "after stroke " << history.strokes.size();
    EXPECT_EQ(a.error.data, b.error.data) << "after stroke " << history.strokes.size();
    EXPECT_EQ(a.exponent.data, b.exponent.data) << "after stroke " << history.strokes.size();
    EXPECT_EQ(a.predicted_gain_db, b.predicted_gain_db);
  }
  EXPECT_GT(compute_error_density(mesh, param, painter.texture(), painter.texel_map(), history).predicted_gain_db, 0.1);
}

// The uncached path skips texels that no dab can reach (their signal is the background); the cache
// evaluates every texel. Both must give the same rasters, bit for bit, on local strokes (lines, dots),
// broad ones (blobs) and both (mixed), on a one-chart torus and a multi-chart genus-3 surface.
TEST(ErrorDensity, SkippingUnreachedTexelsChangesNothing) {
  const std::vector<Case> cases{{shapes::torus(48, 24), StrokeKind::Lines, 12},
                                {shapes::torus(48, 24), StrokeKind::Dots, 60},
                                {shapes::torus(48, 24), StrokeKind::Blobs, 3},
                                {shapes::genus_surface(3, 6), StrokeKind::Mixed, 16},
                                {shapes::genus_surface(3, 6), StrokeKind::Dots, 80}};
  for (const Case& cs : cases) {
    const Parameterization param = unwrap(cs.mesh).param;
    GenerateOptions go;
    go.kind = cs.kind;
    go.count = cs.count;
    const StrokeFile history = generate_strokes(cs.mesh, go);
    const int N = 96;
    Painter painter(cs.mesh, param, PainterOptions{N, N, 4}, history.background);
    for (const Stroke& s : history.strokes) painter.paint_stroke(s);
    const ErrorDensity fast = compute_error_density(cs.mesh, param, painter.texture(), painter.texel_map(), history);
    ErrorDensityReference reference(cs.mesh, param, N, history.background);
    const ErrorDensity every =
        compute_error_density(cs.mesh, param, painter.texture(), painter.texel_map(), history, reference);
    const std::string what = "kind " + std::to_string(static_cast<int>(cs.kind)) + ", " +
                             std::to_string(cs.mesh.num_faces()) + " faces";
    ASSERT_EQ(fast.density.data.size(), every.density.data.size()) << what;
    EXPECT_EQ(fast.density.data, every.density.data) << what;
    EXPECT_EQ(fast.error.data, every.error.data) << what;
    EXPECT_EQ(fast.exponent.data, every.exponent.data) << what;
    EXPECT_EQ(fast.predicted_gain_db, every.predicted_gain_db) << what;
    EXPECT_EQ(fast.signal_fraction, every.signal_fraction) << what;
    EXPECT_GT(fast.predicted_gain_db, 0.1) << what;  // the strokes were seen
    // Not vacuous: part of the surface is unpainted (the skip applies), part is painted.
    EXPECT_GT(fast.signal_fraction, 0.0) << what;
    const StrokeSignal signal(cs.mesh, history);
    int untouched = 0;
    for (int f = 0; f < cs.mesh.num_faces(); ++f) untouched += signal.evaluate(SurfacePoint{f, 0.3, 0.3}) == history.background;
    EXPECT_GT(untouched, 0) << what;
  }
}

// ErrorDensityOptions::quarter_texel_reference: where N >= 4·cells the reference points are the
// texture's own grid shifted by a quarter texel. They sample the two levels' errors at the distances
// of the 2N raster, so the density must match the 2N raster's closely; a wrong shift (points on the
// texture's texel centres, where the stored texture is exact) would lose the hard edges' error. The
// cache and the uncached path must agree on it as on the 2N raster.
TEST(ErrorDensity, QuarterTexelReferenceMatchesTheTwiceFinerRaster) {
  for (const StrokeKind kind : {StrokeKind::Lines, StrokeKind::Dots}) {
    const TriMesh mesh = shapes::torus(48, 24);
    const Parameterization param = unwrap(mesh).param;
    GenerateOptions go;
    go.kind = kind;
    go.count = kind == StrokeKind::Dots ? 60 : 12;
    const StrokeFile history = generate_strokes(mesh, go);
    const int N = 256;
    Painter painter(mesh, param, PainterOptions{N, N, 4}, history.background);
    for (const Stroke& s : history.strokes) painter.paint_stroke(s);
    ErrorDensityOptions quarter, fine;
    quarter.cells = fine.cells = 64;  // N = 4·cells: the shifted grid applies
    fine.quarter_texel_reference = false;
    const ErrorDensity q = compute_error_density(mesh, param, painter.texture(), painter.texel_map(), history, quarter);
    const ErrorDensity f = compute_error_density(mesh, param, painter.texture(), painter.texel_map(), history, fine);
    const std::string what = kind == StrokeKind::Dots ? "dots" : "lines";
    EXPECT_EQ(q.reference_size, N) << what;
    EXPECT_EQ(f.reference_size, 2 * N) << what;
    ASSERT_EQ(q.density.data.size(), f.density.data.size()) << what;
    ASSERT_GT(f.predicted_gain_db, 1.0) << what;
    // Measured: lines 4.11 against 4.19 dB, dots 2.94 against 2.59 (points on the texel centres
    // instead: 13.1 and 9.0).
    EXPECT_NEAR(q.predicted_gain_db, f.predicted_gain_db, 0.2 * f.predicted_gain_db) << what;
    // The densities agree cell by cell: correlation of log ρ over the square.
    double sq = 0, sf = 0, sqq = 0, sff = 0, sqf = 0;
    const double n = static_cast<double>(q.density.data.size());
    for (size_t k = 0; k < q.density.data.size(); ++k) {
      const double a = std::log(q.density.data[k]), b = std::log(f.density.data[k]);
      sq += a, sf += b, sqq += a * a, sff += b * b, sqf += a * b;
    }
    const double cov = sqf / n - sq * sf / (n * n);
    const double corr = cov / std::sqrt((sqq / n - sq * sq / (n * n)) * (sff / n - sf * sf / (n * n)));
    EXPECT_GT(corr, 0.95) << what;
    ErrorDensityReference reference(mesh, param, N, history.background, quarter);
    const ErrorDensity cached =
        compute_error_density(mesh, param, painter.texture(), painter.texel_map(), history, reference, quarter);
    EXPECT_EQ(cached.density.data, q.density.data) << what;
    EXPECT_EQ(cached.reference_size, N) << what;
    EXPECT_FALSE(reference.matches(mesh, param, N, fine)) << what;  // another grid: refused
  }
}

TEST(ErrorDensity, ReferenceOfAnotherLayoutOrSizeIsRefused) {
  const TriMesh mesh = shapes::torus(32, 16);
  const Parameterization param = unwrap(mesh).param;
  Parameterization moved = param;
  moved.uv[0] *= 0.999;
  ErrorDensityReference reference(mesh, param, 64, Vec3(1, 1, 1));
  EXPECT_TRUE(reference.matches(mesh, param, 64, {}));
  EXPECT_FALSE(reference.matches(mesh, param, 128, {}));
  EXPECT_FALSE(reference.matches(mesh, moved, 64, {}));
  StrokeFile history;
  Painter painter(mesh, moved, PainterOptions{64, 64, 4}, Vec3(1, 1, 1));
  EXPECT_THROW(compute_error_density(mesh, moved, painter.texture(), painter.texel_map(), history, reference),
               InvalidInputError);
  EXPECT_THROW(ErrorDensityReference(mesh, param, 0, Vec3(1, 1, 1)), InvalidInputError);
}

TEST(ErrorDensity, PredictedErrorIsTheModelsSumAtAGivenDensity) {
  // A 2 x 2 model: an edge cell (p = 1), a smooth cell (p = 4), an unpainted cell and a gutter.
  ErrorDensity m;
  m.error = ImageF(2, 2, 0.0f);
  m.exponent = ImageF(2, 2, 0.0f);
  m.error.data = {0.5f, 0.25f, 0.0f, 0.0f};
  m.exponent.data = {1.0f, 4.0f, 0.0f, 0.0f};
  EXPECT_DOUBLE_EQ(predicted_error(m, ImageF{}), 0.75);  // the layout the model was computed on
  ImageF d(2, 2, 1.0f);
  d.data = {4.0f, 2.0f, 0.5f, 0.5f};
  // 0.5 · 4^(−1/2) + 0.25 · 2^(−2); the unpainted cells add nothing at any density.
  EXPECT_DOUBLE_EQ(predicted_error(m, d), 0.5 * 0.5 + 0.25 * 0.25);
  d.data[1] = 0.0f;
  EXPECT_THROW(predicted_error(m, d), InvalidInputError);  // a painted cell with no area
  d.data[1] = std::nanf("");
  EXPECT_THROW(predicted_error(m, d), InvalidInputError);
  EXPECT_THROW(predicted_error(m, ImageF(3, 3, 1.0f)), InvalidInputError);
}

TEST(ErrorDensity, TheModelsDensityPredictsLessErrorThanTheLayoutItCameFrom) {
  const test::Scene sc = test::torus_scene(48, 24, StrokeKind::Mixed, 6);
  const int N = 64;
  Painter painter(sc.mesh, sc.param, PainterOptions{N, N, 4}, sc.strokes.background);
  painter.paint_all(sc.strokes);
  const ErrorDensity m = compute_error_density(sc.mesh, sc.param, painter.texture(), painter.texel_map(), sc.strokes);
  const double held = predicted_error(m, ImageF{}), best = predicted_error(m, m.density);
  ASSERT_GT(best, 0);
  const double gain = 10 * std::log10(held / best);
  // The same gain the model reports (which it sums before the gutters get their share and the
  // density is scaled to mean 1: close, not equal).
  EXPECT_GT(gain, 0.5);
  EXPECT_NEAR(gain, m.predicted_gain_db, 0.25 * m.predicted_gain_db);
}

}  // namespace
}  // namespace adaptex
