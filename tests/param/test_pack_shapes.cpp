// Tests of pack_shapes(): placed triangles of different charts are disjoint and at least the gap
// apart (checked on the triangles themselves, not on the raster), inside the padded square, at one
// scale; L-shapes nest (more coverage than their bounding rectangles get); thousands of tiny
// charts, the minimum side, quarter turns, progress, cancel and bad input.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>
#include <random>
#include <string>
#include <unordered_map>
#include <vector>

#include "adaptex/core/errors.h"
#include "adaptex/param/pack.h"
#include "../asan_detect.h"
#include "triangle_distance.h"

namespace adaptex {
namespace {

using test::cross;
using test::triangle_distance;
using test::triangles_meet;
using test::Tri;

/// Asserts every placed vertex lies in [gap, 1 - gap]² and that triangles of different charts do
/// not meet and are at least \p gap apart (broad phase: a grid of buckets). Returns the area the
/// placed triangles cover.
double check_shapes(const std::vector<ChartShape>& charts, const std::vector<ShapePlacement>& pl,
                    double gap) {
  EXPECT_EQ(pl.size(), charts.size());
  std::vector<Tri> tris;
  std::vector<int> owner;
  double covered = 0;
  for (size_t c = 0; c < charts.size(); ++c) {
    EXPECT_GE(pl[c].turns, 0);
    EXPECT_LE(pl[c].turns, 3);
    for (const Vec2& p : charts[c].uv) {
      const Vec2 q = pl[c].apply(p);
      EXPECT_GE(q.minCoeff(), gap - 1e-12) << c;
      EXPECT_LE(q.maxCoeff(), 1 - gap + 1e-12) << c;
    }
    for (const Face& f : charts[c].faces) {
      const Tri t{pl[c].apply(charts[c].uv[f[0]]), pl[c].apply(charts[c].uv[f[1]]),
                  pl[c].apply(charts[c].uv[f[2]])};
      covered += 0.5 * std::abs(cross(t[1] - t[0], t[2] - t[0]));
      tris.push_back(t);
      owner.push_back(static_cast<int>(c));
    }
  }
  const int cells = 128;
  std::unordered_map<long, std::vector<int>> bucket;
  const auto key = [&](int i, int j) { return static_cast<long>(i) * 1000003L + j; };
  for (size_t t = 0; t < tris.size(); ++t) {
    Vec2 lo = tris[t][0].cwiseMin(tris[t][1]).cwiseMin(tris[t][2]) - Vec2::Constant(gap);
    Vec2 hi = tris[t][0].cwiseMax(tris[t][1]).cwiseMax(tris[t][2]) + Vec2::Constant(gap);
    for (int i = static_cast<int>(std::floor(lo.x() * cells)); i <= static_cast<int>(hi.x() * cells); ++i)
      for (int j = static_cast<int>(std::floor(lo.y() * cells)); j <= static_cast<int>(hi.y() * cells); ++j)
        bucket[key(i, j)].push_back(static_cast<int>(t));
  }
  long meeting = 0, close = 0;
  for (const auto& [k, list] : bucket)
    for (size_t a = 0; a < list.size(); ++a)
      for (size_t b = a + 1; b < list.size(); ++b) {
        const int s = list[a], t = list[b];
        if (owner[s] == owner[t]) continue;
        if (triangles_meet(tris[s], tris[t])) ++meeting;
        else if (gap > 0 && triangle_distance(tris[s], tris[t]) < gap * (1 - 1e-9)) ++close;
      }
  EXPECT_EQ(meeting, 0);
  EXPECT_EQ(close, 0);
  return covered;
}

/// A chart of unit squares (two triangles each) at the given integer cells, times \p size.
ChartShape squares(const std::vector<std::pair<int, int>>& cells, double size) {
  ChartShape c;
  for (const auto& [i, j] : cells) {
    const int v = static_cast<int>(c.uv.size());
    for (const auto& [di, dj] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 1}})
      c.uv.push_back(size * Vec2(i + di, j + dj));
    c.faces.push_back({v, v + 1, v + 2});
    c.faces.push_back({v, v + 2, v + 3});
  }
  return c;
}

/// A star-shaped random polygon fanned from its centre, of radius about \p r, irregular.
ChartShape random_blob(std::mt19937& rng, double r) {
  std::uniform_real_distribution<double> u(0.3, 1.0);
  ChartShape c;
  c.uv.push_back(Vec2(0.1 * r, -0.2 * r));
  const int k = 3 + static_cast<int>(rng() % 9);
  for (int i = 0; i < k; ++i) {
    const double a = 2 * M_PI * (i + 0.5 * u(rng)) / k;
    c.uv.push_back(r * u(rng) * Vec2(std::cos(a), std::sin(a)) + c.uv[0]);
  }
  for (int i = 0; i < k; ++i) c.faces.push_back({0, 1 + i, 1 + (i + 1) % k});
  return c;
}

TEST(PackShapes, IrregularChartsAreDisjointPaddedAndAtOneScale) {
  std::mt19937 rng(7);
  std::vector<ChartShape> charts;
  for (int i = 0; i < 300; ++i) charts.push_back(random_blob(rng, std::pow(10.0, -2.0 * (i % 37) / 37.0)));
  for (int i = 0; i < 40; ++i) charts.push_back(squares({{0, 0}, {1, 0}, {2, 0}, {0, 1}}, 0.3));  // L
  for (double gap : {0.0, 1.0 / 512}) {
    SCOPED_TRACE(gap);
    ShapePackOptions o;
    o.padding = gap;
    const std::vector<ShapePlacement> pl = pack_shapes(charts, o);
    const double covered = check_shapes(charts, pl, gap);
    EXPECT_GT(covered, 0.4);
    for (const ShapePlacement& p : pl) EXPECT_DOUBLE_EQ(p.scale, pl[0].scale);  // no min_side
  }
}

TEST(PackShapes, LShapesNestTighterThanTheirRectangles) {
  // L-trominoes fill 3/4 of their bounding box: rectangles cannot cover more than that, turned L's
  // that interlock can.
  std::vector<ChartShape> charts(400, squares({{0, 0}, {1, 0}, {0, 1}}, 1.0));
  const std::vector<ShapePlacement> pl = pack_shapes(charts, {});
  const double shapes = check_shapes(charts, pl, 0.0);
  std::vector<Vec2> sizes(charts.size(), Vec2(2, 2));
  RectPackOptions ro;
  ro.may_turn = true;
  double rects = 0;
  for (const RectPlacement& r : pack_rectangles(sizes, ro)) rects += 0.75 * r.size.prod();
  EXPECT_GT(shapes, rects + 0.05) << shapes << " against " << rects;
  std::printf("L-trominoes: shapes cover %.3f, rectangles %.3f\n", shapes, rects);
  int turned = 0;
  for (const ShapePlacement& p : pl) turned += p.turns != 0;
  EXPECT_GT(turned, 0);
}

TEST(PackShapes, ThousandsOfTinyChartsAndAFewLargeOnes) {
  std::mt19937 rng(3);
  std::vector<ChartShape> charts;
  for (int i = 0; i < 5; ++i) charts.push_back(random_blob(rng, 1.0));
  for (int i = 0; i < 4000; ++i) charts.push_back(random_blob(rng, 1e-3 * (1 + i % 5)));
  ShapePackOptions o;
  o.padding = 1.0 / 2048;
  o.min_side = 2.0 / 2048;
  const std::vector<ShapePlacement> pl = pack_shapes(charts, o);
  check_shapes(charts, pl, o.padding);
  for (size_t c = 0; c < charts.size(); ++c) {  // the minimum texel floor
    Vec2 lo = Vec2::Constant(1e300), hi = -lo;
    for (const Vec2& p : charts[c].uv) lo = lo.cwiseMin(pl[c].apply(p)), hi = hi.cwiseMax(pl[c].apply(p));
    EXPECT_GE((hi - lo).minCoeff(), o.min_side * (1 - 1e-9)) << c;
  }
}

TEST(PackShapes, SmallChartsFillTheHoleUnderAnArch) {
  // An arch (legs at columns 0 and 9, a crossbar on rows 6-7) dropped from above leaves its
  // 8 x 6 inside empty under the horizon; without turning, the four unit squares that follow can
  // only go there or on top of the arch. They go inside: none reaches the crossbar.
  std::vector<std::pair<int, int>> arch;
  for (int j = 0; j < 6; ++j) arch.push_back({0, j}), arch.push_back({9, j});
  for (int i = 0; i < 10; ++i) arch.push_back({i, 6}), arch.push_back({i, 7});
  std::vector<ChartShape> charts{squares(arch, 1.0)};
  for (int i = 0; i < 4; ++i) charts.push_back(squares({{0, 0}}, 1.0));
  ShapePackOptions o;
  o.padding = 1.0 / 512;
  o.may_turn = false;
  const std::vector<ShapePlacement> pl = pack_shapes(charts, o);
  check_shapes(charts, pl, o.padding);
  const double crossbar = pl[0].apply(Vec2(0, 6)).y();
  const double left = pl[0].apply(Vec2(1, 0)).x(), right = pl[0].apply(Vec2(9, 0)).x();
  for (size_t c = 1; c < charts.size(); ++c)
    for (const Vec2& p : charts[c].uv) {
      const Vec2 q = pl[c].apply(p);
      EXPECT_LT(q.y(), crossbar) << c;
      EXPECT_GT(q.x(), left) << c;
      EXPECT_LT(q.x(), right) << c;
    }
}

/// Coverage of \p count random blobs (seed \p seed) packed with gap \p padding at the default
/// raster and at \p resolution cells (each packing checked by check_shapes()).
std::pair<double, double> default_and_coarse_cover(int count, unsigned seed, double padding,
                                                   int resolution) {
  std::mt19937 rng(seed);
  std::vector<ChartShape> charts;
  for (int i = 0; i < count; ++i) charts.push_back(random_blob(rng, 1.0 + 0.5 * (i % 3)));
  ShapePackOptions o;
  o.padding = padding;
  const double fine = check_shapes(charts, pack_shapes(charts, o), o.padding);
  o.resolution = resolution;
  return {fine, check_shapes(charts, pack_shapes(charts, o), o.padding)};
}

TEST(PackShapes, ManyChartsGetAFinerRasterByDefault) {
#ifdef ADAPTEX_TEST_ASAN
  GTEST_SKIP() << "packings of 5,000 and 8,000 charts and their triangle checks: a layout "
                  "property, checked in the Release pass (the other PackShapes tests run the same "
                  "code here)";
#endif
  // 5,000 charts: the default raster (4,096 cells, a chart of the mean size 32 cells across)
  // rounds each chart up by less than 2,048 cells do, so the same charts cover more of the square.
  const auto [fine, coarse] = default_and_coarse_cover(5000, 13, 1.0 / 1024, 2048);
  EXPECT_GT(fine, coarse * 1.03) << coarse << " -> " << fine;
  std::printf("5,000 charts: 2,048 cells cover %.3f, the default %.3f\n", coarse, fine);
  // From 7,169 to 12,288 charts the default is 8,192 cells (a chart of the mean size about 90
  // cells across instead of 45).
  const auto [finest, fine_8k] = default_and_coarse_cover(8000, 17, 1.0 / 2048, 4096);
  EXPECT_GT(finest, fine_8k * 1.01) << fine_8k << " -> " << finest;
  std::printf("8,000 charts: 4,096 cells cover %.3f, the default %.3f\n", fine_8k, finest);
}

TEST(PackShapes, GapsThatDoNotFitAreHalved) {
  std::vector<ChartShape> charts(1000, squares({{0, 0}}, 1.0));
  ShapePackOptions o;
  o.padding = 0.08;  // 1000 gaps of 0.08 cannot fit in the square
  double gap = -1;
  const std::vector<ShapePlacement> pl = pack_shapes(charts, o, &gap);
  // The gap kept is a halving of the requested one, and the placed triangles keep it.
  EXPECT_LT(gap, o.padding);
  EXPECT_GT(gap, 0.0);
  EXPECT_DOUBLE_EQ(std::exp2(std::round(std::log2(o.padding / gap))), o.padding / gap);
  check_shapes(charts, pl, gap);
  // A gap that fits comes back unchanged.
  const std::vector<ChartShape> few(20, squares({{0, 0}}, 1.0));
  o.padding = 1.0 / 512;
  pack_shapes(few, o, &gap);
  EXPECT_EQ(gap, o.padding);
}

TEST(PackShapes, OneThreadGivesTheSamePlacements) {
  // The placements do not depend on the threads: on one thread every placement must be the same,
  // with gaps that fit and that do not (0.08: the gap is halved).
  std::mt19937 rng(5);
  std::vector<ChartShape> charts;
  for (int i = 0; i < 200; ++i) charts.push_back(random_blob(rng, std::pow(10.0, -1.5 * (i % 17) / 17.0)));
  for (double gap : {1.0 / 512, 0.08}) {
    SCOPED_TRACE(gap);
    ShapePackOptions o;
    o.padding = gap;
    const std::vector<ShapePlacement> together = pack_shapes(charts, o);
    std::vector<ShapePlacement> alone;
    tbb::task_arena(1).execute([&] { alone = pack_shapes(charts, o); });
    ASSERT_EQ(together.size(), alone.size());
    for (size_t c = 0; c < alone.size(); ++c) {
      EXPECT_EQ(together[c].offset, alone[c].offset) << c;
      EXPECT_EQ(together[c].scale, alone[c].scale) << c;
      EXPECT_EQ(together[c].turns, alone[c].turns) << c;
    }
  }
}

TEST(PackShapes, WithoutTurningNoChartIsTurned) {
  std::mt19937 rng(11);
  std::vector<ChartShape> charts;
  for (int i = 0; i < 200; ++i) charts.push_back(random_blob(rng, 0.5 + (i % 4)));
  ShapePackOptions o;
  o.may_turn = false;
  o.padding = 0.004;
  const std::vector<ShapePlacement> pl = pack_shapes(charts, o);
  check_shapes(charts, pl, o.padding);
  for (const ShapePlacement& p : pl) EXPECT_EQ(p.turns, 0);
}

TEST(PackShapes, ReportsProgressAndCancels) {
  std::vector<ChartShape> charts(500, squares({{0, 0}, {1, 0}}, 1.0));
  ShapePackOptions o;
  int calls = 0;
  o.progress = [&](std::string_view phase, double f) {
    EXPECT_EQ(phase, "pack");
    EXPECT_GE(f, 0.0);
    EXPECT_LE(f, 1.0);
    return ++calls < 2;
  };
  EXPECT_THROW(pack_shapes(charts, o), CancelledError);
  EXPECT_EQ(calls, 2);
}

TEST(PackShapes, WhenNoTrialFitsTheScaleShrinksUntilItDoes) {
  // Five equal squares: at the first scale (about where their boxes fill 0.65 of the square, side
  // 0.35-0.36) two fit in a row and three rows do not fit; with one trial, the fit test then runs
  // and the scale shrinks by steps of 0.8 until three fit in a row (measured 0.276).
  const std::vector<ChartShape> charts(5, squares({{0, 0}}, 1.0));
  ShapePackOptions o;
  o.trials = 1;
  const std::vector<ShapePlacement> pl = pack_shapes(charts, o);
  check_shapes(charts, pl, 0.0);
  for (const ShapePlacement& p : pl) {
    EXPECT_EQ(p.scale, pl[0].scale);
    EXPECT_GT(p.scale, 0.25);
    EXPECT_LT(p.scale, 1.0 / 3);
  }
}

TEST(PackShapes, ProgressNeverStepsBack) {
  std::vector<ChartShape> charts(2000, squares({{0, 0}, {1, 0}}, 1.0));
  ShapePackOptions o;
  std::vector<double> seen;
  o.progress = [&](std::string_view, double f) {
    seen.push_back(f);  // pack_shapes() serialises its calls
    return true;
  };
  pack_shapes(charts, o);
  ASSERT_GT(seen.size(), 3u);
  for (size_t i = 1; i < seen.size(); ++i) EXPECT_GE(seen[i], seen[i - 1]) << "call " << i;
}

TEST(PackShapes, BadInputIsRejected) {
  ShapePackOptions o;
  EXPECT_THROW(pack_shapes({}, o), InvalidInputError);
  ChartShape bad_index = squares({{0, 0}}, 1.0);
  bad_index.faces[0][2] = 7;
  EXPECT_THROW(pack_shapes({bad_index}, o), InvalidInputError);
  ChartShape nan = squares({{0, 0}}, 1.0);
  nan.uv[1].x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(pack_shapes({nan}, o), InvalidInputError);
  o.padding = 0.25;
  EXPECT_THROW(pack_shapes({squares({{0, 0}}, 1.0)}, o), InvalidInputError);
  o.padding = 0;
  o.resolution = 10;
  EXPECT_THROW(pack_shapes({squares({{0, 0}}, 1.0)}, o), InvalidInputError);
  // A chart without triangles (a point) and one of a single degenerate triangle still pack.
  ChartShape point;
  point.uv.push_back(Vec2(3, 4));
  ChartShape flat;
  flat.uv = {Vec2(0, 0), Vec2(1, 0), Vec2(2, 0)};
  flat.faces = {{0, 1, 2}};
  const std::vector<ChartShape> odd{point, flat, squares({{0, 0}}, 1.0)};
  check_shapes(odd, pack_shapes(odd, ShapePackOptions{}), 0.0);
}

}  // namespace
}  // namespace adaptex

namespace adaptex {
namespace {

/// FNV-1a over the bits of every placement.
uint64_t placement_hash(const std::vector<ShapePlacement>& pl) {
  uint64_t h = 1469598103934665603ull;
  const auto mix = [&](const void* p, size_t n) {
    for (size_t i = 0; i < n; ++i) h = (h ^ static_cast<const unsigned char*>(p)[i]) * 1099511628211ull;
  };
  for (const ShapePlacement& p : pl) {
    mix(p.offset.data(), 2 * sizeof(double));
    mix(&p.scale, sizeof(double));
    mix(&p.turns, sizeof(int));
  }
  return h;
}

TEST(PackShapes, PruningTheDropsKeepsThePlacements) {
  // The drop search skips positions only when a lower bound of their score already loses (the
  // horizon's tall columns, the chart's lowest column, the column that ruled out the position
  // before). Such speed-ups must not move a single chart: the placements of 3,000 random charts
  // on a 4,096-cell raster are pinned to their hash (the same before the last of those pruning
  // rules, and different when its bound is off by one row). Update the value only with an
  // intended change of the packing (docs/decisions.md, "Packing: the column that ruled out the
  // last position is tried early").
  std::mt19937 rng(11);
  std::vector<ChartShape> charts;
  for (int i = 0; i < 3000; ++i) charts.push_back(random_blob(rng, std::pow(10.0, -1.2 * (i % 13) / 13.0)));
  ShapePackOptions o;
  o.padding = 1.0 / 1024;
  o.resolution = 4096;
  const std::vector<ShapePlacement> pl = pack_shapes(charts, o);
  check_shapes(charts, pl, o.padding);
  EXPECT_EQ(placement_hash(pl), 0x41b4344d6e5cca81ull) << std::hex << placement_hash(pl);
}

}  // namespace
}  // namespace adaptex
