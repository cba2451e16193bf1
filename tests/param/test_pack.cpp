// Tests of pack_rectangles(sizes, RectPackOptions): thousands of rectangles, the minimum side,
// progress and cancel, hostile sizes, and equality with the older entry points.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "adaptex/core/errors.h"
#include "adaptex/param/pack.h"

namespace adaptex {
namespace {

/// Rectangles of sizes spread over three decades (a few large charts, many small ones) and
/// aspect ratios 1/4-4, deterministic.
std::vector<Vec2> spread_rectangles(int n) {
  std::vector<Vec2> sizes(n);
  for (int i = 0; i < n; ++i) {
    const double side = std::pow(10.0, -3.0 * ((i * 7919) % 1000) / 1000.0);
    const double aspect = std::pow(4.0, ((i * 31) % 17 - 8) / 8.0);
    sizes[i] = Vec2(side * std::sqrt(aspect), side / std::sqrt(aspect));
  }
  return sizes;
}

/// Asserts that the placements are inside [gap, 1 - gap]², pairwise at least \p gap apart (a
/// sweep over x: O(n log n + pairs that overlap in x)), have the (possibly turned) shape of the
/// input, all at one scale except those raised to \p min_side, and returns the area they cover.
double check_layout(const std::vector<Vec2>& sizes, const std::vector<RectPlacement>& pl,
                    const std::vector<char>& turned, double gap, double min_side) {
  const size_t n = sizes.size();
  EXPECT_EQ(pl.size(), n);
  EXPECT_EQ(turned.size(), n);
  double used = 0, scale = -1, largest = 0;
  for (const Vec2& s : sizes) largest = std::max(largest, s.maxCoeff());
  for (size_t i = 0; i < n; ++i) {
    const Vec2 shape = turned[i] ? Vec2(sizes[i].y(), sizes[i].x()) : sizes[i];
    const double k = pl[i].size.x() / shape.x();
    EXPECT_NEAR(pl[i].size.y() / shape.y(), k, 1e-9 * k) << i;
    EXPECT_GE(pl[i].size.minCoeff(), min_side * (1 - 1e-12)) << i;
    // Not raised to min_side nor to the smallest relative size (1e-3 of the largest side): the
    // common scale.
    if (pl[i].size.minCoeff() > min_side * (1 + 1e-9) && shape.minCoeff() > 1.001e-3 * largest) {
      if (scale < 0) scale = k;
      EXPECT_NEAR(k, scale, 1e-9 * scale) << i;
    }
    EXPECT_GE(pl[i].offset.minCoeff(), gap - 1e-12) << i;
    EXPECT_LE((pl[i].offset + pl[i].size).maxCoeff(), 1.0 - gap + 1e-12) << i;
    used += pl[i].size.prod();
  }
  std::vector<size_t> order(n);
  for (size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return pl[a].offset.x() < pl[b].offset.x(); });
  long overlaps = 0;
  for (size_t a = 0; a < n; ++a) {
    const RectPlacement& p = pl[order[a]];
    for (size_t b = a + 1; b < n; ++b) {
      const RectPlacement& q = pl[order[b]];
      if (q.offset.x() >= p.offset.x() + p.size.x() + gap - 1e-12) break;
      const bool apart = q.offset.y() >= p.offset.y() + p.size.y() + gap - 1e-12 ||
                         p.offset.y() >= q.offset.y() + q.size.y() + gap - 1e-12;
      overlaps += !apart;
    }
  }
  EXPECT_EQ(overlaps, 0);
  return used;
}

TEST(PackMany, ThousandsOfRectanglesAreDisjointPaddedAndFillTheSquare) {
  for (int n : {201, 2000, 20000}) {
    SCOPED_TRACE(n);
    const std::vector<Vec2> sizes = spread_rectangles(n);
    RectPackOptions o;
    o.padding = 1.0 / 4096;
    o.may_turn = true;
    std::vector<char> turned;
    const std::vector<RectPlacement> pl = pack_rectangles(sizes, o, &turned);
    const double used = check_layout(sizes, pl, turned, o.padding, 0);
    // First-fit decreasing-height shelves of rectangles this spread fill most of the square.
    EXPECT_GT(used, n == 201 ? 0.6 : 0.75);
  }
}

TEST(PackMany, MinimumSideRaisesTinyRectangles) {
  // One large chart and 300 specks a million times smaller: without the floor they would get
  // rectangles far below a texel.
  std::vector<Vec2> sizes(301, Vec2(1e-6, 2e-6));
  sizes[0] = Vec2(1, 1);
  for (int n : {150, 301}) {  // MaxRects path and shelf path
    SCOPED_TRACE(n);
    std::vector<Vec2> s(sizes.begin(), sizes.begin() + n);
    RectPackOptions o;
    o.padding = 8.0 / 1024;
    o.min_side = o.padding;
    o.may_turn = true;
    std::vector<char> turned;
    const std::vector<RectPlacement> pl = pack_rectangles(s, o, &turned);
    check_layout(s, pl, turned, o.padding, o.min_side);
    EXPECT_GT(pl[0].size.minCoeff(), 0.3);  // the large chart still gets most of the square
  }
}

TEST(PackMany, AtMost200RectanglesWithoutFloorAsTheOlderEntryPoints) {
  const std::vector<Vec2> sizes = spread_rectangles(120);
  std::vector<char> turned_old, turned_new;
  const std::vector<RectPlacement> old_t = pack_rectangles_turning(sizes, 0.004, turned_old);
  RectPackOptions o;
  o.padding = 0.004;
  o.may_turn = true;
  const std::vector<RectPlacement> new_t = pack_rectangles(sizes, o, &turned_new);
  ASSERT_EQ(old_t.size(), new_t.size());
  EXPECT_EQ(turned_old, turned_new);
  for (size_t i = 0; i < sizes.size(); ++i) {
    EXPECT_EQ(old_t[i].offset, new_t[i].offset);
    EXPECT_EQ(old_t[i].size, new_t[i].size);
  }
  o.may_turn = false;
  const std::vector<RectPlacement> old_n = pack_rectangles(sizes, 0.004);
  const std::vector<RectPlacement> new_n = pack_rectangles(sizes, o);
  for (size_t i = 0; i < sizes.size(); ++i) EXPECT_EQ(old_n[i].offset, new_n[i].offset);
}

TEST(PackMany, HostileSizesAndOptions) {
  // NaN, infinite, zero and negative sizes get the smallest size; the layout stays valid.
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (int n : {6, 400}) {
    SCOPED_TRACE(n);
    std::vector<Vec2> sizes = spread_rectangles(n);
    sizes[1] = Vec2(nan, 1);
    sizes[2] = Vec2(inf, inf);
    sizes[3] = Vec2(0, 0);
    sizes[4] = Vec2(-1, 2);
    RectPackOptions o;
    o.padding = 0.002;
    std::vector<char> turned;
    const std::vector<RectPlacement> pl = pack_rectangles(sizes, o, &turned);
    for (const RectPlacement& p : pl) {
      ASSERT_TRUE(p.offset.allFinite() && p.size.allFinite());
      EXPECT_GT(p.size.minCoeff(), 0);
    }
  }
  RectPackOptions bad;
  bad.min_side = 0.3;
  EXPECT_THROW(pack_rectangles({Vec2(1, 1), Vec2(1, 1)}, bad), InvalidInputError);
  bad.min_side = nan;
  EXPECT_THROW(pack_rectangles({Vec2(1, 1), Vec2(1, 1)}, bad), InvalidInputError);
  EXPECT_THROW(pack_rectangles({}, RectPackOptions{}), InvalidInputError);
}

TEST(PackMany, ReportsProgressAndCancels) {
  for (int n : {50, 1000}) {
    SCOPED_TRACE(n);
    const std::vector<Vec2> sizes = spread_rectangles(n);
    RectPackOptions o;
    o.padding = 0.001;
    int calls = 0;
    o.progress = [&](std::string_view phase, double f) {
      EXPECT_EQ(phase, "pack");
      EXPECT_GE(f, 0.0);
      EXPECT_LE(f, 1.0);
      ++calls;
      return true;
    };
    pack_rectangles(sizes, o);
    EXPECT_GT(calls, 3);
    o.progress = [](std::string_view, double) { return false; };
    EXPECT_THROW(pack_rectangles(sizes, o), CancelledError);
  }
}

TEST(PackMany, ReportsTheGapItKept) {
  // 3000 rectangles with a gap of 0.02: the gaps alone take 1.2 of the square, so the gap is
  // halved (pack.h) and the halved gap is what comes back; a gap that fits comes back unchanged.
  const std::vector<Vec2> sizes = spread_rectangles(3000);
  RectPackOptions o;
  o.padding = 0.02;
  std::vector<char> turned;
  double gap = -1;
  const std::vector<RectPlacement> pl = pack_rectangles(sizes, o, &turned, &gap);
  EXPECT_LT(gap, o.padding);
  EXPECT_GT(gap, 0.0);
  check_layout(sizes, pl, turned, gap, 0.0);
  o.padding = 1.0 / 4096;
  pack_rectangles(sizes, o, &turned, &gap);
  EXPECT_EQ(gap, o.padding);
}

}  // namespace
}  // namespace adaptex
