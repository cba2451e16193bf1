// The linear-time no-overlap proof of flip-free remaps (overlap_certificate.h), checked against the
// exact pair count (count_overlapping_triangles), and the bounded per-chart flow lattices
// (chart_lattice_cells, atlas_flow.h).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "adaptex/adapt/atlas_flow.h"
#include "adaptex/adapt/overlap_certificate.h"
#include "adaptex/adapt/remap.h"
#include "adaptex/core/errors.h"
#include "adaptex/param/stretch.h"

namespace adaptex {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// A grid chart of nx x ny quads (2 triangles each, counter-clockwise) over [x0, x0+w] x [y0, y0+h],
/// appended to \p p as chart \p chart.
void add_grid_chart(Parameterization& p, int nx, int ny, double x0, double y0, double w, double h, int chart) {
  const int base = static_cast<int>(p.uv.size());
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      p.uv.push_back(Vec2(x0 + w * i / nx, y0 + h * j / ny));
      p.wedge_vertex.push_back(static_cast<int>(p.wedge_vertex.size()));
    }
  auto id = [&](int i, int j) { return base + j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      p.uv_faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      p.uv_faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      p.face_chart.push_back(chart);
      p.face_chart.push_back(chart);
    }
  p.num_charts = std::max(p.num_charts, chart + 1);
}

/// A strip chart bent along a circular arc of \p turns full turns around (0.5, 0.5): every triangle
/// keeps its orientation, and beyond one turn the strip lies on itself.
Parameterization bent_strip(double turns) {
  Parameterization p;
  add_grid_chart(p, 120, 3, 0.0, 0.0, 1.0, 0.1, 0);
  Parameterization out = p;
  for (size_t w = 0; w < p.uv.size(); ++w) {
    const double s = p.uv[w].x(), t = p.uv[w].y();
    const double a = 2 * kPi * turns * s, r = 0.4 - 0.5 * t - 0.02 * s;  // a slow spiral inward
    out.uv[w] = Vec2(0.5 + r * std::cos(a), 0.5 + r * std::sin(a));
  }
  return out;
}

int flipped(const Parameterization& before, const Parameterization& after) {
  int n = 0;
  for (int f = 0; f < static_cast<int>(before.uv_faces.size()); ++f)
    n += uv_signed_area(after, f) * uv_signed_area(before, f) <= 0;
  return n;
}

TEST(OverlapCertificate, ProvesSeparatedChartsAndRefusesOverlappingOnes) {
  Parameterization p;
  add_grid_chart(p, 6, 4, 0.05, 0.05, 0.4, 0.3, 0);
  add_grid_chart(p, 5, 5, 0.55, 0.55, 0.35, 0.35, 1);
  const OverlapCertificate cert(p, 1e-12);
  ASSERT_TRUE(cert.applicable());
  EXPECT_TRUE(cert.certifies(p));
  EXPECT_EQ(count_overlapping_triangles(p), 0);
  // Chart 1 translated onto chart 0: no flip, but overlapping pairs.
  Parameterization moved = p;
  for (size_t w = 35; w < moved.uv.size(); ++w) moved.uv[w] -= Vec2(0.45, 0.45);
  ASSERT_EQ(flipped(p, moved), 0);
  EXPECT_GT(count_overlapping_triangles(moved), 0);
  EXPECT_FALSE(cert.certifies(moved));
}

TEST(OverlapCertificate, RefusesAChartThatLiesOnItselfWithoutFlipping) {
  const Parameterization flat = [] {
    Parameterization p;
    add_grid_chart(p, 120, 3, 0.0, 0.0, 1.0, 0.1, 0);
    return p;
  }();
  const OverlapCertificate cert(flat, 1e-12);
  ASSERT_TRUE(cert.applicable());
  const Parameterization once = bent_strip(0.8), twice = bent_strip(1.3);
  ASSERT_EQ(flipped(flat, once), 0);
  ASSERT_EQ(flipped(flat, twice), 0);
  EXPECT_EQ(count_overlapping_triangles(once), 0);
  EXPECT_TRUE(cert.certifies(once));
  EXPECT_GT(count_overlapping_triangles(twice), 0);  // the strip's ends lie on each other
  EXPECT_FALSE(cert.certifies(twice));
}

TEST(OverlapCertificate, NeverCertifiesAnOverlappingFlipFreeLayout) {
  // Random smooth distortions of a two-chart layout, strong enough that many overlap: whenever no
  // face flips, a certified layout must have no overlapping pair.
  Parameterization p;
  add_grid_chart(p, 8, 8, 0.1, 0.1, 0.35, 0.35, 0);
  add_grid_chart(p, 8, 8, 0.55, 0.1, 0.35, 0.35, 1);
  const OverlapCertificate cert(p, 1e-12);
  ASSERT_TRUE(cert.applicable());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1, 1);
  int certified = 0, refused = 0, wrong = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const double ax = 0.25 * U(rng), ay = 0.25 * U(rng), fx = 2 + 4 * std::abs(U(rng)), shift = 0.12 * U(rng);
    Parameterization q = p;
    for (size_t w = 0; w < q.uv.size(); ++w) {
      const Vec2 u = p.uv[w];
      const double side = w < 81 ? 1.0 : -1.0;  // the charts move toward or away from each other
      q.uv[w] = u + Vec2(side * shift + ax * 0.1 * std::sin(fx * u.y()), ay * 0.1 * std::sin(fx * u.x()));
    }
    if (flipped(p, q) > 0) continue;
    const bool ok = cert.certifies(q);
    certified += ok;
    refused += !ok;
    wrong += ok && count_overlapping_triangles(q) > 0;
  }
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(certified, 20);  // the certificate is not vacuous
  EXPECT_GT(refused, 20);    // and the trials did include charts running into each other
}

TEST(OverlapCertificate, DoesNotApplyToLayoutsOutsideItsArgument) {
  // A chart with faces of both orientations.
  Parameterization mixed;
  add_grid_chart(mixed, 2, 2, 0.1, 0.1, 0.3, 0.3, 0);
  std::swap(mixed.uv_faces[0][1], mixed.uv_faces[0][2]);
  EXPECT_FALSE(OverlapCertificate(mixed, 1e-12).applicable());
  EXPECT_FALSE(OverlapCertificate(mixed, 1e-12).certifies(mixed));
  // Two fans sharing only a wedge (a pinched boundary wedge).
  Parameterization pinched;
  pinched.uv = {Vec2(0.5, 0.5), Vec2(0.6, 0.5), Vec2(0.6, 0.6), Vec2(0.4, 0.5), Vec2(0.4, 0.4)};
  pinched.uv_faces = {{0, 1, 2}, {0, 3, 4}};
  pinched.num_charts = 1;
  EXPECT_FALSE(OverlapCertificate(pinched, 1e-12).applicable());
  // A degenerate face.
  Parameterization flat;
  flat.uv = {Vec2(0.1, 0.1), Vec2(0.2, 0.2), Vec2(0.3, 0.3)};
  flat.uv_faces = {{0, 1, 2}};
  EXPECT_FALSE(OverlapCertificate(flat, 1e-12).applicable());
  // Bad input is an error, not a silent answer.
  Parameterization broken = flat;
  broken.uv_faces = {{0, 1, 7}};
  EXPECT_THROW(OverlapCertificate(broken, 1e-12), InvalidInputError);
  Parameterization fewer = mixed;
  fewer.uv.pop_back();
  EXPECT_THROW(OverlapCertificate(mixed, 1e-12).certifies(fewer), InvalidInputError);
}

TEST(OverlapCertificate, SafeRemapStillRefusesChartsRunningIntoEachOther) {
  // A warp of the whole square that pushes chart 0 into chart 1 (no face flips): safe_remap must damp
  // it until nothing overlaps, whether or not the certificate applies.
  Parameterization p;
  add_grid_chart(p, 6, 6, 0.1, 0.3, 0.35, 0.35, 0);
  add_grid_chart(p, 6, 6, 0.5, 0.3, 0.35, 0.35, 1);
  GridWarp g = GridWarp::uniform(16);
  for (int j = 1; j < 16; ++j)
    for (int i = 1; i < 16; ++i) {
      const double x = double(i) / 16;
      g.at(i, j).x() = x + 0.6 * x * (1 - x) * (x < 0.5 ? 1.0 : 0.3);
    }
  const SafeRemapResult r = safe_remap(p, {&g});
  EXPECT_EQ(count_overlapping_triangles(r.param), 0);
  EXPECT_EQ(flipped(p, r.param), 0);
  EXPECT_LT(r.mean_damping, 1.0);  // the full warp would have overlapped: something was damped
  EXPECT_GT(count_overlapping_triangles(remap_parameterization(p, {&g})), 0);
}

TEST(OverlapCertificate, OverlapDampingLeavesALayoutThatOverlapsItselfToTheGlobalBlend) {
  // SafeRemapOptions::damp_overlaps damps the faces of overlapping pairs locally only when the input
  // has none (as damp_crossings): with stacked charts (an artist's mirrored or stacked UVs given to
  // `adaptex reparam`) the result is the one without it, and still adds no overlapping pair.
  Parameterization p;
  add_grid_chart(p, 6, 6, 0.1, 0.3, 0.35, 0.35, 0);
  add_grid_chart(p, 6, 6, 0.2, 0.35, 0.35, 0.35, 1);  // lies on chart 0
  add_grid_chart(p, 6, 6, 0.6, 0.3, 0.3, 0.35, 2);
  const long before = count_overlapping_triangles(p);
  ASSERT_GT(before, 0);
  GridWarp g = GridWarp::uniform(16);
  for (int j = 1; j < 16; ++j)
    for (int i = 1; i < 16; ++i) {
      const double x = double(i) / 16;
      g.at(i, j).x() = x + 0.6 * x * (1 - x) * (x < 0.5 ? 0.3 : 1.0);  // chart 2 into chart 1
    }
  SafeRemapOptions on, off;
  off.damp_overlaps = false;
  ASSERT_TRUE(on.damp_overlaps);
  const SafeRemapResult a = safe_remap(p, {&g}, on), b = safe_remap(p, {&g}, off);
  EXPECT_TRUE(a.param.uv == b.param.uv);
  EXPECT_EQ(a.mean_damping, b.mean_damping);
  EXPECT_EQ(check_remap(p, a.param).overlaps, 0);
  EXPECT_EQ(flipped(p, a.param), 0);
}

TEST(AtlasFlow, ChartLatticesAddUpToAboutOneSquareLattice) {
  // Elongated charts: their square lattices would add up to far more than one 128-cell lattice.
  std::vector<ChartMove> moves;
  for (int c = 0; c < 8; ++c) {
    ChartMove m;
    m.src = UvRect{Vec2(0.02 + 0.12 * c, 0.02), Vec2(0.12 + 0.12 * c, 0.98)};
    m.dst_lo = m.src.lo;
    moves.push_back(m);
  }
  const std::vector<int> n = chart_lattice_cells(moves, 128, 8);
  ASSERT_EQ(n.size(), moves.size());
  double points = 0;
  for (int k : n) {
    EXPECT_GE(k, 8);
    EXPECT_LE(k, 128);
    EXPECT_EQ(k % 4, 0) << "from 16 cells on, a multiple of 4 (coarse-to-fine advection)";
    points += double(k + 1) * (k + 1);
  }
  EXPECT_LE(points, 1.1 * 129 * 129);
  EXPECT_GE(points, 0.8 * 129 * 129);  // the budget is used, not wasted
  // One chart filling the square gets the full lattice.
  ChartMove whole;
  whole.src = UvRect{Vec2(0, 0), Vec2(1, 1)};
  EXPECT_EQ(chart_lattice_cells({whole}, 128, 8), std::vector<int>{128});
  EXPECT_THROW(chart_lattice_cells({whole}, 0, 8), InvalidInputError);
}

}  // namespace
}  // namespace adaptex
