// Tests of --charts auto on scans (unwrap.h, "Auto on scans"; docs/charts.md, "Scans"): a mesh
// built in code with over 100 components, handles, hundreds of holes, tiny strips and slivers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "adaptex/core/errors.h"
#include "adaptex/core/topology.h"
#include "adaptex/param/stretch.h"
#include "adaptex/param/unwrap.h"
#include "scan_fixtures.h"
#include "triangle_distance.h"
#include "unwrap_checks.h"

namespace adaptex {
namespace {

TEST(UnwrapScan, ManyComponentsHandlesAndHolesGetDiskChartsWithHighShare) {
  const TriMesh mesh = test::scan_like_mesh(30000);
  const MeshTopology topo = analyze_topology(mesh);
  ASSERT_GT(topo.num_components, 100);
  ASSERT_GE(topo.total_genus(), 8);
  ASSERT_GT(topo.total_loops(), 100);
  UnwrapOptions opt;
  opt.augment_time_budget = 1e9;  // the layout must not depend on the machine's load
  UnwrapResult r;
  test::check_unwrap("scan_like", mesh, opt, &r);  // disks, no flips, no overlaps, UVs in [0,1]²
  // More charts than components (the large pieces and the handles were segmented), and far
  // fewer than faces (the counts follow the stretch and the texel budget, not the face count).
  EXPECT_GT(r.report.num_charts, topo.num_components);
  EXPECT_LT(r.report.num_charts, mesh.num_faces() / 50);
  // One chart per component reaches 0.05 on such meshes (docs/bench_unwrap.md, "Scans").
  EXPECT_GE(r.report.effective_texel_share, 0.5);
}

TEST(UnwrapScan, SplitsLargeCoarseFragmentsOfFewFaces) {
  // A photogrammetry scan keeps much of its area in few large, folded faces. Here one fragment of
  // 32 such faces holds most of the area, beside 40 two-face squares and a fine flat patch.
  // Two charts for that fragment cost the layout its share (0.42 when pieces of fewer than 32
  // faces were never split); splitting it as long as the stretch pays for the seam gives 0.54.
  std::vector<TriMesh> parts{test::crumpled_patch(4, 4, 4.0, 6.0, Vec3(0, 0, 0), 1),
                             test::flat_patch(40, 4.0, Vec3(0, 6, 0))};
  for (int k = 0; k < 40; ++k)
    parts.push_back(test::flat_patch(1, 0.3, Vec3(6 + 0.5 * (k % 8), 0.5 * (k / 8), 0)));
  const TriMesh mesh = shapes::disjoint_union(parts);
  ASSERT_GT(analyze_topology(mesh).num_components, 32);  // the scan segmentation runs
  UnwrapOptions opt;
  opt.augment_time_budget = 1e9;
  UnwrapResult r;
  test::check_unwrap("coarse_fragments", mesh, opt, &r);
  EXPECT_GT(r.report.num_charts, 42);  // the fragment was split
  EXPECT_GE(r.report.effective_texel_share, 0.5);
}

TEST(UnwrapScan, FewComponentsThatNoChartCountServesGetStretchDrivenCharts) {
  // Ten rough coarse fragments and a large flat patch: 11 components, below the scan path. No
  // count of compact charts (4 ... 64 over the whole mesh) reaches the share (0.45 at best): the
  // flat patch, most of the area, draws the charts the fragments need. The segmentation that
  // splits each piece by its own stretch is then built too, and kept: 0.50.
  std::vector<TriMesh> parts;
  for (int k = 0; k < 10; ++k)
    parts.push_back(
        test::crumpled_patch(4, 3, 1.0, 3.0, Vec3(1.5 * (k % 5), 1.5 * (k / 5), 0), k + 1));
  parts.push_back(test::flat_patch(40, 8.0, Vec3(0, 8, 0)));
  const TriMesh mesh = shapes::disjoint_union(parts);
  UnwrapOptions opt;
  opt.augment_time_budget = 1e9;
  UnwrapResult r;
  test::check_unwrap("rough_fragments", mesh, opt, &r);
  EXPECT_GT(r.report.time_segment, 0.0);
  EXPECT_GE(r.report.effective_texel_share, 0.48);
}

TEST(UnwrapScan, ReportsEveryPhaseAndCancelsInEach) {
  const TriMesh mesh = test::scan_like_mesh(20000);
  std::set<std::string> phases;
  UnwrapOptions opt;
  opt.progress = [&](std::string_view phase, double f) {
    EXPECT_GE(f, 0.0);
    EXPECT_LE(f, 1.0);
    phases.emplace(phase);
    return true;
  };
  const UnwrapResult r = unwrap(mesh, opt);
  EXPECT_GT(r.report.time_segment, 0.0);
  for (const char* p : {"cut", "segment", "augment", "yoshizawa", "pack"}) EXPECT_TRUE(phases.count(p)) << p;
  // A cancel in any phase stops the unwrap with CancelledError (and nothing else).
  for (const std::string& phase : phases) {
    SCOPED_TRACE(phase);
    int seen = 0;
    opt.progress = [&](std::string_view p, double) { return !(p == phase && ++seen >= 2); };
    EXPECT_THROW(unwrap(mesh, opt), CancelledError);
  }
}

TEST(UnwrapScan, ACancelEndsBothCandidates) {
  // The two candidates run side by side; once the callback returned false it is not called again
  // (the other candidate stops at its next report instead of running on).
  const TriMesh mesh = test::scan_like_mesh(20000);
  for (const char* phase : {"segment", "augment", "pack"}) {
    SCOPED_TRACE(phase);
    UnwrapOptions opt;
    int seen = 0, after = 0;
    bool cancelled = false;
    opt.progress = [&](std::string_view p, double) {
      if (cancelled) return ++after, false;
      return !(cancelled = p == phase && ++seen >= 2);
    };
    EXPECT_THROW(unwrap(mesh, opt), CancelledError);
    EXPECT_TRUE(cancelled);
    EXPECT_EQ(after, 0);
  }
}

TEST(UnwrapScan, SingleModeAndFewComponentsKeepTheirLayouts) {
  // --charts single is one chart per component, scan or not.
  const TriMesh mesh = test::scan_like_mesh(20000);
  UnwrapOptions single;
  single.charts = ChartMode::Single;
  EXPECT_EQ(unwrap(mesh, single).report.num_charts, analyze_topology(mesh).num_components);
  // The scan segmentation starts above max_charts / 2 components: five tori stay on the path
  // of before (auto keeps one chart per torus when that reaches the share).
  UnwrapOptions opt;
  const UnwrapResult r = unwrap(test::five_tori(), opt);
  EXPECT_EQ(r.report.time_segment, 0.0);
}

/// \p n flat L-shaped components (three unit squares each, scaled 1-2.8), spread along z: no
/// interior vertices, so each is unfolded into an L that fills 3/4 of its rectangle.
TriMesh l_shaped_components(int n) {
  TriMesh m;
  for (int i = 0; i < n; ++i) {
    const double k = 1.0 + 0.3 * (i % 7);
    const int v = m.num_vertices();
    // Grid points (x, y) in {0,1,2}²; the L is the squares (0,0), (1,0), (0,1).
    for (int y = 0; y <= 2; ++y)
      for (int x = 0; x <= 2; ++x) m.positions.push_back(Vec3(k * x, k * y, 3.0 * i));
    const auto id = [&](int x, int y) { return v + 3 * y + x; };
    for (const auto& [x, y] : {std::pair{0, 0}, {1, 0}, {0, 1}}) {
      m.faces.push_back({id(x, y), id(x + 1, y), id(x + 1, y + 1)});
      m.faces.push_back({id(x, y), id(x + 1, y + 1), id(x, y + 1)});
    }
  }
  // Drop the unused corner (2, 2) of every grid: validate-free meshes keep no stray vertex.
  TriMesh out;
  std::vector<int> map(m.num_vertices(), -1);
  for (Face f : m.faces) {
    for (int& c : f) {
      if (map[c] < 0) map[c] = out.num_vertices(), out.positions.push_back(m.positions[c]);
      c = map[c];
    }
    out.faces.push_back(f);
  }
  return out;
}

TEST(UnwrapScan, LShapedChartsArePackedByTheirShapes) {
  // Unfolded L's fill 3/4 of their rectangles: packed by their shapes they nest (pack_shapes()),
  // the share rises, and the layout stays valid (check_unwrap(): no flips, no overlaps).
  const TriMesh mesh = l_shaped_components(120);
  UnwrapOptions opt;
  opt.augment_time_budget = 1e9;
  opt.scan_layout_fill_exponent = 0;  // the L's keep their unfoldings (L2 1) over the square
  // Measured 0.669 -> 0.695. With the default 8-texel gutter the rectangles win (a wide gap costs
  // the rounded-up raster more than the nesting gains, docs/bench_unwrap.md) and that is kept.
  opt.gutter_texels = 2;
  UnwrapResult with;
  test::check_unwrap("L shapes", mesh, opt, &with);
  opt.scan_pack_shapes = false;
  const UnwrapResult without = unwrap(mesh, opt);
  std::printf("L shapes: share %.4f with shape packing, %.4f without\n",
              with.report.effective_texel_share, without.report.effective_texel_share);
  EXPECT_GT(with.report.effective_texel_share, without.report.effective_texel_share + 0.01);
}

/// The smallest distance between UV triangles of two different charts of \p p (disjoint
/// triangles: the smallest vertex-to-edge distance), over pairs of charts whose bounding boxes are
/// closer than \p within; \p within when none is.
double closest_charts(const Parameterization& p, double within) {
  std::vector<std::vector<int>> faces(p.num_charts);
  for (int f = 0; f < static_cast<int>(p.face_chart.size()); ++f) faces[p.face_chart[f]].push_back(f);
  std::vector<Vec2> lo(p.num_charts, Vec2::Constant(2)), hi(p.num_charts, Vec2::Constant(-1));
  for (int c = 0; c < p.num_charts; ++c)
    for (int f : faces[c])
      for (int w : p.uv_faces[f]) lo[c] = lo[c].cwiseMin(p.uv[w]), hi[c] = hi[c].cwiseMax(p.uv[w]);
  double best = within;
  for (int a = 0; a < p.num_charts; ++a)
    for (int b = 0; b < a; ++b) {
      const Vec2 gap = (lo[b] - hi[a]).cwiseMax(lo[a] - hi[b]);
      if (std::max(gap.x(), gap.y()) >= best) continue;
      const auto tri = [&](int f) {
        return test::Tri{p.uv[p.uv_faces[f][0]], p.uv[p.uv_faces[f][1]], p.uv[p.uv_faces[f][2]]};
      };
      for (int fa : faces[a])
        for (int fb : faces[b]) best = std::min(best, test::triangle_distance(tri(fa), tri(fb)));
    }
  return best;
}

TEST(UnwrapScan, ReportsTheGutterTheChartsGot) {
  UnwrapOptions opt;
  opt.augment_time_budget = 1e9;
  const double requested = opt.gutter_texels / opt.gutter_texture_size;
  // Five tori fit with the full gutter of 8 texels at 1024².
  const UnwrapResult few = unwrap(test::five_tori(), opt);
  EXPECT_DOUBLE_EQ(few.report.requested_gutter, requested);
  EXPECT_DOUBLE_EQ(few.report.gutter, requested);
  EXPECT_GE(closest_charts(few.param, 1.0), requested * (1 - 1e-9));
  // 6,000 small squares, each at least a gutter wide with a gutter around it, need more than the
  // square: the gap is halved until they fit, the report says by how much, and the charts keep it.
  std::vector<TriMesh> parts;
  for (int k = 0; k < 6000; ++k)
    parts.push_back(test::flat_patch(1, 0.1 + 0.01 * (k % 5), Vec3(0.5 * (k % 80), 0.5 * (k / 80), 0)));
  const TriMesh many = shapes::disjoint_union(parts);
  UnwrapResult r;
  test::check_unwrap("6000 squares", many, opt, &r);
  EXPECT_DOUBLE_EQ(r.report.requested_gutter, requested);
  EXPECT_LT(r.report.gutter, requested);
  EXPECT_GT(r.report.gutter, 0);
  const double halvings = std::log2(requested / r.report.gutter);
  EXPECT_NEAR(halvings, std::round(halvings), 1e-9);
  EXPECT_GE(closest_charts(r.param, 1.0), r.report.gutter * (1 - 1e-6));
}

TEST(UnwrapScan, OptionsOutOfRangeAreOneClearError) {
  const TriMesh mesh = test::scan_like_mesh(20000);
  for (int k = 0; k < 9; ++k) {
    UnwrapOptions o;
    if (k == 0) o.scan_piece_faces = 0;
    if (k == 1) o.scan_max_rounds = -1;
    if (k == 2) o.scan_chart_l2 = std::numeric_limits<double>::quiet_NaN();
    if (k == 3) o.min_chart_side_of_gap = 5;
    if (k == 4) o.scan_planar_angle = 90;
    if (k == 5) o.scan_planar_angle = std::numeric_limits<double>::quiet_NaN();
    if (k == 6) o.scan_planar_min_area = 1.5;
    if (k == 7) o.scan_layout_fill_exponent = 2;
    if (k == 8) o.augment_time_budget = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(unwrap(mesh, o), InvalidInputError) << k;
  }
}

}  // namespace
}  // namespace adaptex
