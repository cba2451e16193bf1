// Isometric unfolding of triangulated polygons (param/unfold.h) and its use for the charts of
// many small components (issue 8: 200 tiny components reach an effective texel share of 0.5).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/param/stretch.h"
#include "adaptex/param/unfold.h"
#include "adaptex/param/unwrap.h"

namespace adaptex {
namespace {

/// A bent strip of \p nf triangles between two zigzag rails 1 apart, 0.5 per step along x.
TriMesh strip(int nf, double sliver_height = -1) {
  TriMesh m;
  for (int j = 0; j < nf + 2; ++j)
    m.positions.push_back(Vec3(0.5 * j, (j % 2) ? 1.0 : 0.0, 0.1 * std::sin(0.7 * j)));
  for (int j = 0; j < nf; ++j) m.faces.push_back(j % 2 ? Face{j, j + 1, j + 2} : Face{j, j + 2, j + 1});
  if (sliver_height > 0) {  // the last vertex drops onto the middle of the edge before it
    const Vec3 a = m.positions[nf - 1], b = m.positions[nf];
    m.positions[nf + 1] = 0.5 * (a + b) + sliver_height * Vec3(0, 0, 1);
  }
  return m;
}

/// L2 of the layout scaled back to the isometric shape (width = aspect * height).
double isometric_l2(const TriMesh& m, const PolygonLayout& u) {
  std::vector<Vec2> scaled = u.uv;
  for (Vec2& t : scaled) t.x() *= u.aspect;
  return measure_stretch(m, scaled).l2;
}

TEST(Unfold, StripsUnfoldIsometricallyIntoTheirRectangle) {
  for (int nf : {1, 2, 5, 10, 40}) {
    SCOPED_TRACE(nf);
    const TriMesh m = strip(nf);
    const std::optional<PolygonLayout> u = unfold_polygon(m);
    ASSERT_TRUE(u.has_value());
    ASSERT_EQ(u->uv.size(), m.positions.size());
    double lo_x = 1, hi_x = 0, lo_y = 1, hi_y = 0;
    for (const Vec2& t : u->uv) {
      ASSERT_TRUE(t.x() >= 0 && t.x() <= 1 && t.y() >= 0 && t.y() <= 1) << t.transpose();
      lo_x = std::min(lo_x, t.x()), hi_x = std::max(hi_x, t.x());
      lo_y = std::min(lo_y, t.y()), hi_y = std::max(hi_y, t.y());
    }
    // The layout touches all four sides of the unit square (it is scaled into it).
    EXPECT_NEAR(lo_x, 0.0, 1e-12);
    EXPECT_NEAR(hi_x, 1.0, 1e-12);
    EXPECT_NEAR(lo_y, 0.0, 1e-12);
    EXPECT_NEAR(hi_y, 1.0, 1e-12);
    // Isometric: L2 = 1 once the aspect is given back; every UV triangle keeps its orientation.
    EXPECT_NEAR(isometric_l2(m, *u), 1.0, 1e-9);
    for (const Face& t : m.faces) {
      const Vec2 e1 = u->uv[t[1]] - u->uv[t[0]], e2 = u->uv[t[2]] - u->uv[t[0]];
      EXPECT_GT(e1.x() * e2.y() - e1.y() * e2.x(), 0.0);
    }
    // Fill: UV area over the rectangle.
    EXPECT_GT(u->fill, 0.0);
    EXPECT_LE(u->fill, 1.0 + 1e-12);
  }
  // A single triangle fills exactly half of its smallest rectangle.
  EXPECT_NEAR(unfold_polygon(strip(1))->fill, 0.5, 1e-9);
  // A long strip lies along its length (the rails are about 1 apart, the strip 0.5 (nf + 1) long)
  // and fills most of its rectangle (all but the two end triangles' halves).
  const PolygonLayout u40 = *unfold_polygon(strip(40));
  EXPECT_GT(std::max(u40.aspect, 1 / u40.aspect), 16.0);
  EXPECT_GT(u40.fill, 0.95);
}

TEST(Unfold, SliversUnfoldButZeroAreaFacesDoNot) {
  // A sliver of height 1e-6 of its base still has a valid (thin) layout; a zero-area face has none.
  const std::optional<PolygonLayout> thin = unfold_polygon(strip(4, 1e-6));
  ASSERT_TRUE(thin.has_value());
  EXPECT_NEAR(isometric_l2(strip(4, 1e-6), *thin), 1.0, 1e-6);
  TriMesh flat = strip(4);
  flat.positions[5] = 0.5 * (flat.positions[3] + flat.positions[4]);  // last face: zero area
  EXPECT_FALSE(unfold_polygon(flat).has_value());
}

TEST(Unfold, RejectsInteriorVerticesAndOverlaps) {
  // A closed fan has an interior vertex: not a triangulated polygon.
  TriMesh closed;
  closed.positions.push_back(Vec3(0, 0, 0.3));
  for (int j = 0; j < 6; ++j)
    closed.positions.push_back(Vec3(std::cos(j * M_PI / 3), std::sin(j * M_PI / 3), 0));
  for (int j = 0; j < 6; ++j) closed.faces.push_back({0, 1 + j, 1 + (j + 1) % 6});
  EXPECT_FALSE(unfold_polygon(closed).has_value());
  // An open fan of 7 equilateral triangles around a boundary vertex (a saddle: 420 degrees of angle
  // at the centre) wraps over itself when unfolded.
  const double s = std::pow(std::sin(M_PI / 8), 2), r = std::sqrt(3.0 / (4 * (1 - s)));
  const double h = std::sqrt(1 - r * r);
  TriMesh saddle;
  saddle.positions.push_back(Vec3(0, 0, 0));
  for (int j = 0; j < 8; ++j)
    saddle.positions.push_back(
        Vec3(r * std::cos(j * M_PI / 4), r * std::sin(j * M_PI / 4), j % 2 ? h : -h));
  for (int j = 0; j < 7; ++j) saddle.faces.push_back({0, 1 + j, 2 + j});
  for (const Face& t : saddle.faces)  // equilateral: every edge has length 1
    for (int k = 0; k < 3; ++k)
      ASSERT_NEAR((saddle.positions[t[k]] - saddle.positions[t[(k + 1) % 3]]).norm(), 1.0, 1e-12);
  EXPECT_FALSE(unfold_polygon(saddle).has_value());
  // The same fan with 5 triangles (300 degrees) unfolds.
  saddle.faces.resize(5);
  saddle.positions.resize(7);
  EXPECT_TRUE(unfold_polygon(saddle).has_value());
  EXPECT_FALSE(unfold_polygon(TriMesh{}).has_value());
}

TEST(Unfold, BadInputThrowsOrHasNoLayout) {
  // Indices outside the positions and non-finite positions: InvalidInputError, not a read out of
  // bounds or a sort of NaN points.
  TriMesh bad_index = strip(5);
  bad_index.faces[2][1] = 7;
  EXPECT_THROW(unfold_polygon(bad_index), InvalidInputError);
  bad_index.faces[2][1] = -1;
  EXPECT_THROW(unfold_polygon(bad_index), InvalidInputError);
  for (double x : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    TriMesh nan = strip(40);
    nan.positions[20].y() = x;
    EXPECT_THROW(unfold_polygon(nan), InvalidInputError) << x;
  }
  // Finite coordinates near the largest double (up to 5.5e307): the squared edge lengths overflow,
  // so there is no layout.
  TriMesh huge = strip(10);
  for (Vec3& p : huge.positions) p *= 1e307;
  EXPECT_FALSE(unfold_polygon(huge).has_value());
  // Every face with zero area (all vertices on a line): no layout.
  TriMesh line = strip(10);
  for (Vec3& p : line.positions) p = Vec3(p.x(), 0, 0);
  EXPECT_FALSE(unfold_polygon(line).has_value());
  // A face with a repeated vertex (zero area, as a "triangle" of a scan's duplicate points): no
  // layout.
  for (const Face& f : {Face{0, 0, 1}, Face{2, 2, 2}}) {
    TriMesh repeated = strip(5);
    repeated.faces[2] = f;
    EXPECT_FALSE(unfold_polygon(repeated).has_value());
  }
  TriMesh one = strip(1);
  one.faces[0] = {0, 1, 1};
  EXPECT_FALSE(unfold_polygon(one).has_value());
  // A face wound against its neighbours lands on top of its parent: no layout.
  TriMesh flipped = strip(5);
  std::swap(flipped.faces[2][1], flipped.faces[2][2]);
  EXPECT_FALSE(unfold_polygon(flipped).has_value());
}

TEST(Unfold, TinyComponentsReachHalfTheTexelsWithTheGutter) {
  // Issue 8: 200 components of 1-10 faces (strips, fans, slivers, zero-area faces, duplicate
  // points). Long strips are unfolded (L2 1 at their own aspect instead of about 1.5 on the
  // square), and the gaps are the 8-texel gutter at 1024 (0.0078) instead of 0.01.
  const TriMesh m = shapes::tiny_components(200);
  const UnwrapResult r = unwrap(m);
  EXPECT_EQ(r.report.num_charts, 200);
  EXPECT_GE(r.report.effective_texel_share, 0.5);
  // At one chart per component and without the minimum chart side (both scale with the gap, so the
  // scan segmentation and the floor pick nothing differently), the 8-texel gutter leaves more texels
  // than the old 1 % gaps.
  UnwrapOptions single, old_gap;
  single.charts = old_gap.charts = ChartMode::Single;
  single.min_chart_side_of_gap = old_gap.min_chart_side_of_gap = 0;
  old_gap.chart_padding = 0.01;
  EXPECT_LT(unwrap(m, old_gap).report.effective_texel_share, unwrap(m, single).report.effective_texel_share);
}

}  // namespace
}  // namespace adaptex
