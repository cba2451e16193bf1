// Generated stroke sets (paint/generate.h), kind `dots`: hard small dots sprinkled in one ball of the
// surface, reproducible per seed. The `lines`/`blobs`/`mixed` kinds are covered through the CLI
// (test_brush_cli.cpp, GenerateIsReproducibleAndOnTheSurface).
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/paint/generate.h"

using namespace adaptex;

namespace {

StrokeFile dots(const TriMesh& mesh, std::uint64_t seed, GeneratedRegion* region = nullptr, int count = -1) {
  GenerateOptions o;
  o.kind = StrokeKind::Dots;
  o.seed = seed;
  o.count = count;
  return generate_strokes(mesh, o, region);
}

bool same(const StrokeFile& a, const StrokeFile& b) {
  if (a.strokes.size() != b.strokes.size()) return false;
  for (size_t k = 0; k < a.strokes.size(); ++k) {
    const Stroke &s = a.strokes[k], &t = b.strokes[k];
    if (s.color != t.color || s.radius != t.radius || s.hardness != t.hardness || s.opacity != t.opacity ||
        s.dabs != t.dabs)
      return false;
  }
  return true;
}

}  // namespace

TEST(GenerateDots, KindNameRoundTrips) {
  EXPECT_EQ(parse_stroke_kind("dots"), StrokeKind::Dots);
  EXPECT_EQ(to_string(StrokeKind::Dots), "dots");
  for (const char* k : {"lines", "blobs", "mixed", "dots"}) EXPECT_EQ(to_string(parse_stroke_kind(k)), k);
  EXPECT_THROW(parse_stroke_kind("speckle"), InvalidInputError);
}

TEST(GenerateDots, HardSmallSaturatedDotsInsideOneBallOnTheSurface) {
  const TriMesh mesh = shapes::icosphere(4, 1.0);
  const double diag = bounding_box(mesh).diagonal();
  for (std::uint64_t seed : {1u, 2u, 7u}) {
    GeneratedRegion region;
    const StrokeFile f = dots(mesh, seed, &region);
    ASSERT_GE(f.strokes.size(), 150u) << seed;
    ASSERT_LE(f.strokes.size(), 400u) << seed;
    EXPECT_GE(region.area_fraction, 0.10);
    EXPECT_LE(region.area_fraction, 0.20);
    // A ball of radius R around a point of the unit sphere cuts a cap of area fraction R^2 / 4.
    EXPECT_NEAR(region.radius * region.radius / 4, region.area_fraction, 0.02) << seed;
    EXPECT_NEAR(region.centre.norm(), 1.0, 0.01);
    double mean_distance = 0;
    long long n = 0;
    std::set<int> dab_counts;
    for (const Stroke& s : f.strokes) {
      EXPECT_GE(s.radius, 0.001 * diag * (1 - 1e-12));
      EXPECT_LE(s.radius, 0.002 * diag * (1 + 1e-12));
      EXPECT_GE(s.hardness, 0.8);
      EXPECT_LE(s.hardness, 1.0);
      EXPECT_EQ(s.opacity, 1.0);
      // Saturated: chroma max - min = value * saturation >= 0.6 * 0.8.
      EXPECT_GE(s.color.maxCoeff() - s.color.minCoeff(), 0.48 - 1e-9);
      ASSERT_GE(s.dabs.size(), 1u);
      ASSERT_LE(s.dabs.size(), 3u);
      dab_counts.insert(static_cast<int>(s.dabs.size()));
      for (size_t d = 1; d < s.dabs.size(); ++d)
        EXPECT_LE((s.dabs[d] - s.dabs[d - 1]).norm(), 1.0 * s.radius + 1e-12);  // a short dash at most
      for (size_t d = 0; d < s.dabs.size(); ++d) {
        const double r = (s.dabs[d] - region.centre).norm();
        EXPECT_LE(r, region.radius * (1 + 1e-12));
        EXPECT_LE(s.dabs[d].norm(), 1 + 1e-9);  // on the surface: the icosphere lies in [0.99, 1]
        EXPECT_GE(s.dabs[d].norm(), 0.99);
        mean_distance += r;
        ++n;
      }
    }
    // Sprinkled over the ball, not clumped: uniform in a disc has mean distance 2R/3.
    mean_distance /= n;
    EXPECT_GT(mean_distance, 0.55 * region.radius) << seed;
    EXPECT_LT(mean_distance, 0.8 * region.radius) << seed;
    EXPECT_EQ(dab_counts, (std::set<int>{1, 2, 3})) << seed;
  }
}

TEST(GenerateDots, ReproduciblePerSeed) {
  const TriMesh mesh = shapes::torus(48, 24);
  GeneratedRegion a, b, c;
  const StrokeFile s1 = dots(mesh, 5, &a), s2 = dots(mesh, 5, &b), s3 = dots(mesh, 6, &c);
  EXPECT_TRUE(same(s1, s2));
  EXPECT_EQ(a.centre, b.centre);
  EXPECT_EQ(a.radius, b.radius);
  EXPECT_FALSE(same(s1, s3));
  EXPECT_NE(a.centre, c.centre);
}

TEST(GenerateDots, CountOptionAndOtherKindsHaveNoBall) {
  const TriMesh mesh = shapes::icosphere(3, 2.0);
  GeneratedRegion region;
  EXPECT_EQ(dots(mesh, 1, &region, 7).strokes.size(), 7u);
  EXPECT_GT(region.radius, 0.0);
  GenerateOptions o;
  o.kind = StrokeKind::Lines;
  generate_strokes(mesh, o, &region);
  EXPECT_EQ(region.radius, 0.0);
  EXPECT_THROW(dots(mesh, 1, nullptr, 0), InvalidInputError);
}
