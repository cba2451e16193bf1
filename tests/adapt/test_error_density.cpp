// Error-model density (error_density.h): the history signal cached per layout (ErrorDensityReference)
// gives the same density as evaluating the whole history, stroke after stroke.
#include <gtest/gtest.h>

#include "adaptex/adapt/error_density.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/paint/generate.h"
#include "adaptex/paint/painter.h"
#include "adaptex/param/unwrap.h"
#include "test_scene.h"

namespace adaptex {
namespace {

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

}  // namespace
}  // namespace adaptex
