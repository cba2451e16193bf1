// Sander 2001 stretch metrics, overlap counting and texel utilization (stretch.h, thesis §2.1.3).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "adaptex/core/predicates.h"
#include "adaptex/core/shapes.h"
#include "adaptex/param/stretch.h"
#include "disk_fixtures.h"

using namespace adaptex;
using adaptex::test::as_param;

TEST(Stretch, IsometricFaceHasUnitSingularValues) {
  // A triangle in 3-D (rotated, translated) and its congruent copy in UV.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Vec2 t0(0.1, 0.2), t1(0.5, 0.25), t2(0.2, 0.6);
  auto lift = [&](const Vec2& t) { return Vec3(R * Vec3(t.x(), t.y(), 0) + Vec3(3, -1, 2)); };
  const FaceStretch s = face_stretch(lift(t0), lift(t1), lift(t2), t0, t1, t2);
  EXPECT_NEAR(s.gamma_max, 1.0, 1e-12);
  EXPECT_NEAR(s.gamma_min, 1.0, 1e-12);
  EXPECT_NEAR(s.l2(), 1.0, 1e-12);
}

TEST(Stretch, ScaledAndShearedFaces) {
  const Vec3 p0(0, 0, 0), p1(1, 0, 0), p2(0, 1, 0);
  // UV twice as large: the map UV -> 3-D shrinks by 1/2.
  FaceStretch s = face_stretch(p0, p1, p2, Vec2(0, 0), Vec2(2, 0), Vec2(0, 2));
  EXPECT_NEAR(s.gamma_max, 0.5, 1e-12);
  EXPECT_NEAR(s.gamma_min, 0.5, 1e-12);
  // Anisotropic: u squeezed by 4, v kept: Γ = 4, γ = 1, L2 = sqrt((16+1)/2).
  s = face_stretch(p0, p1, p2, Vec2(0, 0), Vec2(0.25, 0), Vec2(0, 1));
  EXPECT_NEAR(s.gamma_max, 4.0, 1e-12);
  EXPECT_NEAR(s.gamma_min, 1.0, 1e-12);
  EXPECT_NEAR(s.l2(), std::sqrt(8.5), 1e-12);
  // Flipped and degenerate UV triangles: infinite stretch.
  EXPECT_TRUE(std::isinf(face_stretch(p0, p1, p2, Vec2(0, 0), Vec2(0, 1), Vec2(1, 0)).gamma_max));
  EXPECT_TRUE(std::isinf(face_stretch(p0, p1, p2, Vec2(0, 0), Vec2(1, 1), Vec2(2, 2)).gamma_max));
}

TEST(Stretch, MeshL2IsScaleInvariantAndOneForPlanarDisk) {
  // A planar disk parameterized by its own xy coordinates, scaled into the unit square: L2 = 1.
  TriMesh m = shapes::plane(8, 3.0);
  std::vector<Vec2> uv;
  for (const Vec3& p : m.positions) uv.push_back(Vec2(p.x(), p.y()) / 3.0);
  StretchStats st = measure_stretch(m, as_param(m, uv));
  EXPECT_NEAR(st.l2, 1.0, 1e-12);
  EXPECT_NEAR(st.linf, 1.0, 1e-12);
  EXPECT_NEAR(st.area_distortion, 1.0, 1e-12);
  EXPECT_NEAR(st.angle_distortion, 1.0, 1e-12);
  EXPECT_EQ(st.flipped, 0);
  EXPECT_EQ(st.degenerate, 0);
  // Same numbers through the per-vertex overload and per face.
  EXPECT_NEAR(measure_stretch(m, uv).l2, 1.0, 1e-12);
  for (double l2 : face_l2_stretch(m, as_param(m, uv))) EXPECT_NEAR(l2, 1.0, 1e-12);
  // Anisotropic scaling u *= 1/2: every face has Γ = 2, γ = 1 before normalization;
  // normalized by sqrt(ΣA₂/ΣA₃) = sqrt(1/2): L2 = sqrt(5/2) * sqrt(1/2) = sqrt(5)/2.
  for (Vec2& t : uv) t.x() *= 0.5;
  st = measure_stretch(m, uv);
  EXPECT_NEAR(st.l2, std::sqrt(5.0) / 2, 1e-12);
  EXPECT_NEAR(st.linf, 2 * std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(st.area_distortion, 1.0, 1e-12);
  EXPECT_NEAR(st.angle_distortion, 2.0, 1e-12);
}

TEST(Stretch, CountsFlippedAndDegenerateFaces) {
  TriMesh m = shapes::plane(4);
  std::vector<Vec2> uv;
  for (const Vec3& p : m.positions) uv.push_back(Vec2(p.x(), p.y()));
  // Mirror one face's corner far across: flip it by moving an interior vertex? Simpler: collapse and
  // reflect through dedicated copies of the faces.
  Parameterization p = as_param(m, uv);
  p.uv.push_back(Vec2(0.1, 0.1));
  p.uv.push_back(Vec2(0.2, 0.2));
  p.uv.push_back(Vec2(0.3, 0.3));
  p.wedge_vertex.insert(p.wedge_vertex.end(), {m.faces[0][0], m.faces[0][1], m.faces[0][2]});
  const int n = static_cast<int>(uv.size());
  p.uv_faces[0] = {n, n + 1, n + 2};                                       // degenerate
  p.uv_faces[1] = {p.uv_faces[1][0], p.uv_faces[1][2], p.uv_faces[1][1]};  // flipped
  const StretchStats st = measure_stretch(m, p);
  EXPECT_EQ(st.degenerate, 1);
  EXPECT_EQ(st.flipped, 1);
  EXPECT_TRUE(std::isinf(st.l2));
  const auto per_face = face_l2_stretch(m, p);
  EXPECT_TRUE(std::isinf(per_face[0]));
  EXPECT_TRUE(std::isinf(per_face[1]));
  EXPECT_TRUE(std::isfinite(per_face[2]));
}

TEST(Overlap, ValidLayoutsHaveNone) {
  // Grid layout: many shared edges and vertices, no overlap.
  TriMesh m = shapes::plane(30);
  std::vector<Vec2> uv;
  for (const Vec3& p : m.positions) uv.push_back(Vec2(p.x(), p.y()));
  Parameterization p = as_param(m, uv);
  EXPECT_EQ(count_overlapping_triangles(p), 0);
  // Two charts side by side touching along a line (separate wedges at equal positions): no overlap.
  Parameterization two = p;
  const int n = static_cast<int>(uv.size());
  for (const Vec2& t : uv) two.uv.push_back(Vec2(t.x() + 1.0, t.y()));
  for (size_t f = 0; f < p.uv_faces.size(); ++f)
    two.uv_faces.push_back({p.uv_faces[f][0] + n, p.uv_faces[f][1] + n, p.uv_faces[f][2] + n});
  EXPECT_EQ(count_overlapping_triangles(two), 0);
}

TEST(Overlap, FindsPlantedOverlaps) {
  TriMesh m = shapes::plane(20);
  std::vector<Vec2> uv;
  for (const Vec3& p : m.positions) uv.push_back(Vec2(p.x(), p.y()));
  Parameterization p = as_param(m, uv);
  // A small triangle strictly inside face 100: overlaps exactly that face.
  const Face& f = p.uv_faces[100];
  const Vec2 c = (p.uv[f[0]] + p.uv[f[1]] + p.uv[f[2]]) / 3.0;
  const int n = p.num_wedges();
  p.uv.insert(p.uv.end(), {c + Vec2(-0.001, -0.001), c + Vec2(0.001, -0.001), c + Vec2(0, 0.001)});
  p.uv_faces.push_back({n, n + 1, n + 2});
  EXPECT_EQ(count_overlapping_triangles(p), 1);
  // A second copy of the whole grid shifted by a quarter cell: overlaps a lot; max_pairs caps.
  Parameterization q = as_param(m, uv);
  for (const Vec2& t : uv) q.uv.push_back(t + Vec2(0.0125, 0.0));
  const int base = static_cast<int>(uv.size());
  for (const Face& g : m.faces) q.uv_faces.push_back({g[0] + base, g[1] + base, g[2] + base});
  EXPECT_EQ(count_overlapping_triangles(q, 50), 50);
  EXPECT_GT(count_overlapping_triangles(q, 1000000), static_cast<long>(m.faces.size()));
  // Flipped overlapping triangle (opposite orientation) is found too.
  Parameterization r = as_param(m, uv);
  const int k = r.num_wedges();
  r.uv.insert(r.uv.end(), {c + Vec2(-0.001, -0.001), c + Vec2(0, 0.001), c + Vec2(0.001, -0.001)});
  r.uv_faces.push_back({k, k + 1, k + 2});
  EXPECT_EQ(count_overlapping_triangles(r), 1);
}

TEST(Overlap, CrossingEdgesWithoutContainedVertices) {
  // Star of David: no vertex of one triangle inside the other, interiors overlap.
  Parameterization p;
  p.uv = {{0.5, 0.9}, {0.1, 0.3}, {0.9, 0.3}, {0.5, 0.1}, {0.9, 0.7}, {0.1, 0.7}};
  p.uv_faces = {{0, 1, 2}, {3, 4, 5}};
  EXPECT_EQ(count_overlapping_triangles(p), 1);
  // Triangles sharing only a vertex, on opposite sides: none.
  p.uv = {{0, 0}, {1, 0}, {0, 1}, {-1, 0}, {0, -1}};
  p.uv_faces = {{0, 1, 2}, {0, 3, 4}};
  EXPECT_EQ(count_overlapping_triangles(p), 0);
}

namespace {

/// Reference: every pair of non-degenerate triangles tested by the plain separating-axis test on
/// coordinates alone (no shared-vertex shortcuts), O(F²).
std::vector<std::array<int, 2>> brute_force_pairs(const Parameterization& p) {
  const auto corners = [&](int f) {
    const Face& t = p.uv_faces[f];
    return std::array<Vec2, 3>{p.uv[t[0]], p.uv[t[1]], p.uv[t[2]]};
  };
  const auto separated = [](const std::array<Vec2, 3>& t, int s, const std::array<Vec2, 3>& o) {
    for (int k = 0; k < 3; ++k) {
      bool out = true;
      for (int j = 0; j < 3 && out; ++j) out = s * orient2d_filtered(t[k], t[(k + 1) % 3], o[j]) <= 0;
      if (out) return true;
    }
    return false;
  };
  std::vector<std::array<int, 2>> pairs;
  const int nf = static_cast<int>(p.uv_faces.size());
  for (int f = 0; f < nf; ++f)
    for (int g = f + 1; g < nf; ++g) {
      const auto a = corners(f), b = corners(g);
      const int sa = orient2d_filtered(a[0], a[1], a[2]), sb = orient2d_filtered(b[0], b[1], b[2]);
      if (sa != 0 && sb != 0 && !separated(a, sa, b) && !separated(b, sb, a)) pairs.push_back({f, g});
    }
  return pairs;
}

}  // namespace

TEST(Overlap, NeighboursAreJudgedAsByThePlainSeparatingAxisTest) {
  // Grids whose vertices are moved by up to a few cells: neighbours share edges and vertices, and
  // many fold over each other. The shared-vertex ordering must find exactly the reference pairs.
  for (unsigned seed : {1u, 2u, 3u}) {
    TriMesh m = shapes::plane(12);
    std::vector<Vec2> uv;
    unsigned state = seed;
    const auto rnd = [&] {
      state = state * 1664525u + 1013904223u;
      return (state >> 8) / double(1u << 24) - 0.5;
    };
    const double amp = 0.05 * seed;
    for (const Vec3& q : m.positions) uv.push_back(Vec2(q.x() + amp * rnd(), q.y() + amp * rnd()));
    const Parameterization p = as_param(m, uv);
    const auto expected = brute_force_pairs(p);
    EXPECT_FALSE(expected.empty());
    EXPECT_EQ(overlapping_triangle_pairs(p, 1000000), expected) << "seed " << seed;
    EXPECT_EQ(count_overlapping_triangles(p, 1000000), static_cast<long>(expected.size()));
  }
}

TEST(Texels, UtilizationOfSquareAndHalf) {
  Parameterization p;
  p.uv = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  p.uv_faces = {{0, 1, 2}, {0, 2, 3}};
  EXPECT_DOUBLE_EQ(texel_utilization(p, 64), 1.0);
  p.uv_faces = {{0, 1, 2}};
  // Lower-right half including the diagonal's texel centres: (n² + n) / 2 of n² texels.
  EXPECT_NEAR(texel_utilization(p, 64), (64.0 * 64 + 64) / 2 / (64.0 * 64), 1e-12);
  p.uv = {{0.25, 0.25}, {0.75, 0.25}, {0.75, 0.75}, {0.25, 0.75}};
  p.uv_faces = {{0, 1, 2}, {0, 2, 3}};
  EXPECT_NEAR(texel_utilization(p, 100), 0.25, 0.02);
}

TEST(Stretch, L2OfAspectsEqualsMeasuringTheScaledMap) {
  // A curved disk with a non-trivial map: the hemisphere projected onto its base plane.
  const TriMesh m = shapes::icosphere(3);
  TriMesh cap;
  std::vector<int> id(m.num_vertices(), -1);
  for (const Face& f : m.faces) {
    bool keep = true;
    for (int v : f) keep = keep && m.positions[v].z() > 0.05;
    if (!keep) continue;
    Face g;
    for (int k = 0; k < 3; ++k) {
      int& j = id[f[k]];
      if (j < 0) j = static_cast<int>(cap.positions.size()), cap.positions.push_back(m.positions[f[k]]);
      g[k] = j;
    }
    cap.faces.push_back(g);
  }
  std::vector<Vec2> uv(cap.positions.size());
  for (size_t v = 0; v < uv.size(); ++v)
    uv[v] = Vec2(0.5 + 0.4 * cap.positions[v].x(), 0.5 + 0.25 * cap.positions[v].y());
  ASSERT_EQ(measure_stretch(cap, uv).flipped, 0);
  const std::vector<double> aspects = {0.25, 0.6, 1.0, 1.7, 4.0};
  const std::vector<double> l2 = l2_stretch_of_aspects(cap, uv, aspects);
  ASSERT_EQ(l2.size(), aspects.size());
  double lo = 1e300, hi = 0;
  for (size_t i = 0; i < aspects.size(); ++i) {
    const double sx = std::sqrt(aspects[i]);
    std::vector<Vec2> scaled(uv.size());
    for (size_t v = 0; v < uv.size(); ++v) scaled[v] = Vec2(uv[v].x() * sx, uv[v].y() / sx);
    const double expected = measure_stretch(cap, scaled).l2;
    EXPECT_NEAR(l2[i], expected, 1e-12 * expected) << "aspect " << aspects[i];
    lo = std::min(lo, l2[i]);
    hi = std::max(hi, l2[i]);
  }
  EXPECT_GT(hi, 1.2 * lo);  // the aspects really differ
  // One flipped triangle: infinite at every aspect.
  std::swap(cap.faces[0][1], cap.faces[0][2]);
  for (double x : l2_stretch_of_aspects(cap, uv, aspects)) EXPECT_TRUE(std::isinf(x));
}

// A unit square with a cut from its centre (wedge 4) to corner (0, 0), which the layout zipped:
// wedges 0 and 5 are the corner's two sides of the cut.
std::vector<Vec2> zipped_square_uv(const Vec2& corner_copy) {
  return {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1), Vec2(0.5, 0.5), corner_copy};
}
const std::vector<Face> kZippedSquare = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 5, 4}};

TEST(BoundaryContact, AnExactlyZippedCutIsNotFragile) {
  EXPECT_FALSE(boundary_near_contact(zipped_square_uv(Vec2(0, 0)), kZippedSquare, 1e-9));
  // Two triangles of a square: no contact at any tolerance below their size.
  EXPECT_FALSE(boundary_near_contact({Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)},
                                     {{0, 1, 2}, {0, 2, 3}}, 0.1));
}

TEST(BoundaryContact, ANearlyZippedCutIsFragile) {
  // The corner's copy 1e-13 off the cut (a sliver of gap): one side within the tolerance of the other.
  const std::vector<Vec2> uv = zipped_square_uv(Vec2(0, 1e-13));
  EXPECT_TRUE(boundary_near_contact(uv, kZippedSquare, 1e-9));
  EXPECT_FALSE(boundary_near_contact(uv, kZippedSquare, 0.0));
  // The layout is valid as it stands: only rounding can make it overlap.
  Parameterization param;
  param.uv = uv;
  param.uv_faces = kZippedSquare;
  EXPECT_TRUE(invalid_uv_faces(param).empty());
}

TEST(BoundaryContact, AWedgeNearAnotherPartOfTheBoundaryIsFragile) {
  // A "C": the tip of its lower arm (wedge 6) ends 1e-12 below the upper arm's lower edge.
  const std::vector<Vec2> uv = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 0.4), Vec2(0.2, 0.4),
                                Vec2(0.2, 0.6), Vec2(1, 0.6),  Vec2(1, 1),   Vec2(0, 1)};
  const std::vector<Face> open = {{0, 1, 2}, {0, 2, 3}, {0, 3, 7}, {3, 4, 7}, {4, 6, 7}, {4, 5, 6}};
  EXPECT_FALSE(boundary_near_contact(uv, open, 1e-9));
  std::vector<Vec2> closing = uv;
  closing[2] = Vec2(1, 0.6 - 1e-12);  // the lower arm's tip, just under the upper arm's edge 4-5
  EXPECT_TRUE(boundary_near_contact(closing, open, 1e-9));
}

TEST(BoundaryContact, ASliversApexNearItsOwnBaseIsNotAContact) {
  // One triangle 1e-12 high: rounding may flip it (the check after packing sees that), but it has
  // nothing to touch; splitting it is impossible, so it must not count as fragile.
  const std::vector<Vec2> uv = {Vec2(0, 0), Vec2(1, 0), Vec2(0.5, 1e-12)};
  EXPECT_FALSE(boundary_near_contact(uv, {{0, 1, 2}}, 1e-9));
  // The same sliver beside a square: still only its own base is near its apex.
  const std::vector<Vec2> strip = {Vec2(0, 0), Vec2(1, 0), Vec2(0.5, -1e-12), Vec2(1, 1), Vec2(0, 1)};
  EXPECT_FALSE(boundary_near_contact(strip, {{0, 2, 1}, {0, 1, 3}, {0, 3, 4}}, 1e-9));
}
