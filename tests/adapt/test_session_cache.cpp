// PaintSession's safeguard reads the exact signal from a stroke-by-stroke cache (PointSignalCache,
// issue 10): its error estimates equal the ones computed from the whole history.
#include <gtest/gtest.h>

#include <cmath>

#include "adaptex/adapt/session.h"
#include "adaptex/core/shapes.h"
#include "adaptex/paint/eval.h"
#include "adaptex/paint/generate.h"
#include "adaptex/paint/signal.h"
#include "adaptex/param/unwrap.h"

namespace adaptex {
namespace {

StrokeFile mixed(const TriMesh& mesh, int count) {
  GenerateOptions go;
  go.kind = StrokeKind::Mixed;
  go.count = count;
  go.seed = 11;
  return generate_strokes(mesh, go);
}

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
  const TriMesh mesh = shapes::torus(40, 20);
  const Parameterization param = unwrap(mesh).param;
  const StrokeFile strokes = mixed(mesh, 16);
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
  const TriMesh mesh = shapes::torus(40, 20);
  const Parameterization param = unwrap(mesh).param;
  const StrokeFile strokes = mixed(mesh, 12);
  const PaintSessionOptions o = small_options(ReparamSchedule::EachStroke, AdaptOptions{}.mode);
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

}  // namespace
}  // namespace adaptex
