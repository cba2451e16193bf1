// PointSignalCache (paint/signal.h): stroke-by-stroke exact signal at fixed surface points equals
// StrokeSignal over the whole history, at every step, on a mesh built in code.
#include <gtest/gtest.h>

#include <algorithm>

#include "adaptex/core/errors.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/shapes.h"
#include "adaptex/paint/eval.h"
#include "adaptex/paint/generate.h"
#include "adaptex/paint/signal.h"

namespace adaptex {
namespace {

double max_abs_diff(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double m = 0;
  for (size_t k = 0; k < a.size(); ++k) m = std::max(m, (a[k] - b[k]).cwiseAbs().maxCoeff());
  return m;
}

TEST(PointSignalCache, EqualsTheWholeHistoryAfterEveryStroke) {
  const TriMesh mesh = shapes::torus(48, 24);
  GenerateOptions go;
  go.kind = StrokeKind::Mixed;
  go.count = 24;
  go.seed = 5;
  go.background = Vec3(0.9, 0.8, 0.7);
  const StrokeFile all = generate_strokes(mesh, go);
  const std::vector<SurfacePoint> pts = sample_surface(mesh, 20000, 7);
  PointSignalCache cache(mesh, pts, all.background);
  StrokeFile prefix;
  prefix.background = all.background;
  for (const Stroke& s : all.strokes) {
    cache.add_stroke(s);
    prefix.strokes.push_back(s);
    const std::vector<Vec3> exact = StrokeSignal(mesh, prefix).evaluate(pts);
    EXPECT_LE(max_abs_diff(cache.values(), exact), 1e-12) << "after stroke " << prefix.strokes.size();
  }
  EXPECT_EQ(cache.strokes(), 24);
  EXPECT_FALSE(cache.has_decals());
  // Not vacuous: the strokes changed a good share of the points.
  const long changed = std::count_if(cache.values().begin(), cache.values().end(),
                                     [&](const Vec3& v) { return (v - all.background).norm() > 0.05; });
  EXPECT_GT(changed, 2000);
}

// A hard brush paints a point at full opacity right up to its radius, so a point a hair inside the
// radius must be painted and one a hair outside must not: the spatial index (which compares in float)
// may not drop either, also where the mesh lies far from the origin and the brush is small.
TEST(PointSignalCache, HardBrushEdgeIsExactAtEveryScale) {
  for (const Vec3& offset : {Vec3(0, 0, 0), Vec3(1000, -500, 300)}) {
    TriMesh mesh = shapes::icosphere(4);
    for (Vec3& v : mesh.positions) v += offset;
    const std::vector<SurfacePoint> pts = sample_surface(mesh, 4000, 11);
    std::vector<Vec3> pos;
    for (const SurfacePoint& sp : pts) pos.push_back(point_on_face(mesh, sp.face, sp.b0, sp.b1));
    for (size_t target : {size_t(7), size_t(1234), size_t(3999)})
      for (double scale : {0.002, 0.02, 0.3, 5.0}) {  // the dab's distance to the target point
        for (double edge : {1 + 1e-9, 1 - 1e-9}) {
          const Vec3 dir = Vec3(0.3, -0.5, 0.8).normalized();
          Stroke s;
          s.color = Vec3(1, 0, 0);
          s.hardness = 1;
          s.opacity = 1;
          s.dabs = {pos[target] + scale * dir};
          s.radius = scale * edge;
          StrokeFile one;
          one.background = Vec3(0, 0, 1);
          one.strokes = {s};
          PointSignalCache cache(mesh, pts, one.background);
          cache.add_stroke(s);
          for (size_t k = 0; k < pts.size(); ++k) ASSERT_EQ(cache.values()[k], evaluate_strokes_reference(one, pos[k])) << k;
          EXPECT_EQ(cache.values()[target], edge > 1 ? s.color : one.background)
              << "offset " << offset.transpose() << ", point " << target << ", scale " << scale;
        }
      }
  }
}

TEST(PointSignalCache, UpdateAddsOnlyTheNewStrokes) {
  const TriMesh mesh = shapes::icosphere(4);
  GenerateOptions go;
  go.kind = StrokeKind::Lines;
  go.count = 12;
  StrokeFile history = generate_strokes(mesh, go);
  const std::vector<SurfacePoint> pts = sample_surface(mesh, 5000, 3);
  PointSignalCache cache(mesh, pts, history.background);
  StrokeFile part = history;
  part.strokes.resize(5);
  cache.update(part);
  EXPECT_EQ(cache.strokes(), 5);
  cache.update(history);
  EXPECT_EQ(cache.strokes(), 12);
  EXPECT_LE(max_abs_diff(cache.values(), StrokeSignal(mesh, history).evaluate(pts)), 1e-12);
}

TEST(PointSignalCache, RejectsPointsOffTheMeshAndBadStrokes) {
  const TriMesh mesh = shapes::icosphere(2);
  EXPECT_THROW(PointSignalCache(mesh, {SurfacePoint{mesh.num_faces(), 0.3, 0.3}}, Vec3(1, 1, 1)), InvalidInputError);
  PointSignalCache cache(mesh, sample_surface(mesh, 100, 1), Vec3(1, 1, 1));
  Stroke bad;
  bad.radius = -1;
  bad.dabs = {Vec3(0, 0, 1)};
  EXPECT_THROW(cache.add_stroke(bad), InvalidInputError);
  EXPECT_EQ(cache.strokes(), 0);
}

}  // namespace
}  // namespace adaptex
