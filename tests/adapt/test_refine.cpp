// Tests of refine_for_warp() (issue 12 item 3): conforming refinement under a strong smooth warp of
// the UV square. Checked independently of the implementation: flips and midpoint deviation after the
// warp, manifoldness and Euler characteristic in 3-D and in UV, surface and UV interpolation
// unchanged, wedge / chart / winding invariants, locality, budget, and painting + export.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <set>

#include "adaptex/adapt/grid.h"
#include "adaptex/adapt/refine.h"
#include "adaptex/adapt/remap.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/core/topology.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/paint/export.h"
#include "adaptex/paint/painter.h"
#include "adaptex/param/unwrap.h"
#include "test_support.h"

namespace adaptex {
namespace {

using Warp = std::function<Vec2(const Vec2&)>;

struct Scene {
  TriMesh mesh;
  Parameterization param;
};

// Radial magnifier x -> c + (x - c)(1 + k (1 - r/R)^2) inside the disk r < R, identity outside:
// radial stretch 1 + k (1 - t)(1 - 3t) >= 1 - k/3 > 0 for k < 3 (t = r/R), so a C^1 diffeomorphism
// of the square that fixes its boundary when the disk lies inside it. Magnifies 1 + k at c.
Warp magnifier(const Vec2& c, double R, double k) {
  return [=](const Vec2& p) -> Vec2 {
    const Vec2 d = p - c;
    const double t = d.norm() / R;
    return t >= 1 ? p : Vec2(c + d * (1 + k * (1 - t) * (1 - t)));
  };
}

// Swirl: rotation about c by theta0 (1 - r/R)^2 inside the disk r < R (radii preserved: bijective).
Warp swirl(const Vec2& c, double R, double theta0) {
  return [=](const Vec2& p) -> Vec2 {
    const Vec2 d = p - c;
    const double t = d.norm() / R;
    if (t >= 1) return p;
    const double a = theta0 * (1 - t) * (1 - t), cs = std::cos(a), sn = std::sin(a);
    return c + Vec2(cs * d.x() - sn * d.y(), sn * d.x() + cs * d.y());
  };
}

Warp compose(Warp outer, Warp inner) {
  return [=](const Vec2& p) { return outer(inner(p)); };
}

// shapes::plane(n) (unit square) with uv = xy: one chart filling the square.
Scene plane_scene(int n) {
  Scene s;
  s.mesh = shapes::plane(n);
  for (int v = 0; v < s.mesh.num_vertices(); ++v) {
    s.param.uv.push_back(s.mesh.positions[v].head<2>());
    s.param.wedge_vertex.push_back(v);
  }
  s.param.uv_faces = s.mesh.faces;
  s.param.face_chart.assign(s.mesh.faces.size(), 0);
  s.param.num_charts = 1;
  return s;
}

// shapes::plane(n) cut along x = 0.5 into two charts: left u = 0.96 x, right u = 0.04 + 0.96 x
// (a gap of 0.04 between them), v = y. The vertices on the cut have one wedge per chart.
Scene seam_scene(int n) {
  Scene s;
  s.mesh = shapes::plane(n);
  s.param.num_charts = 2;
  std::vector<std::array<int, 2>> wedge(s.mesh.num_vertices(), {-1, -1});
  for (const Face& f : s.mesh.faces) {
    const double cx = (s.mesh.positions[f[0]].x() + s.mesh.positions[f[1]].x() + s.mesh.positions[f[2]].x()) / 3;
    const int chart = cx < 0.5 ? 0 : 1;
    Face w;
    for (int k = 0; k < 3; ++k) {
      int& id = wedge[f[k]][chart];
      if (id < 0) {
        const Vec3& p = s.mesh.positions[f[k]];
        id = s.param.num_wedges();
        s.param.uv.push_back(Vec2(chart * 0.04 + 0.96 * p.x(), p.y()));
        s.param.wedge_vertex.push_back(f[k]);
      }
      w[k] = id;
    }
    s.param.uv_faces.push_back(w);
    s.param.face_chart.push_back(chart);
  }
  return s;
}

Scene unwrapped(TriMesh mesh) {
  Scene s;
  s.param = unwrap(mesh).param;
  s.mesh = std::move(mesh);
  return s;
}

Parameterization warped(const Parameterization& p, const Warp& warp) {
  Parameterization out = p;
  for (Vec2& uv : out.uv) uv = warp(uv);
  return out;
}

// Largest |warp(midpoint) - midpoint of the warped ends| over the UV edges.
double max_deviation(const Parameterization& p, const Warp& warp) {
  double worst = 0;
  for (const Face& w : p.uv_faces)
    for (int k = 0; k < 3; ++k) {
      const Vec2 &a = p.uv[w[k]], &b = p.uv[w[(k + 1) % 3]];
      worst = std::max(worst, (warp(0.5 * (a + b)) - 0.5 * (warp(a) + warp(b))).norm());
    }
  return worst;
}

// Flipped + degenerate faces after the warp (the library's own remap check, no overlap test).
int bad_faces(const Parameterization& p, const Warp& warp) {
  SafeRemapOptions o;
  o.check_overlaps = false;
  const RemapCheck c = check_remap(p, warped(p, warp), o);
  return c.flipped + c.degenerate;
}

// The UV layout as a flat mesh (one vertex per wedge), to check its topology.
TriMesh uv_mesh(const Parameterization& p) {
  TriMesh m;
  for (const Vec2& uv : p.uv) m.positions.push_back(Vec3(uv.x(), uv.y(), 0));
  m.faces = p.uv_faces;
  return m;
}

void expect_same_topology(const TriMesh& a, const TriMesh& b, const char* what) {
  const MeshTopology ta = analyze_topology(a), tb = analyze_topology(b);
  EXPECT_TRUE(tb.is_manifold()) << what;
  EXPECT_EQ(tb.nonmanifold_edges.size(), 0u) << what;
  EXPECT_EQ(tb.euler_characteristic, ta.euler_characteristic) << what;
  EXPECT_EQ(tb.total_loops(), ta.total_loops()) << what;
  EXPECT_EQ(tb.num_components, ta.num_components) << what;
  EXPECT_EQ(tb.num_unreferenced_vertices, 0) << what;
}

// Barycentric coordinates of p in the 3-D triangle (a, b, c) and p's distance to its plane.
std::pair<Vec3, double> barycentric(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e1 = b - a, e2 = c - a, d = p - a;
  const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
  const double det = d11 * d22 - d12 * d12;
  const double s = (d22 * e1.dot(d) - d12 * e2.dot(d)) / det, t = (d11 * e2.dot(d) - d12 * e1.dot(d)) / det;
  return {Vec3(1 - s - t, s, t), std::abs(e1.cross(e2).normalized().dot(d))};
}

// Every invariant of a refinement of `in` that does not depend on the warp.
void expect_valid_refinement(const Scene& in, const RefineResult& r) {
  const TriMesh& m = r.mesh;
  const Parameterization& p = r.param;
  const int V = in.mesh.num_vertices(), U = in.param.num_wedges(), F = in.mesh.num_faces();
  ASSERT_EQ(m.num_vertices(), V + r.added_vertices);
  ASSERT_EQ(p.num_wedges(), U + r.added_wedges);
  ASSERT_EQ(m.num_faces(), F + r.added_faces);
  ASSERT_EQ(p.uv_faces.size(), m.faces.size());
  ASSERT_EQ(p.face_chart.size(), m.faces.size());
  ASSERT_EQ(r.parent_face.size(), m.faces.size());
  ASSERT_EQ(p.wedge_vertex.size(), p.uv.size());
  EXPECT_EQ(p.num_charts, in.param.num_charts);
  for (int v = 0; v < V; ++v) EXPECT_EQ(m.positions[v], in.mesh.positions[v]);
  for (int w = 0; w < U; ++w) {
    EXPECT_EQ(p.uv[w], in.param.uv[w]);
    EXPECT_EQ(p.wedge_vertex[w], in.param.wedge_vertex[w]);
  }
  const double scale = bounding_box(in.mesh).diagonal();
  int checked = 0;
  for (int f = 0; f < m.num_faces(); ++f) {
    const int q = r.parent_face[f];
    ASSERT_GE(q, 0);
    ASSERT_LT(q, F);
    EXPECT_EQ(p.face_chart[f], in.param.face_chart[q]);
    const Face &pv = in.mesh.faces[q], &pw = in.param.uv_faces[q];
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(p.wedge_vertex[p.uv_faces[f][k]], m.faces[f][k]);
      // The corner lies on the parent face, and its UV is the parent's UV interpolation there.
      const auto [b, dist] = barycentric(m.positions[m.faces[f][k]], in.mesh.positions[pv[0]],
                                         in.mesh.positions[pv[1]], in.mesh.positions[pv[2]]);
      EXPECT_LE(dist, 1e-12 * scale);
      EXPECT_GE(b.minCoeff(), -1e-9);
      const Vec2 uv = b[0] * in.param.uv[pw[0]] + b[1] * in.param.uv[pw[1]] + b[2] * in.param.uv[pw[2]];
      EXPECT_LE((uv - p.uv[p.uv_faces[f][k]]).norm(), 1e-9);
      ++checked;
    }
    // Same winding as the parent in 3-D and in UV.
    EXPECT_GT(face_normal(m, f).dot(face_normal(in.mesh, q)), 0.99);
    EXPECT_GT(uv_signed_area(p, f) * uv_signed_area(in.param, q), 0.0);
  }
  EXPECT_EQ(checked, 3 * m.num_faces());
  EXPECT_NEAR(surface_area(m), surface_area(in.mesh), 1e-12 * surface_area(in.mesh));
  expect_same_topology(in.mesh, m, "3-D mesh");
  expect_same_topology(uv_mesh(in.param), uv_mesh(p), "UV layout");
}

RefineOptions options(double tolerance, int levels, long max_faces = 10'000'000) {
  RefineOptions o;
  o.tolerance = tolerance;
  o.max_levels = levels;
  o.max_faces = max_faces;
  return o;
}

TEST(Refine, MagnifierBendsCoarseTrianglesRefinementBringsThemWithinTolerance) {
  const Scene s = plane_scene(16);
  const Warp warp = magnifier(Vec2(0.5, 0.5), 0.35, 2.8);
  const double tol = 0.5 / 256;
  ASSERT_GT(max_deviation(s.param, warp), 4 * tol);
  const RefineResult r = refine_for_warp(s.mesh, s.param, warp, options(tol, 12));
  expect_valid_refinement(s, r);
  EXPECT_GT(r.added_faces, 0);
  EXPECT_LT(r.levels, 12);  // converged, not stopped by the level limit
  EXPECT_FALSE(r.budget_reached);
  EXPECT_LE(max_deviation(r.param, warp), tol);
  EXPECT_DOUBLE_EQ(r.max_deviation, max_deviation(r.param, warp));
  EXPECT_EQ(bad_faces(r.param, warp), 0);
  EXPECT_EQ(r.flipped, 0);
}

TEST(Refine, SwirlFlipsCoarseTrianglesRefinementLeavesNoFlippedOrDegenerateFace) {
  const Scene s = plane_scene(12);
  const Warp warp = swirl(Vec2(0.45, 0.55), 0.3, 3.0);
  ASSERT_GT(bad_faces(s.param, warp), 0);
  const RefineResult r = refine_for_warp(s.mesh, s.param, warp, options(0.5 / 512, 12));
  expect_valid_refinement(s, r);
  EXPECT_EQ(bad_faces(r.param, warp), 0);
  EXPECT_EQ(r.flipped, 0);
  EXPECT_LE(max_deviation(r.param, warp), 0.5 / 512);
  EXPECT_LT(r.levels, 12);
}

TEST(Refine, FlipsAloneAreRepairedWithALooseTolerance) {
  // Tolerance so loose that only the flip criterion marks edges.
  const Scene s = plane_scene(12);
  const Warp warp = swirl(Vec2(0.45, 0.55), 0.3, 3.0);
  const int before = bad_faces(s.param, warp);
  ASSERT_GT(before, 0);
  const RefineResult r = refine_for_warp(s.mesh, s.param, warp, options(1.0, 12));
  expect_valid_refinement(s, r);
  EXPECT_GT(r.added_faces, 0);
  EXPECT_EQ(bad_faces(r.param, warp), 0);
}

TEST(Refine, LevelLimitStopsEarlyAndReportsTheRemainingDeviation) {
  const Scene s = plane_scene(8);
  const Warp warp = compose(magnifier(Vec2(0.5, 0.5), 0.4, 2.9), swirl(Vec2(0.5, 0.5), 0.4, 3.0));
  const double tol = 0.5 / 1024;
  const RefineResult one = refine_for_warp(s.mesh, s.param, warp, options(tol, 1));
  expect_valid_refinement(s, one);
  EXPECT_EQ(one.levels, 1);
  EXPECT_GT(one.max_deviation, tol);
  EXPECT_DOUBLE_EQ(one.max_deviation, max_deviation(one.param, warp));
  EXPECT_EQ(one.flipped, bad_faces(one.param, warp));
  const RefineResult two = refine_for_warp(s.mesh, s.param, warp, options(tol, 2));
  EXPECT_EQ(two.levels, 2);
  EXPECT_GT(two.added_faces, one.added_faces);
  EXPECT_LT(two.max_deviation, one.max_deviation);
  const RefineResult none = refine_for_warp(s.mesh, s.param, warp, options(tol, 0));
  EXPECT_EQ(none.added_faces, 0);
  EXPECT_EQ(none.mesh.faces, s.mesh.faces);
}

TEST(Refine, FaceBudgetIsRespected) {
  const Scene s = plane_scene(16);
  const Warp warp = compose(magnifier(Vec2(0.5, 0.5), 0.4, 2.9), swirl(Vec2(0.5, 0.5), 0.4, 3.0));
  for (long extra : {150L, 1000L, 3000L}) {
    const long budget = s.mesh.num_faces() + extra;
    const RefineResult r = refine_for_warp(s.mesh, s.param, warp, options(0.5 / 1024, 10, budget));
    expect_valid_refinement(s, r);
    EXPECT_TRUE(r.budget_reached);
    EXPECT_GT(r.added_faces, extra / 2);
    EXPECT_LE(r.mesh.num_faces(), budget);
  }
  // Budget below the input: nothing is refined.
  const RefineResult z = refine_for_warp(s.mesh, s.param, warp, options(0.5 / 1024, 10, 10));
  EXPECT_EQ(z.added_faces, 0);
  EXPECT_TRUE(z.budget_reached);
}

TEST(Refine, SmallBudgetGoesToTheWorstEdgeFirst) {
  // A flip-free magnifier off-centre: the edge with the largest deviation is split first.
  const Scene s = plane_scene(16);
  const Warp warp = magnifier(Vec2(0.4, 0.55), 0.3, 2.5);
  ASSERT_EQ(bad_faces(s.param, warp), 0);
  int worst_face = -1;
  double worst = 0;
  for (int f = 0; f < s.mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Vec2 &a = s.param.uv[s.param.uv_faces[f][k]], &b = s.param.uv[s.param.uv_faces[f][(k + 1) % 3]];
      const double d = (warp(0.5 * (a + b)) - 0.5 * (warp(a) + warp(b))).norm();
      if (d > worst) worst = d, worst_face = f;
    }
  const RefineResult r = refine_for_warp(s.mesh, s.param, warp, options(0.5 / 1024, 10, s.mesh.num_faces() + 8));
  EXPECT_TRUE(r.budget_reached);
  EXPECT_LE(r.added_faces, 8);
  EXPECT_GT(r.added_faces, 0);
  EXPECT_NE(r.mesh.faces[worst_face], s.mesh.faces[worst_face]);  // the worst face was split
}

TEST(Refine, FacesFarFromTheWarpAreUntouched) {
  const int n = 32;
  const Scene s = plane_scene(n);
  const Vec2 c(0.3, 0.3);
  const double R = 0.2;
  const Warp warp = magnifier(c, R, 2.5);
  const RefineResult r = refine_for_warp(s.mesh, s.param, warp, options(0.5 / 512, 10));
  expect_valid_refinement(s, r);
  ASSERT_GT(r.added_faces, 0);
  int far = 0, far_untouched = 0, untouched = 0;
  for (int f = 0; f < s.mesh.num_faces(); ++f) {
    const bool same = r.mesh.faces[f] == s.mesh.faces[f] && r.param.uv_faces[f] == s.param.uv_faces[f];
    untouched += same;
    double dist = 1e9;
    for (int k = 0; k < 3; ++k) dist = std::min(dist, (s.param.uv[s.param.uv_faces[f][k]] - c).norm());
    if (dist > R + 2.0 / n) ++far, far_untouched += same;
  }
  EXPECT_GT(far, s.mesh.num_faces() / 2);
  EXPECT_EQ(far_untouched, far);
  // Only faces near the disk are split: parent_face is the identity on every untouched face.
  int identity = 0;
  for (int f = 0; f < s.mesh.num_faces(); ++f) identity += r.parent_face[f] == f;
  EXPECT_EQ(identity, s.mesh.num_faces());
  EXPECT_LT(untouched, s.mesh.num_faces());
}

TEST(Refine, GridWarpThroughApply) {
  // The form adaptex's warps take: a GridWarp (piecewise bilinear), passed through apply().
  const Scene s = plane_scene(12);
  const Warp smooth = compose(magnifier(Vec2(0.5, 0.5), 0.35, 2.5), swirl(Vec2(0.5, 0.5), 0.35, 2.5));
  GridWarp grid = GridWarp::uniform(128);
  for (Vec2& p : grid.points) p = smooth(p);
  const Warp warp = [&grid](const Vec2& p) { return grid.apply(p); };
  ASSERT_GT(bad_faces(s.param, warp), 0);
  const RefineResult r = refine_for_warp(s.mesh, s.param, warp, options(0.5 / 256, 12));
  expect_valid_refinement(s, r);
  EXPECT_LT(r.levels, 12);
  EXPECT_EQ(bad_faces(r.param, warp), 0);
  EXPECT_LE(max_deviation(r.param, warp), 0.5 / 256);
  // And the library's remap of the refined layout through the same grid needs no damping.
  const SafeRemapResult sr = safe_remap(r.param, {&grid});
  EXPECT_EQ(sr.damping, 1.0);
  EXPECT_EQ(sr.locally_damped, 0);
}

TEST(Refine, IdentityWarpChangesNothing) {
  const Scene s = plane_scene(10);
  const RefineResult r = refine_for_warp(s.mesh, s.param, [](const Vec2& p) { return p; });
  EXPECT_EQ(r.added_faces, 0);
  EXPECT_EQ(r.added_vertices, 0);
  EXPECT_EQ(r.levels, 0);
  EXPECT_EQ(r.mesh.faces, s.mesh.faces);
  EXPECT_EQ(r.param.uv_faces, s.param.uv_faces);
  EXPECT_EQ(r.max_deviation, 0.0);
}

TEST(Refine, SeamEdgesGetOneNewWedgePerSide) {
  const Scene s = seam_scene(16);
  const Warp warp = compose(magnifier(Vec2(0.5, 0.5), 0.35, 2.5), swirl(Vec2(0.5, 0.5), 0.35, 2.0));
  ASSERT_GT(max_deviation(s.param, warp), 0.5 / 256);
  const RefineResult r = refine_for_warp(s.mesh, s.param, warp, options(0.5 / 256, 12));
  expect_valid_refinement(s, r);
  EXPECT_EQ(bad_faces(r.param, warp), 0);
  EXPECT_LE(max_deviation(r.param, warp), 0.5 / 256);
  std::vector<int> wedges_of(r.mesh.num_vertices(), 0);
  for (int w = 0; w < r.param.num_wedges(); ++w) ++wedges_of[r.param.wedge_vertex[w]];
  int seam_midpoints = 0;
  double off_cut = 0;  // distance of the two-wedge midpoints from the cut x = 0.5
  for (int v = s.mesh.num_vertices(); v < r.mesh.num_vertices(); ++v) {
    EXPECT_GE(wedges_of[v], 1);
    EXPECT_LE(wedges_of[v], 2);
    seam_midpoints += wedges_of[v] == 2;
    off_cut = std::max(off_cut, wedges_of[v] == 2 ? std::abs(r.mesh.positions[v].x() - 0.5) : 0.0);
  }
  EXPECT_GT(seam_midpoints, 0);
  EXPECT_LE(off_cut, 1e-12);
  EXPECT_EQ(r.added_wedges, r.added_vertices + seam_midpoints);
}

TEST(Refine, UnwrappedMultiChartMeshes) {
  for (TriMesh mesh : {shapes::two_components(), shapes::sphere(24, 12)}) {
    const Scene s = unwrapped(std::move(mesh));
    const Warp warp = compose(magnifier(Vec2(0.5, 0.5), 0.4, 2.5), swirl(Vec2(0.5, 0.5), 0.4, 1.5));
    const double tol = 0.5 / 512;
    ASSERT_GT(max_deviation(s.param, warp), tol);
    const RefineResult r = refine_for_warp(s.mesh, s.param, warp, options(tol, 12));
    expect_valid_refinement(s, r);
    EXPECT_LT(r.levels, 12);
    EXPECT_EQ(bad_faces(r.param, warp), 0);
    EXPECT_LE(max_deviation(r.param, warp), tol);
    EXPECT_GE(r.added_wedges, r.added_vertices);
  }
}

TEST(Refine, PaintAndExportWorkOnTheRefinedMesh) {
  const Scene s = unwrapped(shapes::two_components());
  const Warp warp = magnifier(Vec2(0.5, 0.5), 0.4, 2.8);
  const RefineResult r = refine_for_warp(s.mesh, s.param, warp, options(0.5 / 256, 8));
  ASSERT_GT(r.added_faces, 0);
  const Parameterization p = warped(r.param, warp);
  Painter painter(r.mesh, p, {256, 256, 2});
  Stroke stroke;
  stroke.color = Vec3(1, 0, 0);
  stroke.radius = 0.05 * bounding_box(r.mesh).diagonal();
  for (int v = 0; v < r.mesh.num_vertices(); v += 97) stroke.dabs.push_back(r.mesh.positions[v]);
  painter.paint_stroke(stroke);
  const ImageRGBA8& tex = painter.texture();
  int red = 0;
  for (int j = 0; j < tex.height; ++j)
    for (int i = 0; i < tex.width; ++i) red += tex.texel(i, j)[0] == 255 && tex.texel(i, j)[1] == 0;
  EXPECT_GT(red, 100);
  test::TempDir tmp;
  {
    AtomicOutput out;
    ExportOptions eo;
    eo.glb = true;
    export_textured_mesh(out, tmp.path, "refined", r.mesh, p, tex, eo);
    out.commit();
  }
  const TexturedMesh back = read_textured_obj(tmp.path / "refined.obj");
  EXPECT_EQ(back.mesh.num_faces(), r.mesh.num_faces());
  EXPECT_EQ(back.mesh.num_vertices(), r.mesh.num_vertices());
  EXPECT_EQ(back.param.num_wedges(), r.param.num_wedges());
  EXPECT_TRUE(std::filesystem::exists(tmp.path / "refined.glb"));
}

TEST(Refine, RejectsBadInput) {
  const Scene s = plane_scene(4);
  const Warp id = [](const Vec2& p) { return p; };
  EXPECT_THROW(refine_for_warp(s.mesh, s.param, Warp{}), InvalidInputError);
  EXPECT_THROW(refine_for_warp(s.mesh, s.param, id, options(0.0, 3)), InvalidInputError);
  EXPECT_THROW(refine_for_warp(s.mesh, s.param, id, options(1e-3, -1)), InvalidInputError);
  EXPECT_THROW(refine_for_warp(s.mesh, s.param, id, options(1e-3, 3, -5)), InvalidInputError);
  Parameterization bad = s.param;
  bad.wedge_vertex[bad.uv_faces[0][0]] = (s.mesh.faces[0][0] + 1) % s.mesh.num_vertices();
  EXPECT_THROW(refine_for_warp(s.mesh, bad, id), InvalidInputError);
  bad = s.param;
  bad.face_chart.pop_back();
  EXPECT_THROW(refine_for_warp(s.mesh, bad, id), InvalidInputError);
  EXPECT_THROW(refine_for_warp(s.mesh, s.param, [](const Vec2&) { return Vec2(NAN, 0); }),
               InvalidInputError);
  const TriMesh fan = shapes::nonmanifold_fan();
  Parameterization fp;
  for (int v = 0; v < fan.num_vertices(); ++v) {
    fp.uv.push_back(Vec2(0.1 * v, 0.05 * v * v));
    fp.wedge_vertex.push_back(v);
  }
  fp.uv_faces = fan.faces;
  fp.face_chart.assign(fan.faces.size(), 0);
  fp.num_charts = 1;
  EXPECT_THROW(refine_for_warp(fan, fp, id), TopologyError);
}

}  // namespace
}  // namespace adaptex
