// Free-boundary, locally injective SLIM layouts (param/slim.h): the layout the scan charts try after
// their square and LSCM layouts (issue 35).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/param/slim.h"
#include "adaptex/param/stretch.h"

namespace adaptex {
namespace {

/// An n × n grid over [0, 2] × [0, 1] rolled onto a cylinder of radius 1 (developable: an
/// isometric layout exists) and its isometric layout.
struct Rolled {
  TriMesh mesh;
  std::vector<Vec2> flat;
};

Rolled rolled_sheet(int n) {
  Rolled r;
  r.mesh = shapes::plane(n, 1.0);
  r.flat.resize(r.mesh.positions.size());
  for (size_t v = 0; v < r.mesh.positions.size(); ++v) {
    const Vec3 p = r.mesh.positions[v];
    const double s = 2.0 * p.x(), t = p.y();  // plane(n, 1) spans [0, 1]²
    r.flat[v] = Vec2(s, t);
    r.mesh.positions[v] = Vec3(std::sin(s), t, 1.0 - std::cos(s));
  }
  return r;
}

double signed_area(const std::vector<Vec2>& uv, const Face& t) {
  const Vec2 a = uv[t[1]] - uv[t[0]], b = uv[t[2]] - uv[t[0]];
  return 0.5 * (a.x() * b.y() - a.y() * b.x());
}

TEST(Slim, RelaxesASquashedLayoutOfADevelopableSheetToAnIsometry) {
  const Rolled r = rolled_sheet(12);
  ASSERT_NEAR(measure_stretch(r.mesh, r.flat).l2, 1.0, 1e-6);
  // Squashed and sheared, as a square boundary map leaves a chart that is not square.
  std::vector<Vec2> start(r.flat.size());
  for (size_t v = 0; v < start.size(); ++v)
    start[v] = Vec2(0.5 * r.flat[v].x() + 0.3 * r.flat[v].y(), 2.0 * r.flat[v].y());
  const StretchStats before = measure_stretch(r.mesh, start);
  ASSERT_GT(before.l2, 1.4);
  SlimOptions opt;
  opt.max_iterations = 40;
  opt.tolerance = 1e-9;
  const std::vector<Vec2> uv = slim_relax(r.mesh, start, opt);
  const StretchStats after = measure_stretch(r.mesh, uv);
  EXPECT_EQ(after.flipped, 0);
  EXPECT_EQ(after.degenerate, 0);
  EXPECT_LT(after.l2, 1.01) << before.l2 << " -> " << after.l2;
  // Scaled to the 3-D area: an isometry keeps every edge length.
  const Face& t = r.mesh.faces[5];
  EXPECT_NEAR((uv[t[1]] - uv[t[0]]).norm(), (r.mesh.positions[t[1]] - r.mesh.positions[t[0]]).norm(), 0.02);
}

TEST(Slim, KeepsEveryTriangleOfADoublyCurvedCapFromFlipping) {
  // A spherical cap (no isometric layout) from its projection onto the plane, which crowds the
  // triangles near its rim: SLIM lowers the stretch and keeps each triangle's orientation.
  TriMesh cap = shapes::plane(16, 2.0);
  std::vector<Vec2> start(cap.positions.size());
  for (size_t v = 0; v < cap.positions.size(); ++v) {
    Vec3& p = cap.positions[v];
    const double x = p.x() - 1, y = p.y() - 1;  // plane(16, 2) spans [0, 2]²
    const double rho = std::hypot(x, y), theta = std::atan2(y, x);
    const double phi = 1.3 * rho / std::sqrt(2.0);  // polar angle up to 1.3 rad at the corners
    p = Vec3(std::sin(phi) * std::cos(theta), std::sin(phi) * std::sin(theta), std::cos(phi));
    start[v] = Vec2(p.x(), p.y());  // orthographic: the rim is squeezed
  }
  const StretchStats before = measure_stretch(cap, start);
  ASSERT_EQ(before.flipped + before.degenerate, 0);
  const std::vector<Vec2> uv = slim_relax(cap, start);
  const StretchStats after = measure_stretch(cap, uv);
  EXPECT_EQ(after.flipped, 0);
  EXPECT_EQ(after.degenerate, 0);
  EXPECT_LT(after.l2, before.l2 - 0.01) << before.l2 << " -> " << after.l2;
  for (const Face& t : cap.faces) ASSERT_GT(signed_area(uv, t), 0.0);
  // Fitted into its smallest rectangle in [0,1]².
  const std::optional<PolygonLayout> fit = slim_layout(cap, start);
  ASSERT_TRUE(fit.has_value());
  for (const Vec2& p : fit->uv) {
    EXPECT_GE(p.minCoeff(), -1e-12);
    EXPECT_LE(p.maxCoeff(), 1 + 1e-12);
  }
  EXPECT_GT(fit->fill, 0.5);
  EXPECT_LE(fit->fill, 1.0);
}

TEST(Slim, AFlippedStartComesBackUnchangedAndBadInputIsOneError) {
  const Rolled r = rolled_sheet(4);
  std::vector<Vec2> flipped = r.flat;
  std::swap(flipped[6], flipped[7]);  // two interior neighbours swapped: folded triangles
  EXPECT_EQ(slim_relax(r.mesh, flipped), flipped);
  std::vector<Vec2> short_start(r.flat.begin(), r.flat.end() - 1);
  EXPECT_THROW(slim_relax(r.mesh, short_start), InvalidInputError);
  std::vector<Vec2> nan_start = r.flat;
  nan_start[3].x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(slim_relax(r.mesh, nan_start), InvalidInputError);
  TriMesh bad_face = r.mesh;
  bad_face.faces[0][1] = bad_face.num_vertices();
  EXPECT_THROW(slim_relax(bad_face, r.flat), InvalidInputError);
  TriMesh bad_position = r.mesh;
  bad_position.positions[2].z() = std::numeric_limits<double>::infinity();
  EXPECT_THROW(slim_relax(bad_position, r.flat), InvalidInputError);
}

}  // namespace
}  // namespace adaptex

namespace adaptex {
namespace {

/// A fan of \p n triangles around a saddle vertex, slit open between its first and last ring
/// vertex (a disk), with an angle sum above 2π at the centre: its near-isometric layouts overlap
/// themselves. The start layout squeezes the fan into \p squeeze of a turn (flip-free).
struct Saddle {
  TriMesh mesh;
  std::vector<Vec2> start;
};

Saddle saddle_fan(int n, double squeeze) {
  Saddle s;
  s.mesh.positions.push_back(Vec3::Zero());
  s.start.push_back(Vec2::Zero());
  for (int k = 0; k <= n; ++k) {
    const double t = 2 * M_PI * k / n;
    s.mesh.positions.push_back(Vec3(std::cos(t), std::sin(t), 0.6 * std::sin(3 * t)));
    s.start.push_back(Vec2(std::cos(squeeze * t), std::sin(squeeze * t)));
  }
  for (int k = 1; k <= n; ++k) s.mesh.faces.push_back({0, k, k + 1});
  return s;
}

TEST(Slim, HalvingGivesTheFirstValidLayoutOfFewerIterationsFromOneRun) {
  const Saddle s = saddle_fan(24, 0.7);
  SlimOptions full;
  full.max_iterations = 12;
  full.tolerance = 0;
  // Precondition: the full run overlaps itself, so the halving must fall back.
  ASSERT_FALSE(slim_layout(s.mesh, s.start, full).has_value());
  std::optional<PolygonLayout> expected;
  SlimOptions o = full;
  for (o.max_iterations = full.max_iterations; !expected && o.max_iterations >= 1; o.max_iterations /= 2)
    expected = slim_layout(s.mesh, s.start, o);
  ASSERT_TRUE(expected.has_value());
  const std::optional<PolygonLayout> got = slim_layout_halving(s.mesh, s.start, full);
  ASSERT_TRUE(got.has_value());
  EXPECT_EQ(got->uv, expected->uv);  // bit for bit: the same iterations
  EXPECT_EQ(got->fill, expected->fill);
  EXPECT_EQ(got->aspect, expected->aspect);
  full.max_iterations = 0;
  EXPECT_FALSE(slim_layout_halving(s.mesh, s.start, full).has_value());
  // Bad input is one error, with or without iterations to run.
  std::vector<Vec2> nan_start = s.start;
  nan_start[2].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(slim_layout_halving(s.mesh, nan_start, full), InvalidInputError);
  full.max_iterations = 12;
  EXPECT_THROW(slim_layout_halving(s.mesh, nan_start, full), InvalidInputError);
  std::vector<Vec2> short_start(s.start.begin(), s.start.end() - 1);
  EXPECT_THROW(slim_layout_halving(s.mesh, short_start, full), InvalidInputError);
}

}  // namespace
}  // namespace adaptex
