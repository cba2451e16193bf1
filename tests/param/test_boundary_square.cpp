// Direct tests of map_boundary_to_square() (param/floater.h): the disk boundary goes onto the boundary
// of [0,1]^2 by arc length, counter-clockwise like the faces, with the four corners at the most
// corner-like vertices; the inscribed circle when no valid corner choice exists.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <functional>

#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/core/topology.h"
#include "adaptex/param/floater.h"

namespace adaptex {
namespace {

/// Position along the square's boundary, counter-clockwise from (0,0): in [0,4).
double perimeter_parameter(const Vec2& p) {
  if (p.y() == 0.0 && p.x() < 1.0) return p.x();
  if (p.x() == 1.0 && p.y() < 1.0) return 1.0 + p.y();
  if (p.y() == 1.0 && p.x() > 0.0) return 2.0 + (1.0 - p.x());
  return 3.0 + (1.0 - p.y());
}

bool on_square_boundary(const Vec2& p) {
  const bool inside = p.x() >= 0 && p.x() <= 1 && p.y() >= 0 && p.y() <= 1;
  return inside && (p.x() == 0.0 || p.x() == 1.0 || p.y() == 0.0 || p.y() == 1.0);
}

/// Signed area of the polygon uv[0], uv[1], ... (positive: counter-clockwise).
double polygon_area(const std::vector<Vec2>& uv) {
  double a = 0;
  for (size_t i = 0; i < uv.size(); ++i) {
    const Vec2 &p = uv[i], &q = uv[(i + 1) % uv.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return a / 2;
}

/// Checks the whole contract on a 10 x 10 grid of a square of side \p w, scaled and moved in 3-D by
/// \p place (a similarity: the corners stay the square's corners).
void check_square(double w, const std::function<Vec3(const Vec3&)>& place) {
  TriMesh m = shapes::plane(10);
  const double h = w;
  for (Vec3& p : m.positions) p *= w;
  TriMesh placed = m;
  for (Vec3& p : placed.positions) p = place(p);
  const MeshTopology topo = analyze_topology(m);
  ASSERT_EQ(topo.boundary_loops.size(), 1u);
  for (bool reversed : {false, true}) {
    SCOPED_TRACE(reversed ? "loop given backwards" : "loop as found");
    std::vector<int> loop = topo.boundary_loops[0];
    if (reversed) std::reverse(loop.begin(), loop.end());
    const DiskBoundary b = map_boundary_to_square(placed, loop);
    const int n = static_cast<int>(b.loop.size());
    ASSERT_EQ(n, 40);
    ASSERT_EQ(b.uv.size(), b.loop.size());
    EXPECT_TRUE(b.on_square);
    // The corners are the rectangle's corners, in counter-clockwise order from (0,0).
    const Vec2 square[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int k = 0; k < 4; ++k) {
      EXPECT_EQ(b.uv[b.corners[k]], square[k]) << k;
      const Vec3 p = m.positions[b.loop[b.corners[k]]];
      EXPECT_TRUE((p.x() == 0 || p.x() == w) && (p.y() == 0 || p.y() == h)) << p.transpose();
    }
    // Every point on the square's boundary, counter-clockwise (the faces' winding: the plane's faces
    // face +z), the perimeter parameter growing along the loop.
    EXPECT_GT(polygon_area(b.uv), 0.99);
    for (int i = 0; i < n; ++i) {
      ASSERT_TRUE(on_square_boundary(b.uv[i])) << i << ": " << b.uv[i].transpose();
      const int i0 = (b.corners[0] + i) % n, i1 = (b.corners[0] + i + 1) % n;
      const double t0 = perimeter_parameter(b.uv[i0]);
      const double t1 = i + 1 == n ? 4.0 : perimeter_parameter(b.uv[i1]);
      EXPECT_GT(t1, t0) << i;
    }
    // Arc length: on each side the 3-D edges are equal, so the UV steps are too (10 per side).
    for (int i = 0; i < n; ++i) {
      const double step = (b.uv[(i + 1) % n] - b.uv[i]).norm();
      EXPECT_NEAR(step, 0.1, 1e-12) << i;
    }
  }
}

TEST(BoundaryToSquare, SquareGrid) {
  check_square(1.0, [](const Vec3& p) { return p; });
}

TEST(BoundaryToSquare, ScaledTiltedAndMovedSquareGivesTheSameMap) {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  check_square(7.5, [&](const Vec3& p) { return Vec3(r * p + Vec3(-3, 10, 0.25)); });
}

TEST(BoundaryToSquare, UnevenEdgesAreSpacedByArcLength) {
  // Move the boundary vertices of the bottom side so their edges have lengths 1, 2, 3, ... (scaled).
  TriMesh m = shapes::plane(6);
  double total = 21;  // 1 + 2 + ... + 6
  for (Vec3& p : m.positions)
    if (p.y() == 0.0) {
      const int i = static_cast<int>(std::lround(p.x() * 6));
      p.x() = i * (i + 1) / 2 / total;
    }
  const MeshTopology topo = analyze_topology(m);
  const DiskBoundary b = map_boundary_to_square(m, topo.boundary_loops[0]);
  ASSERT_TRUE(b.on_square);
  int bottom = 0;
  for (size_t i = 0; i < b.loop.size(); ++i) {
    const size_t j = (i + 1) % b.loop.size();
    const Vec3 p = m.positions[b.loop[i]], q = m.positions[b.loop[j]];
    if (p.y() != 0.0 || q.y() != 0.0) continue;
    ++bottom;
    EXPECT_EQ(b.uv[i].y(), 0.0);
    EXPECT_NEAR(b.uv[j].x() - b.uv[i].x(), q.x() - p.x(), 1e-12);  // the side is 1 long in 3-D too
  }
  EXPECT_EQ(bottom, 6);
}

TEST(BoundaryToSquare, OneTriangleGoesOnTheInscribedCircle) {
  TriMesh m;
  m.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  m.faces = {Face{0, 1, 2}};
  const DiskBoundary b = map_boundary_to_square(m, {0, 2, 1});  // given clockwise
  EXPECT_FALSE(b.on_square);  // three ears cannot all be among four distinct corners of a square
  ASSERT_EQ(b.uv.size(), 3u);
  for (const Vec2& p : b.uv) EXPECT_NEAR((p - Vec2(0.5, 0.5)).norm(), 0.5, 1e-12);
  EXPECT_GT(polygon_area(b.uv), 0);  // oriented like the face
  EXPECT_EQ(b.loop, (std::vector<int>{1, 2, 0}));
}

TEST(BoundaryToSquare, BadLoopsAreTopologyErrors) {
  const TriMesh m = shapes::plane(4);
  EXPECT_THROW(map_boundary_to_square(m, {0, 1}), TopologyError);
  // Two vertices joined by an interior edge are not a boundary edge.
  const MeshTopology topo = analyze_topology(m);
  std::vector<bool> on_boundary(m.num_vertices(), false);
  for (int v : topo.boundary_loops[0]) on_boundary[v] = true;
  int a = -1, c = -1;
  for (const Face& f : m.faces)
    for (int k = 0; k < 3 && a < 0; ++k)
      if (!on_boundary[f[k]] && !on_boundary[f[(k + 1) % 3]]) a = f[k], c = f[(k + 1) % 3];
  ASSERT_GE(a, 0);
  EXPECT_THROW(map_boundary_to_square(m, {a, c, topo.boundary_loops[0][0]}), TopologyError);
}

}  // namespace
}  // namespace adaptex
