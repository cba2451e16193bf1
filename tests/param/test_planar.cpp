// Planar chart growth and projection layouts (param/planar.h), free-boundary conformal layouts
// (param/lscm.h), and their use for scans (UnwrapOptions::scan_planar_angle, scan_free_boundary).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/core/topology.h"
#include "adaptex/param/lscm.h"
#include "adaptex/param/planar.h"
#include "adaptex/param/stretch.h"
#include "adaptex/param/unwrap.h"
#include "../asan_detect.h"
#include "scan_fixtures.h"
#include "unwrap_checks.h"

namespace adaptex {
namespace {

/// The floor and four walls of the cube [0,1]³ (no ceiling), n × n squares per side, welded into
/// one connected surface, faces wound outwards-consistently; \p noise moves interior grid vertices
/// along the side's normal by a deterministic amount in [-noise, noise] (a depth scan's wall).
TriMesh open_box(int n, double noise = 0.0) {
  TriMesh m;
  std::map<std::tuple<int, int, int>, int> index;
  unsigned state = 12345u;
  auto vertex = [&](int i, int j, int k) {
    auto [it, fresh] = index.try_emplace({i, j, k}, m.num_vertices());
    if (fresh) {
      Vec3 p(double(i) / n, double(j) / n, double(k) / n);
      state = state * 1664525u + 1013904223u;
      const double r = noise * (2.0 * static_cast<double>(state >> 8) / (1u << 24) - 1.0);
      const bool inner_x = i > 0 && i < n, inner_y = j > 0 && j < n, inner_z = k > 0 && k < n;
      if (k == 0 && inner_x && inner_y) p.z() += r;
      else if ((i == 0 || i == n) && inner_y && inner_z) p.x() += r;
      else if ((j == 0 || j == n) && inner_x && inner_z) p.y() += r;
      m.positions.push_back(p);
    }
    return it->second;
  };
  // side(a, b) -> grid point; each side is wound so that the mesh is consistently oriented.
  auto side = [&](auto point, bool flip) {
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) {
        const int p00 = point(a, b), p10 = point(a + 1, b), p01 = point(a, b + 1), p11 = point(a + 1, b + 1);
        if (flip) m.faces.push_back({p00, p11, p10}), m.faces.push_back({p00, p01, p11});
        else m.faces.push_back({p00, p10, p11}), m.faces.push_back({p00, p11, p01});
      }
  };
  side([&](int a, int b) { return vertex(a, b, 0); }, true);    // floor z = 0, normal -z
  side([&](int a, int b) { return vertex(a, 0, b); }, false);   // y = 0, normal -y
  side([&](int a, int b) { return vertex(a, n, b); }, true);    // y = 1, normal +y
  side([&](int a, int b) { return vertex(0, a, b); }, true);    // x = 0, normal -x
  side([&](int a, int b) { return vertex(n, a, b); }, false);   // x = 1, normal +x
  return m;
}

TEST(PlanarCharts, TheWallsAndFloorOfARoomAreOneChartEach) {
  const TriMesh box = open_box(12, 0.01);  // noise: normals up to ~10° off their side's
  ASSERT_EQ(analyze_topology(box).num_components, 1);
  ASSERT_TRUE(analyze_topology(box).components[0].consistently_oriented);
  const PlanarCharts pc = planar_charts(box);
  EXPECT_EQ(pc.num_planar, 5);
  EXPECT_EQ(pc.num_charts, 5);
  // Faces 2 n² s .. 2 n² (s + 1) are side s: one label per side, five different labels.
  const int per_side = 2 * 12 * 12;
  std::set<int> labels;
  for (int s = 0; s < 5; ++s) {
    const int l = pc.label[s * per_side];
    labels.insert(l);
    for (int f = s * per_side; f < (s + 1) * per_side; ++f) ASSERT_EQ(pc.label[f], l) << "face " << f;
  }
  EXPECT_EQ(labels.size(), 5u);
}

TEST(PlanarCharts, SmallChartsGoBackToTheRestAndOptionsAreChecked) {
  // A sphere has no plane: with a 10° cone every planar chart is tiny, so all faces are given back
  // (one connected rest); with no area floor the same growth keeps them.
  const TriMesh sphere = shapes::sphere(24, 12);
  PlanarChartOptions o;
  o.max_normal_angle = 10;
  o.min_area_fraction = 0.05;
  const PlanarCharts rest = planar_charts(sphere, o);
  EXPECT_EQ(rest.num_planar, 0);
  EXPECT_EQ(rest.num_charts, 1);
  o.min_area_fraction = 0;
  EXPECT_GT(planar_charts(sphere, o).num_planar, 10);
  o.max_normal_angle = 90;
  EXPECT_THROW(planar_charts(sphere, o), InvalidInputError);
  o.max_normal_angle = 30;
  o.min_area_fraction = -1;
  EXPECT_THROW(planar_charts(sphere, o), InvalidInputError);
}

TEST(ProjectionLayout, IsIsometricOnAPlaneAndRejectsAFold) {
  const TriMesh flat = test::flat_patch(6, 2.0, Vec3(0, 0, 0));
  const std::optional<PolygonLayout> u = projection_layout(flat);
  ASSERT_TRUE(u.has_value());
  std::vector<Vec2> scaled = u->uv;
  for (Vec2& q : scaled) q.x() *= u->aspect;
  EXPECT_NEAR(measure_stretch(flat, scaled).l2, 1.0, 1e-9);
  EXPECT_NEAR(u->fill, 1.0, 1e-9);  // a square fills its rectangle
  // A tube folds over itself under any projection.
  EXPECT_FALSE(projection_layout(shapes::open_cylinder(16, 4)).has_value());
}

TEST(LscmLayout, UnrollsADevelopableStripAndKeepsOrientation) {
  // A quarter of a cylinder (developable, a disk): LSCM unrolls it nearly isometrically, where
  // a projection onto one plane stretches its sides.
  TriMesh m;
  const int n = 16, h = 4;
  for (int j = 0; j <= h; ++j)
    for (int i = 0; i <= n; ++i) {
      const double a = 0.5 * M_PI * i / n;
      m.positions.push_back(Vec3(std::cos(a), std::sin(a), 0.4 * j));
    }
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      m.faces.push_back({a, b, d});
      m.faces.push_back({a, d, c});
    }
  const std::optional<PolygonLayout> u = lscm_layout(m);
  ASSERT_TRUE(u.has_value());
  std::vector<Vec2> scaled = u->uv;
  for (Vec2& q : scaled) q.x() *= u->aspect;
  const StretchStats st = measure_stretch(m, scaled);
  EXPECT_EQ(st.flipped, 0);
  EXPECT_LT(st.l2, 1.01);
  EXPECT_GT(u->fill, 0.95);
  const std::optional<PolygonLayout> p = projection_layout(m);
  ASSERT_TRUE(p.has_value());
  std::vector<Vec2> ps = p->uv;
  for (Vec2& q : ps) q.x() *= p->aspect;
  EXPECT_LT(st.l2, measure_stretch(m, ps).l2);
  TriMesh bad = m;
  bad.faces[0][0] = 1000;
  EXPECT_THROW(lscm_layout(bad), InvalidInputError);
}

/// A hall 4 × 1.5 × 0.6 (the noisy floor and walls of open_box(n)) and the separate components of
/// \p clutter: a depth scan of a room.
TriMesh hall_with(int n, std::vector<TriMesh> clutter) {
  TriMesh room = open_box(n, 0.002);
  for (Vec3& p : room.positions) p = p.cwiseProduct(Vec3(4.0, 1.5, 0.6));
  clutter.insert(clutter.begin(), std::move(room));
  return shapes::disjoint_union(clutter);
}

/// A scanned room: a hall plus 40 small crumpled fragments (the clutter of a depth scan) so that
/// the scan segmentation runs.
TriMesh scanned_room() {
  std::vector<TriMesh> parts;
  for (int k = 0; k < 40; ++k)
    parts.push_back(test::crumpled_patch(3, 3, 0.08, 0.02,
                                         Vec3(4.5 + 0.12 * (k % 8), 0.12 * (k / 8), 0), k + 1));
  return hall_with(40, std::move(parts));
}

/// Options that compare the scan segmentations: no augmentation deadline, and one chart per
/// component left out (scan_single_max_faces = 0).
UnwrapOptions segmentations_compared() {
  UnwrapOptions o;
  o.augment_time_budget = 1e9;
  o.scan_single_max_faces = 0;
  return o;
}

TEST(UnwrapScan, PlanarChartsAndFreeBoundariesRaiseTheShareOfARoom) {
  // Measured: 0.171 (926 charts, L2 1.56) -> 0.627 (147 charts, L2 1.04); one chart per component
  // is left out of both (scan_single_max_faces = 0) so that the segmentations are compared.
  const TriMesh mesh = scanned_room();
  ASSERT_GT(analyze_topology(mesh).num_components, 32);  // the scan segmentation runs
  UnwrapOptions old_way = segmentations_compared();
  old_way.scan_planar_angle = 0;
  old_way.scan_free_boundary = false;
  UnwrapResult before, after;
  test::check_unwrap("room_old", mesh, old_way, &before);
  test::check_unwrap("room", mesh, segmentations_compared(), &after);  // no flips, overlaps; UVs in [0,1]²
  EXPECT_GT(after.report.effective_texel_share, before.report.effective_texel_share + 0.05)
      << before.report.effective_texel_share << " -> " << after.report.effective_texel_share;
  EXPECT_LT(after.report.final_l2, before.report.final_l2);
  EXPECT_THROW(
      [] {
        UnwrapOptions o;
        o.scan_planar_angle = 90;
        unwrap(shapes::sphere(8, 4), o);
      }(),
      InvalidInputError);
}

/// A hall with 40 copies of \p object (scaled by \p scale, lifted by \p z) on its floor in an
/// 8 x 5 grid, as separate components: the clutter of a depth scan.
TriMesh hall_with_grid(const TriMesh& object, double scale, double z) {
  std::vector<TriMesh> parts;
  for (int k = 0; k < 40; ++k) {
    TriMesh m = object;
    for (Vec3& p : m.positions) p = p * scale + Vec3(0.3 + 0.4 * (k % 8), 0.2 + 0.25 * (k / 8), z);
    parts.push_back(std::move(m));
  }
  return hall_with(24, std::move(parts));
}

/// A hall with 40 small open boxes on the floor: each box too small for planar charts of its
/// own, so the planar candidate halves it (scan_planar_normal_weight).
TriMesh room_with_boxes() { return hall_with_grid(open_box(4), 0.08, 0.01); }

TEST(UnwrapScan, PlanarCandidateHalvesAlongCreasesAndTopDownIgnoresTheWeight) {
  const TriMesh mesh = room_with_boxes();
  ASSERT_GT(analyze_topology(mesh).num_components, 32);  // the scan segmentation runs
  UnwrapOptions opt = segmentations_compared();
  opt.scan_planar_normal_weight = 0;
  UnwrapResult compact, creased;
  test::check_unwrap("boxes_w0", mesh, opt, &compact);
  opt.scan_planar_normal_weight = 1;
  test::check_unwrap("boxes_w1", mesh, opt, &creased);  // no flips, overlaps; UVs in [0,1]²
  // The boxes' halves follow their edges: flatter pieces, a higher share (measured: 269 charts,
  // L2 1.0411, share 0.6679 -> 276 charts, L2 1.0401, 0.6712).
  EXPECT_GT(creased.report.effective_texel_share, compact.report.effective_texel_share)
      << compact.report.effective_texel_share << " -> " << creased.report.effective_texel_share;
  // Without planar charts the weight is not read: the same layout, bit for bit.
  UnwrapOptions plain = opt;
  plain.scan_planar_angle = 0;
  plain.scan_free_boundary = false;
  const UnwrapResult a = unwrap(mesh, plain);
  plain.scan_planar_normal_weight = 8;
  const UnwrapResult b = unwrap(mesh, plain);
  EXPECT_EQ(a.param.uv, b.param.uv);
  EXPECT_EQ(a.param.uv_faces, b.param.uv_faces);
  UnwrapOptions bad;
  bad.scan_planar_normal_weight = -1;
  EXPECT_THROW(unwrap(shapes::sphere(8, 4), bad), InvalidInputError);
  bad.scan_planar_normal_weight = std::numeric_limits<double>::infinity();
  EXPECT_THROW(unwrap(shapes::sphere(8, 4), bad), InvalidInputError);
  UnwrapOptions bad_chart;
  bad_chart.chart_normal_weight = std::numeric_limits<double>::infinity();
  EXPECT_THROW(unwrap(shapes::sphere(8, 4), bad_chart), InvalidInputError);
}

/// A hall with 40 small double tori on the floor (closed clutter with handles, as a depth scan
/// fuses nearby surfaces): with the halvings off (scan_max_rounds = 0) each stays one chart, cut
/// to a disk and stretched (L2 > 2).
TriMesh room_with_double_tori() { return hall_with_grid(shapes::double_torus(24), 0.1, 0.05); }

TEST(UnwrapScan, RegrowingStretchedChartsRaisesTheShareAndLeavesTopDownAlone) {
  const TriMesh mesh = room_with_double_tori();
  ASSERT_GT(analyze_topology(mesh).num_components, 32);  // the scan segmentation runs
  UnwrapOptions opt = segmentations_compared();
  opt.scan_max_rounds = 0;  // no halvings: the charts left stretched are the tori
  // The top-down candidate with SLIM layouts would win both ways (0.4798): the planar one decides.
  opt.scan_top_down_free_layouts = false;
  opt.scan_regrow_l2 = 0;
  UnwrapResult halved, regrown;
  test::check_unwrap("clutter_halved", mesh, opt, &halved);
  opt.scan_regrow_l2 = 2;  // the default
  test::check_unwrap("clutter_regrown", mesh, opt, &regrown);  // no flips, overlaps; UVs in [0,1]²
  // The stretched charts are cut into patches within a normal cone and rebuilt: a lower L2 and a
  // higher share (measured: 41 charts, L2 3.32, share 0.057 -> 267 charts, L2 1.03, 0.436).
  EXPECT_GT(regrown.report.effective_texel_share, halved.report.effective_texel_share)
      << halved.report.effective_texel_share << " -> " << regrown.report.effective_texel_share;
  EXPECT_LT(regrown.report.final_l2, halved.report.final_l2);
  // Above scan_regrow_max_faces the pass is skipped: the layout without it, bit for bit.
  opt.scan_regrow_max_faces = mesh.num_faces() - 1;
  const UnwrapResult skipped = unwrap(mesh, opt);
  EXPECT_EQ(skipped.param.uv, halved.param.uv);
  EXPECT_EQ(skipped.param.uv_faces, halved.param.uv_faces);
  opt.scan_regrow_max_faces = UnwrapOptions{}.scan_regrow_max_faces;
  // The top-down candidate (no planar charts) never regrows: the same layout, bit for bit.
  UnwrapOptions plain = opt;
  plain.scan_planar_angle = 0;
  plain.scan_free_boundary = false;
  plain.scan_regrow_l2 = 0;
  const UnwrapResult a = unwrap(mesh, plain);
  plain.scan_regrow_l2 = 1.5;
  const UnwrapResult b = unwrap(mesh, plain);
  EXPECT_EQ(a.param.uv, b.param.uv);
  EXPECT_EQ(a.param.uv_faces, b.param.uv_faces);
  for (double bad_l2 : {0.5, -1.0, std::numeric_limits<double>::infinity()}) {
    UnwrapOptions bad;
    bad.scan_regrow_l2 = bad_l2;
    EXPECT_THROW(unwrap(shapes::sphere(8, 4), bad), InvalidInputError) << bad_l2;
  }
  UnwrapOptions bad_max;
  bad_max.scan_regrow_max_faces = -1;
  EXPECT_THROW(unwrap(shapes::sphere(8, 4), bad_max), InvalidInputError);
  for (double bad_angle : {0.0, 90.0}) {
    UnwrapOptions bad;
    bad.scan_regrow_angle = bad_angle;
    EXPECT_THROW(unwrap(shapes::sphere(8, 4), bad), InvalidInputError) << bad_angle;
  }
}

TEST(UnwrapScan, SlimLayoutsLowerTheStretchOfTheChartsAndKeepThemValid) {
#ifdef ADAPTEX_TEST_ASAN
  GTEST_SKIP() << "three unwraps of the hall: checked in the Release pass (about 175 s under the "
                  "sanitizers, whose SLIM and second-build paths the regrowth test and Slim.* run)";
#endif
  const TriMesh mesh = room_with_double_tori();
  ASSERT_GT(analyze_topology(mesh).num_components, 32);  // the scan segmentation runs
  UnwrapOptions opt = segmentations_compared();
  opt.scan_max_rounds = 0;  // no halvings: the stretched tori are regrown (scan_regrow_l2)
  opt.scan_top_down_free_layouts = false;  // the planar candidate decides (previous test)
  // Rectangles only: with the shapes' packing filling holes, the first build's layout packs as
  // well as the second one's on this mesh (both 0.4599), so the second build could not be seen.
  opt.scan_pack_shapes = false;
  opt.scan_slim_iterations = 0;
  UnwrapResult square, slim;
  test::check_unwrap("clutter_square", mesh, opt, &square);
  opt.scan_slim_iterations = UnwrapOptions{}.scan_slim_iterations;
  test::check_unwrap("clutter_slim", mesh, opt, &slim);  // no flips, overlaps; UVs in [0,1]²
  // The charts let their boundaries find their own shape: a lower L2, a higher share (measured:
  // 267 charts, L2 1.236, share 0.305 -> L2 1.030, 0.436, before the second build existed).
  EXPECT_LT(slim.report.final_l2, square.report.final_l2 - 0.1)
      << square.report.final_l2 << " -> " << slim.report.final_l2;
  EXPECT_GT(slim.report.effective_texel_share, square.report.effective_texel_share)
      << square.report.effective_texel_share << " -> " << slim.report.effective_texel_share;
  EXPECT_GT(slim.report.time_layouts, 0.0);
  // Short of min_texel_share, the planar candidate is also built with the SLIM tries scored by
  // fill^0.5 / L2² and the higher share kept (here the second build wins).
  ASSERT_LT(slim.report.effective_texel_share, opt.min_texel_share);
  UnwrapOptions first_only = opt;
  first_only.scan_slim_second_exponent = -1;
  const UnwrapResult one = unwrap(mesh, first_only);
  EXPECT_GT(slim.report.effective_texel_share, one.report.effective_texel_share)
      << one.report.effective_texel_share << " -> " << slim.report.effective_texel_share;
  UnwrapOptions bad;
  bad.scan_slim_iterations = -1;
  EXPECT_THROW(unwrap(shapes::sphere(8, 4), bad), InvalidInputError);
  for (double e : {-0.5, 1.5, std::numeric_limits<double>::quiet_NaN()}) {
    UnwrapOptions bad_e;
    bad_e.scan_slim_fill_exponent = e;
    EXPECT_THROW(unwrap(shapes::sphere(8, 4), bad_e), InvalidInputError) << e;
  }
  for (double e : {1.5, std::numeric_limits<double>::quiet_NaN(), -std::numeric_limits<double>::infinity()}) {
    UnwrapOptions bad_e;
    bad_e.scan_slim_second_exponent = e;
    EXPECT_THROW(unwrap(shapes::sphere(8, 4), bad_e), InvalidInputError) << e;
  }
}

}  // namespace
TEST(UnwrapScan, RejectedSlimLayoutsArePackedByShapeAndKeptWhenTheyWin) {
#ifdef ADAPTEX_TEST_ASAN
  GTEST_SKIP() << "six unwraps of three halls: checked in the Release pass";
#endif
  // The SLIM layouts that fill^1 / L2² rejects but fill^0.5 / L2² takes are packed too, and kept
  // only when the share is higher. Measured: on the room 3 of them win (0.653000 -> 0.653407); on
  // the tori (8) and the boxes (9) they lose (0.4797 < 0.4801, 0.6667 < 0.6712), so the charts get
  // their layouts back, bit for bit.
  struct Case {
    const char* name;
    TriMesh mesh;
    bool wins;
  };
  const Case cases[] = {{"room", scanned_room(), true},
                        {"tori", room_with_double_tori(), false},
                        {"boxes", room_with_boxes(), false}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    UnwrapOptions opt = segmentations_compared();
    opt.scan_regrow_max_faces = 0;  // neither the regrowth nor the second build
    opt.scan_slim_second_exponent = -1;
    const UnwrapResult without = unwrap(c.mesh, opt);
    opt.scan_slim_second_exponent = UnwrapOptions{}.scan_slim_second_exponent;
    UnwrapResult with;
    test::check_unwrap(c.name, c.mesh, opt, &with);  // no flips, overlaps; UVs in [0,1]²
    EXPECT_EQ(with.report.num_charts, without.report.num_charts);  // no new seams
    if (c.wins) {
      EXPECT_GT(with.report.effective_texel_share, without.report.effective_texel_share)
          << without.report.effective_texel_share << " -> " << with.report.effective_texel_share;
      EXPECT_LT(with.report.final_l2, without.report.final_l2);
    } else {
      EXPECT_EQ(with.param.uv, without.param.uv);
      EXPECT_EQ(with.param.uv_faces, without.param.uv_faces);
    }
  }
}

TEST(UnwrapScan, TopDownCandidateTakesFreeBoundaryLayoutsAndWinsWithThem) {
#ifdef ADAPTEX_TEST_ASAN
  GTEST_SKIP() << "two unwraps of the hall: checked in the Release pass (the SLIM paths run under "
                  "the sanitizers in Slim.* and the regrowth test)";
#endif
  // The tori left whole (no halvings) are stretched in the top-down candidate's disk layouts and
  // the planar candidate (regrown) wins; with the free-boundary and SLIM layouts the top-down
  // candidate's charts (whole tori, cut to disks) win (measured: 0.4598 -> 0.4798; L2 1.028 ->
  // 1.082, but far fewer charts and gutters).
  const TriMesh mesh = room_with_double_tori();
  ASSERT_GT(analyze_topology(mesh).num_components, 32);  // the scan segmentation runs
  UnwrapOptions opt = segmentations_compared();
  opt.scan_max_rounds = 0;
  opt.scan_top_down_free_layouts = false;
  UnwrapResult disk, free;
  test::check_unwrap("clutter_top_down_disk", mesh, opt, &disk);
  opt.scan_top_down_free_layouts = true;  // the default
  test::check_unwrap("clutter_top_down_free", mesh, opt, &free);  // no flips, overlaps; UVs in [0,1]²
  EXPECT_GT(free.report.effective_texel_share, disk.report.effective_texel_share)
      << disk.report.effective_texel_share << " -> " << free.report.effective_texel_share;
  EXPECT_LT(free.report.num_charts, disk.report.num_charts);  // the other candidate's charts
}

TEST(UnwrapScan, TheTopDownCandidateKeepsItsUnfoldedLayoutsWhereTheyPackBetter) {
#ifdef ADAPTEX_TEST_ASAN
  GTEST_SKIP() << "two unwraps of a 20k-face scan: checked in the Release pass";
#endif
  // On this scan the top-down candidate's free-boundary layouts pack to a lower share than its
  // unfolded (disk) layouts, so pack_unfolded() keeps the latter: taking the free layouts costs no
  // share against leaving them off (measured 0.7805 both ways; 0.7739 with the free layouts
  // when pack_unfolded() does not repack).
  const TriMesh mesh = shapes::synthetic_scan(20000, 100, 10);
  UnwrapOptions opt = segmentations_compared();
  opt.scan_top_down_free_layouts = false;
  UnwrapResult disk, free;
  test::check_unwrap("synthetic_top_down_disk", mesh, opt, &disk);
  opt.scan_top_down_free_layouts = true;  // the default
  test::check_unwrap("synthetic_top_down_free", mesh, opt, &free);
  EXPECT_GE(free.report.effective_texel_share, disk.report.effective_texel_share)
      << disk.report.effective_texel_share << " -> " << free.report.effective_texel_share;
}

}  // namespace adaptex
