// PaintSession's safeguard reads the exact signal from a stroke-by-stroke cache (PointSignalCache,
// issue 10): its error estimates equal the ones computed from the whole history.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "adaptex/adapt/session.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/paint/eval.h"
#include "adaptex/paint/generate.h"
#include "adaptex/paint/signal.h"
#include "adaptex/param/unwrap.h"
#include "test_scene.h"

namespace adaptex {
namespace {

using test::Scene;

/// A torus of (major x minor) segments, its unwrap() layout and \p count mixed strokes (seed 11).
Scene torus_scene(int major, int minor, int count) { return test::torus_scene(major, minor, StrokeKind::Mixed, count, 11); }

/// Reconstruction MSE of \p texture on \p param against the whole history, evaluated afresh.
double exact_mse(const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& texture,
                 const StrokeFile& history, const PaintSessionOptions& o) {
  const std::vector<SurfacePoint> pts = sample_surface(mesh, o.safeguard_samples, o.safeguard_seed);
  return reconstruction_mse(param, texture, pts, StrokeSignal(mesh, history).evaluate(pts));
}

/// 128² texture, 8,000 safeguard samples, the given schedule and method.
PaintSessionOptions small_options(ReparamSchedule schedule, AdaptMode mode) {
  PaintSessionOptions o;
  o.texture_size = 128;
  o.safeguard_samples = 8000;
  o.schedule = schedule;
  o.adapt.mode = mode;
  return o;
}

TEST(PaintSessionCache, EstimateErrorEqualsTheWholeHistoryAfterEveryStroke) {
  const Scene sc = torus_scene(40, 20, 16);
  const TriMesh& mesh = sc.mesh;
  const Parameterization& param = sc.param;
  const StrokeFile& strokes = sc.strokes;
  const PaintSessionOptions o = small_options(ReparamSchedule::End, AdaptMode::None);
  PaintSession s(mesh, param, o, strokes.background);
  for (const Stroke& st : strokes.strokes) {
    s.add_stroke(st);
    const double want = exact_mse(mesh, s.param(), s.texture(), s.history(), o);
    EXPECT_GT(want, 0);
    EXPECT_NEAR(s.estimate_error(), want, 1e-12 * want) << "stroke " << s.history().strokes.size();
  }
}

TEST(PaintSessionCache, EachStrokeReferenceErrorEqualsTheWholeHistory) {
  const Scene sc = torus_scene(40, 20, 12);
  const TriMesh& mesh = sc.mesh;
  const Parameterization& param = sc.param;
  const StrokeFile& strokes = sc.strokes;
  PaintSessionOptions o = small_options(ReparamSchedule::EachStroke, AdaptOptions{}.mode);
  o.min_gain_db = 0;  // a safeguard run after every stroke
  PaintSession s(mesh, param, o, strokes.background);
  PainterOptions po;
  po.width = po.height = o.texture_size;
  po.padding = o.padding;
  Painter initial(mesh, param, po, strokes.background);  // the reference: the initial layout, replayed
  int checked = 0;
  for (const Stroke& st : strokes.strokes) {
    s.add_stroke(st);
    initial.paint_stroke(st);
    const AdaptReport& r = s.reports().back();
    if (r.error_before == 0) continue;  // the method declined the cycle: no safeguard ran
    const double want = exact_mse(mesh, param, initial.texture(), s.history(), o);
    EXPECT_NEAR(r.error_before, want, 1e-12 * want) << "stroke " << s.history().strokes.size();
    ++checked;
  }
  EXPECT_GE(checked, 6);
}

/// Reconstruction PSNR of a session's texture against the exact signal of its history.
double session_psnr(PaintSession& s) {
  const std::vector<SurfacePoint> pts = sample_surface(s.mesh(), 100000, 21);
  const double mse = reconstruction_mse(s.param(), s.texture(), pts, StrokeSignal(s.mesh(), s.history()).evaluate(pts));
  return 10 * std::log10(1.0 / mse);
}

TEST(PaintSessionCache, SurfaceCacheEachStrokeIsEndModeForTheHistorySoFar) {
  const Scene sc = torus_scene(40, 20, 6);
  PaintSessionOptions each = small_options(ReparamSchedule::EachStroke, AdaptOptions{}.mode);
  each.surface_cache = 3;
  each.min_gain_db = 0;  // a cycle after every stroke
  PaintSessionOptions end = each;
  end.schedule = ReparamSchedule::End;
  PaintSession s(sc.mesh, sc.param, each, sc.strokes.background);
  int accepted = 0;
  for (size_t k = 0; k < sc.strokes.strokes.size(); ++k) {
    s.add_stroke(sc.strokes.strokes[k]);
    PaintSession e(sc.mesh, sc.param, end, sc.strokes.background);
    for (size_t i = 0; i <= k; ++i) e.add_stroke(sc.strokes.strokes[i]);
    e.finish();
    EXPECT_EQ(s.mesh().num_faces(), e.mesh().num_faces()) << "stroke " << k + 1;
    EXPECT_EQ(s.param().uv, e.param().uv) << "stroke " << k + 1;
    EXPECT_EQ(s.texture().data, e.texture().data) << "stroke " << k + 1;
    accepted += s.reports().back().accepted;
  }
  // Not vacuous: some candidates were taken (else both sessions just hold the initial layout).
  EXPECT_GT(accepted, 0);
}

TEST(PaintSessionCache, SurfaceCacheQualityIsWithinAFewTenthsOfADecibelOfExactReplay) {
  const Scene sc = torus_scene(48, 24, 30);
  PaintSessionOptions o = small_options(ReparamSchedule::End, AdaptOptions{}.mode);
  o.texture_size = 256;
  o.safeguard_samples = 20000;
  PaintSession exact(sc.mesh, sc.param, o, sc.strokes.background);
  o.surface_cache = 3;
  PaintSession cached(sc.mesh, sc.param, o, sc.strokes.background);
  for (const Stroke& st : sc.strokes.strokes) {
    exact.add_stroke(st);
    cached.add_stroke(st);
  }
  exact.finish();
  cached.finish();
  const double pe = session_psnr(exact), pc = session_psnr(cached);
  std::printf("end mode PSNR: exact replay %.2f dB, surface cache %.2f dB\n", pe, pc);
  // Not vacuous: the cached session adapted and its texture is the cache's, not a replay.
  ASSERT_TRUE(cached.reports().back().accepted);
  EXPECT_NE(cached.texture().data, exact.texture().data);
  EXPECT_GT(pc, pe - 0.3);
  EXPECT_LT(pc, pe + 1.0);
}

TEST(PaintSessionCache, RejectsBadCacheOptionsAtConstruction) {
  const TriMesh mesh = shapes::icosphere(2);
  const Parameterization param = unwrap(mesh).param;
  for (double q : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    PaintSessionOptions o;
    o.surface_cache = q;
    EXPECT_THROW(PaintSession(mesh, param, o), InvalidInputError) << q;
  }
  // A lattice past kMaxSurfaceCacheSamples (~1e4 samples per texel spacing) fails before any stroke.
  PaintSessionOptions big;
  big.surface_cache = 1e4;
  EXPECT_THROW(PaintSession(mesh, param, big), InvalidInputError);
  for (int n : {-1, kMaxSafeguardSamples + 1}) {
    PaintSessionOptions o;
    o.safeguard_samples = n;
    EXPECT_THROW(PaintSession(mesh, param, o), InvalidInputError) << n;
  }
  // The largest accepted values construct (the samples are drawn at the first stroke, not here).
  PaintSessionOptions ok;
  ok.safeguard_samples = kMaxSafeguardSamples;
  ok.surface_cache = 3;
  ok.texture_size = 64;
  EXPECT_NO_THROW(PaintSession(mesh, param, ok));
}

}  // namespace
}  // namespace adaptex
