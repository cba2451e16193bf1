// parameterize_disk(): Floater + Yoshizawa on disks built in code (and the two open shared meshes).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/core/topology.h"
#include "adaptex/param/cut.h"
#include "adaptex/param/disk_param.h"
#include "adaptex/param/stretch.h"
#include "adaptex/param/yoshizawa.h"
#include "disk_fixtures.h"

using namespace adaptex;
using adaptex::test::as_param;

namespace {

/// Every property a valid disk parameterization has.
void expect_valid_layout(const std::string& name, const TriMesh& m, const DiskParamResult& r) {
  SCOPED_TRACE(name);
  ASSERT_EQ(r.uv.size(), m.positions.size());
  const Parameterization p = as_param(m, r.uv);
  const StretchStats st = measure_stretch(m, p);
  EXPECT_EQ(st.flipped, 0);
  EXPECT_EQ(st.degenerate, 0);
  for (int f = 0; f < m.num_faces(); ++f) ASSERT_GT(uv_signed_area(p, f), 0.0) << "face " << f;
  EXPECT_EQ(count_overlapping_triangles(p), 0);
  EXPECT_TRUE(std::isfinite(r.final_l2));
  EXPECT_GE(r.final_l2, 1.0 - 1e-9);
  EXPECT_LE(r.final_l2, r.floater_l2);
  // Boundary on the square (or the inscribed circle), interior strictly inside.
  const MeshTopology topo = analyze_topology(m);
  std::vector<char> on_b(m.positions.size(), 0);
  for (int v : topo.boundary_loops.at(0)) on_b[v] = 1;
  for (size_t v = 0; v < r.uv.size(); ++v) {
    const Vec2& t = r.uv[v];
    ASSERT_TRUE(t.x() >= -1e-12 && t.x() <= 1 + 1e-12 && t.y() >= -1e-12 && t.y() <= 1 + 1e-12)
        << "vertex " << v << " at " << t.transpose();
    if (!on_b[v]) continue;
    if (r.on_square) {
      const double d = std::min({t.x(), 1 - t.x(), t.y(), 1 - t.y()});
      EXPECT_NEAR(d, 0.0, 1e-12) << "boundary vertex " << v;
    } else {
      EXPECT_NEAR((t - Vec2(0.5, 0.5)).norm(), 0.5, 1e-12) << "boundary vertex " << v;
    }
  }
}

}  // namespace

TEST(DiskParam, FloaterAndYoshizawaOnEveryTestDisk) {
  for (const auto& d : adaptex::test::test_disks()) {
    for (EmbeddingWeights w : {EmbeddingWeights::ShapePreserving, EmbeddingWeights::MeanValue}) {
      DiskParamOptions opt;
      opt.weights = w;
      opt.yoshizawa = false;
      const DiskParamResult floater = parameterize_disk(d.mesh, {}, opt);
      expect_valid_layout(d.name + (w == EmbeddingWeights::MeanValue ? "/mvc" : "/floater"), d.mesh,
                          floater);
      EXPECT_EQ(floater.iterations, 0);
      opt.yoshizawa = true;
      const DiskParamResult yosh = parameterize_disk(d.mesh, {}, opt);
      expect_valid_layout(d.name + "/yoshizawa", d.mesh, yosh);
      EXPECT_DOUBLE_EQ(yosh.floater_l2, floater.final_l2) << d.name;
      if (d.curved) {
        EXPECT_LT(yosh.final_l2, yosh.floater_l2 * 0.999) << d.name;
        EXPECT_GE(yosh.iterations, 1) << d.name;
      }
    }
  }
}

TEST(DiskParam, PlaneIsReproducedIsometrically) {
  // The unit plane's own coordinates are an embedding onto the square with identical shape: the
  // shape-preserving weights reproduce it exactly (linear precision), so L2 = 1.
  const TriMesh m = shapes::plane(10);
  DiskParamOptions opt;
  opt.yoshizawa = false;
  const DiskParamResult r = parameterize_disk(m, {}, opt);
  EXPECT_NEAR(r.final_l2, 1.0, 1e-9);
  EXPECT_TRUE(r.on_square);
}

TEST(DiskParam, SixEarsFallsBackToCircle) {
  const DiskParamResult r = parameterize_disk(adaptex::test::six_ears(), {});
  EXPECT_FALSE(r.on_square);
}

TEST(DiskParam, GivenLoopInEitherDirection) {
  const TriMesh m = adaptex::test::hemisphere(16);
  std::vector<int> loop = analyze_topology(m).boundary_loops.at(0);
  DiskParamOptions opt;
  opt.yoshizawa = false;
  const DiskParamResult a = parameterize_disk(m, loop, opt);
  std::reverse(loop.begin(), loop.end());
  const DiskParamResult b = parameterize_disk(m, loop, opt);
  expect_valid_layout("forward", m, a);
  expect_valid_layout("backward", m, b);
  EXPECT_NEAR(a.final_l2, b.final_l2, 1e-9);
}

TEST(DiskParam, BackendsAgree) {
  const TriMesh m = adaptex::test::bump(12);
  DiskParamOptions opt;
  opt.max_iterations = 3;
  opt.min_improvement = 0;
  opt.backend = TutteSolver::Backend::Umfpack;
  const DiskParamResult a = parameterize_disk(m, {}, opt);
  for (auto b : {TutteSolver::Backend::SparseLU, TutteSolver::Backend::Multigrid}) {
    opt.backend = b;
    const DiskParamResult r = parameterize_disk(m, {}, opt);
    ASSERT_EQ(r.uv.size(), a.uv.size());
    for (size_t v = 0; v < r.uv.size(); ++v) EXPECT_NEAR((r.uv[v] - a.uv[v]).norm(), 0.0, 1e-7);
  }
}

TEST(DiskParam, RejectsNonDisks) {
  EXPECT_THROW(parameterize_disk(shapes::sphere(8, 6), {}), TopologyError);
  EXPECT_THROW(parameterize_disk(shapes::open_cylinder(8, 3), {}), TopologyError);
  EXPECT_THROW(parameterize_disk(shapes::disk_with_holes(2, 12), {}), TopologyError);
  EXPECT_THROW(parameterize_disk(TriMesh{}, {}), TopologyError);
}

TEST(DiskParam, CancelThrows) {
  DiskParamOptions opt;
  opt.progress = [](std::string_view phase, double) { return phase != "yoshizawa"; };
  EXPECT_THROW(parameterize_disk(adaptex::test::bump(8), {}, opt), CancelledError);
}

TEST(DiskParam, MultigridMatchesDirectOnLargerDisk) {
  // ~8k unknowns: the AMG hierarchy has several levels (coarsest level is below 2000 unknowns).
  const TriMesh m = adaptex::test::bump(64);
  DiskParamOptions opt;
  opt.max_iterations = 2;
  opt.min_improvement = 0;
  opt.backend = TutteSolver::Backend::Umfpack;
  const DiskParamResult a = parameterize_disk(m, {}, opt);
  opt.backend = TutteSolver::Backend::Multigrid;
  const DiskParamResult b = parameterize_disk(m, {}, opt);
  EXPECT_EQ(a.iterations, b.iterations);
  double max_diff = 0;
  for (size_t v = 0; v < a.uv.size(); ++v) max_diff = std::max(max_diff, (a.uv[v] - b.uv[v]).norm());
  EXPECT_LT(max_diff, 1e-7);
  EXPECT_NEAR(a.final_l2, b.final_l2, 1e-8);
}

TEST(DiskParam, ContinuedRunEqualsOneFullRun) {
  // A cheap run (0 or 1 Yoshizawa iterations, as the cut augmentation compares cuts) continued to
  // the full cap gives exactly the uv of one full run: the loop only depends on the cap through its
  // end (continue_disk_param, unwrap's full solve of the chosen cut).
  for (const auto& d : adaptex::test::test_disks()) {
    if (!d.curved) continue;
    for (int cheap_iterations : {0, 1, 2}) {
      DiskParamOptions full;
      full.weights = EmbeddingWeights::MeanValue;
      full.eta = 1.0;
      const DiskParamResult direct = parameterize_disk(d.mesh, {}, full);
      DiskParamOptions cheap = full;
      cheap.max_iterations = cheap_iterations;
      cheap.yoshizawa = cheap_iterations > 0;
      DiskParamStatePtr state;
      const DiskParamResult first = parameterize_disk(d.mesh, {}, cheap, &state);
      ASSERT_TRUE(state) << d.name;
      EXPECT_EQ(first.iterations, std::min(cheap_iterations, direct.iterations)) << d.name;
      const TriMesh moved = d.mesh;  // the disk may be another object with the same contents
      const DiskParamResult cont = continue_disk_param(moved, *state, first, full);
      EXPECT_EQ(cont.iterations, direct.iterations) << d.name << " cheap " << cheap_iterations;
      EXPECT_EQ(cont.final_l2, direct.final_l2) << d.name << " cheap " << cheap_iterations;
      EXPECT_EQ(cont.floater_l2, direct.floater_l2) << d.name;
      EXPECT_EQ(cont.flipped + cont.degenerate, 0) << d.name;
      ASSERT_EQ(cont.uv.size(), direct.uv.size());
      double max_diff = 0;
      for (size_t v = 0; v < cont.uv.size(); ++v)
        max_diff = std::max(max_diff, (cont.uv[v] - direct.uv[v]).cwiseAbs().maxCoeff());
      EXPECT_EQ(max_diff, 0.0) << d.name << " cheap " << cheap_iterations;
    }
  }
}

namespace {

/// For every vertex of \p sub: its wedge in \p pattern when the input vertex has only one there.
std::vector<int> map_to_pattern(const SlicedDisk& pattern, const SlicedDisk& sub, int input_vertices) {
  std::vector<int> single(input_vertices, -1);
  for (size_t w = 0; w < pattern.wedge_vertex.size(); ++w) {
    int& p = single[pattern.wedge_vertex[w]];
    p = p == -1 ? static_cast<int>(w) : -2;
  }
  std::vector<int> out(sub.wedge_vertex.size());
  for (size_t w = 0; w < out.size(); ++w) out[w] = single[sub.wedge_vertex[w]];
  return out;
}

/// icosphere(3) with its edges, edge graph, initial cut and the disk of that cut.
struct CutSphere {
  TriMesh m = shapes::icosphere(3);
  EdgeConnectivity ec = build_edges(m);
  EdgeGraph graph = build_edge_graph(m, ec);
  std::vector<char> cut = initial_cut(m, ec, graph);
  SlicedDisk d0 = slice_along_cut(m, ec, cut);
};

/// Adds the shortest path from the vertex farthest from the cut to the cut (the GGH augmentation step).
void add_farthest_path(const TriMesh& m, const EdgeConnectivity& ec, const EdgeGraph& graph,
                       std::vector<char>& cut) {
  const std::vector<char> on_cut = cut_vertices(m, ec, cut);
  const std::vector<double> dist = distance_to_cut(graph, on_cut);
  const int from = static_cast<int>(std::max_element(dist.begin(), dist.end()) - dist.begin());
  for (int e : shortest_path_to_cut(graph, on_cut, from)) cut[e] = 1;
}

double max_uv_difference(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  double d = 0;
  for (size_t v = 0; v < a.size(); ++v) d = std::max(d, (a[v] - b[v]).cwiseAbs().maxCoeff());
  return d;
}

}  // namespace

TEST(DiskParam, SubdiskReusesTheSolverWithTheSameResult) {
  // The cut augmentation's situation: a closed surface cut to a disk, then cut further along two
  // paths (GGH 2002). parameterize_subdisk() solves the larger cuts' disks with the first disk's
  // factorized system (identity rows for the vertices that joined the cut) and must give the
  // layout of a fresh parameterize_disk() of the same disk.
  CutSphere f;
  DiskParamOptions cheap;
  cheap.weights = EmbeddingWeights::MeanValue;
  cheap.max_iterations = 1;
  DiskParamStatePtr s0;
  parameterize_disk(f.d0.disk, f.d0.boundary_loop, cheap, &s0);
  ASSERT_TRUE(s0);
  DiskParamOptions full = cheap;
  full.max_iterations = 30;
  const DiskParamState* parent = s0.get();
  DiskParamStatePtr s1, s2;
  for (int step = 0; step < 2; ++step) {
    add_farthest_path(f.m, f.ec, f.graph, f.cut);
    const SlicedDisk d = slice_along_cut(f.m, f.ec, f.cut);
    const std::vector<int> to_pattern = map_to_pattern(f.d0, d, f.m.num_vertices());
    DiskParamStatePtr& s = step == 0 ? s1 : s2;
    const DiskParamResult sub = parameterize_subdisk(d.disk, d.boundary_loop, to_pattern, *parent,
                                                     cheap, &s);
    const DiskParamResult fresh = parameterize_disk(d.disk, d.boundary_loop, cheap);
    EXPECT_NEAR(sub.floater_l2, fresh.floater_l2, 1e-9 * fresh.floater_l2) << "step " << step;
    EXPECT_NEAR(sub.final_l2, fresh.final_l2, 1e-9 * fresh.final_l2) << "step " << step;
    EXPECT_LT(max_uv_difference(sub.uv, fresh.uv), 1e-9) << "step " << step;
    // Continued to the full cap, too (the solver is shared with s0 and the other sub-disk).
    const DiskParamResult sub_full = continue_disk_param(d.disk, *s, sub, full);
    const DiskParamResult fresh_full = parameterize_disk(d.disk, d.boundary_loop, full);
    EXPECT_EQ(sub_full.iterations, fresh_full.iterations) << "step " << step;
    EXPECT_NEAR(sub_full.final_l2, fresh_full.final_l2, 1e-9 * fresh_full.final_l2);
    EXPECT_LT(max_uv_difference(sub_full.uv, fresh_full.uv), 1e-8) << "step " << step;
    EXPECT_LT(sub_full.final_l2, sub.final_l2);
    parent = s.get();
  }
  // A map that sends interior vertices nowhere, or the wrong size, is refused.
  const SlicedDisk d = slice_along_cut(f.m, f.ec, f.cut);
  EXPECT_THROW(parameterize_subdisk(d.disk, d.boundary_loop, std::vector<int>(d.disk.num_vertices(), -1),
                                    *s0, cheap, nullptr),
               InvalidInputError);
  EXPECT_THROW(parameterize_subdisk(d.disk, d.boundary_loop, {}, *s0, cheap, nullptr),
               InvalidInputError);
}

TEST(DiskParam, ResultVertexStretchEqualsMeasuringTheResult) {
  // σ of the returned uv from the run's own measurements (the best iterate's, also when the last
  // iterate was worse), with 0, 1 and the full number of Yoshizawa iterations.
  for (const auto& d : adaptex::test::test_disks()) {
    for (int iterations : {0, 1, 30}) {
      DiskParamOptions opt;
      opt.max_iterations = iterations;
      opt.yoshizawa = iterations > 0;
      DiskParamStatePtr state;
      const DiskParamResult r = parameterize_disk(d.mesh, {}, opt, &state);
      const std::vector<double> expected = vertex_stretch(d.mesh, r.uv);
      const std::vector<double> got = result_vertex_stretch(d.mesh, *state, r);
      ASSERT_EQ(got.size(), expected.size());
      for (size_t v = 0; v < got.size(); ++v)
        ASSERT_EQ(got[v], expected[v]) << d.name << " iterations " << iterations << " vertex " << v;
    }
  }
}

TEST(DiskParam, SubdiskWeightsAreTheRowsOfTheFirstDisk) {
  // A vertex inside both disks keeps its closed one-ring, so compute_subdisk_weights() copies its
  // row from the first disk's weights; the result must equal computing the sub-disk's weights.
  CutSphere f;
  add_farthest_path(f.m, f.ec, f.graph, f.cut);
  const SlicedDisk d1 = slice_along_cut(f.m, f.ec, f.cut);
  auto boundary_flags = [](const SlicedDisk& d) {
    std::vector<char> b(d.disk.num_vertices(), 0);
    for (int v : d.boundary_loop) b[v] = 1;
    return b;
  };
  const std::vector<char> b0 = boundary_flags(f.d0), b1 = boundary_flags(d1);
  const std::vector<int> to_pattern = map_to_pattern(f.d0, d1, f.m.num_vertices());
  for (EmbeddingWeights kind : {EmbeddingWeights::MeanValue, EmbeddingWeights::ShapePreserving}) {
    const ConvexWeights w0 = compute_embedding_weights(f.d0.disk, b0, kind);
    const ConvexWeights w1 = compute_embedding_weights(d1.disk, b1, kind);
    const ConvexWeights copied = compute_subdisk_weights(d1.disk, b1, kind, w0, to_pattern);
    EXPECT_EQ(copied.offsets, w1.offsets);
    EXPECT_EQ(copied.neighbors, w1.neighbors);
    EXPECT_EQ(copied.values, w1.values);
    // The rows are really taken from the pattern: with doubled pattern values, the rows of
    // vertices with an interior neighbour come out doubled.
    ConvexWeights doubled = w0;
    for (double& x : doubled.values) x *= 2;
    const ConvexWeights from_doubled = compute_subdisk_weights(d1.disk, b1, kind, doubled, to_pattern);
    int rows = 0, copied_rows = 0;
    for (int v = 0; v < w1.num_vertices(); ++v) {
      if (w1.offsets[v + 1] == w1.offsets[v]) continue;
      ++rows;
      bool all_doubled = true;
      for (int k = w1.offsets[v]; k < w1.offsets[v + 1]; ++k)
        all_doubled = all_doubled && from_doubled.values[k] == 2 * w1.values[k];
      copied_rows += all_doubled;
    }
    EXPECT_GT(copied_rows, 0.9 * rows);
  }
  EXPECT_THROW(compute_subdisk_weights(d1.disk, b1, EmbeddingWeights::MeanValue,
                                       compute_embedding_weights(f.d0.disk, b0, EmbeddingWeights::MeanValue),
                                       {}),
               InvalidInputError);
}
