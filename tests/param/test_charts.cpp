// Multi-chart layouts (docs/charts.md): one test body over a family of meshes built in code
// (closed genus 0-6, spheres with 1, 5 and 30 holes, a pinched hole, 200 tiny components with
// slivers): every layout is valid (UVs in [0,1]^2, no flipped, degenerate or overlapping
// triangles, every chart a disk) and auto never does worse than one chart per component. The
// effective texel share target of 0.5 (docs/benchmarks.md) is asserted on every one. Also:
// rectangle packing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "adaptex/core/shapes.h"
#include "adaptex/param/charts.h"
#include "adaptex/param/pack.h"
#include "unwrap_checks.h"

namespace adaptex {
namespace {

struct FamilyMesh {
  std::string name;
  TriMesh mesh;
  double min_share;  ///< Asserted effective texel share of the auto layout.
};

std::vector<FamilyMesh> family() {
  std::vector<FamilyMesh> out;
  // Measured (docs/benchmarks.md): all reach 0.5.
  for (int g = 0; g <= 6; ++g)
    out.push_back({"genus " + std::to_string(g), shapes::genus_surface(g), 0.5});
  out.push_back({"1 hole", shapes::sphere_with_holes(1, 4), 0.5});
  out.push_back({"5 holes", shapes::sphere_with_holes(5, 4), 0.5});
  out.push_back({"30 holes", shapes::sphere_with_holes(30, 5), 0.5});
  out.push_back({"pinched hole", shapes::with_pinched_hole(shapes::sphere_with_holes(1, 3)), 0.5});
  // 200 charts: strips unfolded (unfold.h), 8-texel gutter at 1024 (0.556 measured).
  out.push_back({"200 tiny components", shapes::tiny_components(200), 0.5});
  return out;
}

TEST(Charts, FamilyUnwrapsToValidLayoutsWithHighTexelShare) {
  for (const FamilyMesh& m : family()) {
    SCOPED_TRACE(m.name);
    const MeshTopology topo = analyze_topology(m.mesh);
    ASSERT_TRUE(topo.nonmanifold_edges.empty());  // pinched vertices are split by unwrap()
    UnwrapOptions single;
    single.charts = ChartMode::Single;
    UnwrapResult one, multi;
    test::check_unwrap(m.name + " single", m.mesh, single, &one);
    test::check_unwrap(m.name + " auto", m.mesh, UnwrapOptions{}, &multi);
    EXPECT_GE(multi.report.effective_texel_share, one.report.effective_texel_share);
    EXPECT_GE(multi.report.effective_texel_share, m.min_share);
    EXPECT_NEAR(multi.report.effective_texel_share,
                multi.report.coverage / (multi.report.final_l2 * multi.report.final_l2), 1e-12);
    // Auto is conservative: one chart per component whenever that reaches the threshold.
    EXPECT_TRUE(one.report.effective_texel_share < 0.5 ||
                multi.report.num_charts == one.report.num_charts);
    EXPECT_GE(multi.report.num_charts, one.report.num_charts);
  }
}

TEST(Charts, SegmentationGivesConnectedChartsWithoutEars) {
  const TriMesh mesh = shapes::genus_surface(3);
  ChartSegmentOptions so;
  so.num_charts = 12;
  const std::vector<int> label = segment_charts(mesh, so);
  ASSERT_EQ(label.size(), mesh.faces.size());
  const int k = *std::max_element(label.begin(), label.end()) + 1;
  EXPECT_GE(k, 12);
  for (const ChartMesh& c : extract_charts(mesh, label, k)) {
    ASSERT_FALSE(c.faces.empty());
    const MeshTopology t = analyze_topology(c.mesh);
    EXPECT_EQ(t.num_components, 1);
    EXPECT_TRUE(t.is_manifold());
    EXPECT_GE(t.total_loops(), 1);
  }
  EXPECT_THROW(segment_charts(mesh, ChartSegmentOptions{0, 3, 4.0}), InvalidInputError);
  EXPECT_THROW(segment_charts(mesh, ChartSegmentOptions{4, 3, std::numeric_limits<double>::infinity()}),
               InvalidInputError);
}

TEST(Charts, SegmenterKeepsTheLabelsOfSegmentCharts) {
  // ChartSegmenter keeps the dual graph and the farthest-point seeds between chart counts (the
  // seeds of k charts are the first k of a longer sequence): in any order of counts, and on a mesh
  // with fewer faces than the count, it gives segment_charts()' labels.
  for (const TriMesh& mesh : {shapes::genus_surface(3), shapes::torus(6, 3)}) {
    ChartSegmenter segmenter(mesh);
    for (int k : {64, 4, 12, 8, 6, 2, 48})
      for (double w : {0.0, 4.0}) {
        ChartSegmentOptions so;
        so.num_charts = k;
        so.normal_weight = w;
        EXPECT_EQ(segmenter.segment(so), segment_charts(mesh, so)) << k << " charts, weight " << w;
      }
  }
  EXPECT_THROW(ChartSegmenter{TriMesh{}}, InvalidInputError);
}

/// Vertices of \p m with a single face (ears: each must be a corner of the chart's square).
int count_ears(const TriMesh& m) {
  std::vector<int> valence(m.num_vertices(), 0);
  for (const Face& t : m.faces)
    for (int v : t) ++valence[v];
  return static_cast<int>(std::count(valence.begin(), valence.end(), 1));
}

TEST(Charts, NoChartKeepsMoreThanFourEars) {
  // Ear removal moves single faces between charts greedily and does not always converge (a face
  // whose three neighbours lie in three charts keeps moving); on the 30-hole sphere six of 64
  // charts kept 5-6 ears and fell back to the circle (L2 about 2). Such charts are halved.
  struct Case {
    TriMesh mesh;
    int charts;
  };
  std::vector<Case> cases;
  cases.push_back({shapes::sphere_with_holes(30, 5), 64});
  cases.push_back({shapes::genus_surface(4), 16});
  for (const Case& c : cases)
    for (double w : {0.0, 4.0}) {
      ChartSegmentOptions so;
      so.num_charts = c.charts;
      so.normal_weight = w;
      const std::vector<int> label = segment_charts(c.mesh, so);
      const int k = *std::max_element(label.begin(), label.end()) + 1;
      EXPECT_GE(k, c.charts);
      for (const ChartMesh& chart : extract_charts(c.mesh, label, k)) {
        ASSERT_FALSE(chart.faces.empty());
        EXPECT_LE(count_ears(chart.mesh), 4);
      }
    }
}

/// Rectangles of mixed shapes (areas 1-11, aspect ratios 1/3-3).
std::vector<Vec2> mixed_rectangles(int n) {
  std::vector<Vec2> sizes(n);
  for (int i = 0; i < n; ++i) {
    const double area = 1.0 + (i * 37 % 11), aspect = std::pow(3.0, ((i * 13 % 9) - 4) / 4.0);
    sizes[i] = Vec2(std::sqrt(area * aspect), std::sqrt(area / aspect));
  }
  return sizes;
}

TEST(Pack, RectanglesAreDisjointPaddedInsideAndFillTheSquare) {
  for (bool turning : {false, true})
    for (int n : {2, 5, 16, 64, 400}) {
      SCOPED_TRACE(std::to_string(n) + (turning ? " turning" : ""));
      const std::vector<Vec2> sizes = mixed_rectangles(n);
      const double pad = 0.004;
      std::vector<char> turned;
      const std::vector<RectPlacement> pl =
          turning ? pack_rectangles_turning(sizes, pad, turned) : pack_rectangles(sizes, pad);
      ASSERT_EQ(static_cast<int>(pl.size()), n);
      ASSERT_EQ(static_cast<int>(turned.size()), turning ? n : 0);
      double used = 0, scale = -1;
      for (int i = 0; i < n; ++i) {
        const bool t = turning && turned[i];
        const Vec2 shape = t ? Vec2(sizes[i].y(), sizes[i].x()) : sizes[i];
        // Same uniform scale and the (possibly turned) shape of the input.
        const double k = pl[i].size.x() / shape.x();
        EXPECT_NEAR(pl[i].size.y() / shape.y(), k, 1e-9 * k);
        if (scale < 0) scale = k;
        EXPECT_NEAR(k, scale, 1e-9 * scale);
        const Vec2 lo = pl[i].offset, hi = pl[i].offset + pl[i].size;
        EXPECT_GE(lo.minCoeff(), pad - 1e-12);
        EXPECT_LE(hi.maxCoeff(), 1.0 - pad + 1e-12);
        used += pl[i].size.prod();
        for (int j = 0; j < i; ++j) {
          const Vec2 lo2 = pl[j].offset, hi2 = pl[j].offset + pl[j].size;
          const bool apart = hi.x() + pad <= lo2.x() + 1e-12 || hi2.x() + pad <= lo.x() + 1e-12 ||
                             hi.y() + pad <= lo2.y() + 1e-12 || hi2.y() + pad <= lo.y() + 1e-12;
          EXPECT_TRUE(apart) << i << " " << j;
        }
      }
      // MaxRects fills most of the square for mixed shapes (the shelf packing alone reached
      // 0.69-0.79 on chart rectangles); above 200 rectangles only shelves are tried.
      EXPECT_GT(used, n <= 5 ? 0.5 : n <= 64 ? 0.8 : 0.7);
    }
  // A single rectangle fills the unit square, whatever its shape.
  const std::vector<RectPlacement> one = pack_rectangles({Vec2(3, 1)}, 0.01);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].offset, Vec2(0, 0));
  EXPECT_EQ(one[0].size, Vec2(1, 1));
  EXPECT_THROW(pack_rectangles({}, 0.01), InvalidInputError);
  EXPECT_THROW(pack_rectangles({Vec2(1, 1)}, 0.3), InvalidInputError);
}

}  // namespace
}  // namespace adaptex
