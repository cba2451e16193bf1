// Issue 8 "no internal errors from solvers": the Tutte solver falls back to a direct factorization
// when its backend fails, degenerate elements get regularized weights, and tiny components,
// slivers, zero-area faces and duplicate points all get a valid layout.
#include <gtest/gtest.h>

#include <cmath>

#include "adaptex/core/shapes.h"
#include "adaptex/core/topology.h"
#include "adaptex/param/disk_param.h"
#include "adaptex/param/floater.h"
#include "adaptex/param/stretch.h"
#include "adaptex/param/unwrap.h"
#include "disk_fixtures.h"

using namespace adaptex;
using adaptex::test::as_param;

namespace {

/// The plane disk (n x n cells) with \p collapsed interior edges (a, a+1) collapsed onto a: the two
/// faces on each such edge have zero area and its two vertices are duplicate points.
TriMesh plane_with_zero_area_faces(int n, int collapsed) {
  TriMesh m = shapes::plane(n);
  const int row = n + 1;
  for (int k = 0; k < collapsed; ++k) {
    const int a = (2 + 2 * k % (n - 4)) * row + 2 + 4 * (k % ((n - 4) / 4));
    m.positions[a + 1] = m.positions[a];
  }
  return m;
}

int zero_area_faces(const TriMesh& m) {
  int z = 0;
  for (int f = 0; f < m.num_faces(); ++f) z += face_area(m, f) == 0.0;
  return z;
}

/// Every UV of \p p in [0,1]^2, every UV triangle positively oriented, no two overlapping.
void expect_valid(const TriMesh& m, const Parameterization& p) {
  ASSERT_EQ(p.uv_faces.size(), m.faces.size());
  for (const Vec2& t : p.uv)
    ASSERT_TRUE(t.allFinite() && t.x() >= 0 && t.x() <= 1 && t.y() >= 0 && t.y() <= 1) << t.transpose();
  for (int f = 0; f < m.num_faces(); ++f) ASSERT_GT(uv_signed_area(p, f), 0.0) << "face " << f;
  const StretchStats st = measure_stretch(m, p);
  EXPECT_EQ(st.flipped, 0);
  EXPECT_EQ(st.degenerate, 0);
  EXPECT_EQ(count_overlapping_triangles(p), 0);
}

std::vector<char> boundary_flags(const TriMesh& m) {
  std::vector<char> b(m.positions.size(), 0);
  for (const auto& loop : analyze_topology(m).boundary_loops)
    for (int v : loop) b[v] = 1;
  return b;
}

TEST(SolverRobust, IterativeSolverThatCannotConvergeFallsBackToDirect) {
  const TriMesh m = test::bump(80);  // > 2000 unknowns: a real AMG hierarchy
  const std::vector<char> is_b = boundary_flags(m);
  const DiskBoundary bd = map_boundary_to_square(m, analyze_topology(m).boundary_loops.at(0));
  std::vector<Vec2> start(m.positions.size(), Vec2(0.5, 0.5));
  for (size_t i = 0; i < bd.loop.size(); ++i) start[bd.loop[i]] = bd.uv[i];
  const ConvexWeights w = compute_embedding_weights(m, is_b, EmbeddingWeights::MeanValue);

  std::vector<Vec2> direct = start;
  TutteSolver klu(w, is_b, TutteSolver::Backend::Klu);
  klu.solve(w, direct);
  EXPECT_EQ(klu.fallbacks(), 0);

  std::vector<Vec2> converged = start;
  TutteSolver mg(w, is_b, TutteSolver::Backend::Multigrid);
  mg.solve(w, converged);
  EXPECT_EQ(mg.fallbacks(), 0);  // the ordinary path converges: no fallback

  std::vector<Vec2> capped = start;
  TutteSolver weak(w, is_b, TutteSolver::Backend::Multigrid);
  weak.set_tolerance(1e-15);
  weak.set_max_iterations(1);  // BiCGSTAB cannot reach 1e-15 in one iteration
  weak.solve(w, capped);
  EXPECT_EQ(weak.fallbacks(), 1);
  EXPECT_EQ(weak.backend(), TutteSolver::Backend::Multigrid);
  double diff = 0;
  for (size_t v = 0; v < direct.size(); ++v) diff = std::max(diff, (capped[v] - direct[v]).norm());
  EXPECT_LT(diff, 1e-9);
  expect_valid(m, as_param(m, capped));
}

TEST(SolverRobust, DegenerateRingsGetFinitePositiveWeights) {
  const TriMesh m = plane_with_zero_area_faces(24, 6);
  ASSERT_GE(zero_area_faces(m), 10);
  const std::vector<char> is_b = boundary_flags(m);
  for (EmbeddingWeights kind : {EmbeddingWeights::MeanValue, EmbeddingWeights::ShapePreserving}) {
    const ConvexWeights w = compute_embedding_weights(m, is_b, kind);
    for (int v = 0; v < w.num_vertices(); ++v) {
      if (w.offsets[v + 1] == w.offsets[v]) continue;
      double sum = 0;
      for (int k = w.offsets[v]; k < w.offsets[v + 1]; ++k) {
        ASSERT_TRUE(std::isfinite(w.values[k]) && w.values[k] > 0) << "vertex " << v;
        sum += w.values[k];
      }
      EXPECT_NEAR(sum, 1.0, 1e-12) << "vertex " << v;
    }
  }
}

TEST(SolverRobust, ZeroAreaFacesAndDuplicatePointsWithAForcedFallback) {
  const TriMesh m = plane_with_zero_area_faces(72, 12);  // > 2000 unknowns
  ASSERT_GE(zero_area_faces(m), 20);
  DiskParamOptions opt;
  opt.weights = EmbeddingWeights::MeanValue;
  opt.backend = TutteSolver::Backend::Multigrid;
  opt.max_solver_iterations = 1;  // every solve needs the fallback
  const DiskParamResult r = parameterize_disk(m, {}, opt);
  EXPECT_EQ(r.solver_fallbacks, 1 + r.iterations);
  EXPECT_GE(r.iterations, 1);
  expect_valid(m, as_param(m, r.uv));
  EXPECT_TRUE(std::isfinite(r.final_l2));
  EXPECT_LE(r.final_l2, r.floater_l2);

  opt.max_solver_iterations = 500;
  const DiskParamResult ok = parameterize_disk(m, {}, opt);
  EXPECT_EQ(ok.solver_fallbacks, 0);
  EXPECT_NEAR(ok.final_l2, r.final_l2, 1e-6 * r.final_l2);
}

TEST(SolverRobust, NearDuplicatePointsKeepTheIterativeSolverConverging) {
  // Like plane_with_zero_area_faces, but the collapsed vertex stays 1e-12 away: the faces are
  // slivers of non-zero area (a reader keeps them) with mean-value weights ~1e12 times the others
  // unless regularized. > 2000 unknowns: the AMG hierarchy is used.
  TriMesh m = shapes::plane(72);
  const int row = 73;
  for (int k = 0; k < 12; ++k) {
    const int a = (2 + 5 * k) * row + 2 + 5 * k;
    m.positions[a + 1] = m.positions[a] + Vec3(1e-12, 0, 0);
  }
  DiskParamOptions opt;
  opt.weights = EmbeddingWeights::MeanValue;
  opt.backend = TutteSolver::Backend::Multigrid;
  const DiskParamResult r = parameterize_disk(m, {}, opt);
  EXPECT_EQ(r.solver_fallbacks, 0);
  expect_valid(m, as_param(m, r.uv));
  EXPECT_TRUE(std::isfinite(r.final_l2));
}

TEST(SolverRobust, TwoHundredTinyComponentsWithSliversUnwrap) {
  const TriMesh m = shapes::tiny_components(200);
  const MeshTopology topo = analyze_topology(m);
  ASSERT_EQ(topo.num_components, 200);
  ASSERT_TRUE(topo.is_manifold());
  EXPECT_GE(zero_area_faces(m), 2);
  for (EmbeddingWeights kind : {EmbeddingWeights::MeanValue, EmbeddingWeights::ShapePreserving}) {
    UnwrapOptions opt;
    opt.weights = kind;
    const UnwrapResult r = unwrap(m, opt);
    EXPECT_GE(r.param.num_charts, 200);
    expect_valid(m, r.param);
  }
}

TEST(SolverRobust, SyntheticScanWithZeroAreaFacesUnwraps) {
  const TriMesh m = shapes::synthetic_scan(40000, 15, 40);
  const MeshTopology topo = analyze_topology(m);
  EXPECT_EQ(topo.num_components, 15);
  EXPECT_GT(topo.total_loops(), 15);
  EXPECT_GE(zero_area_faces(m), 30);
  const UnwrapResult r = unwrap(m);
  expect_valid(m, r.param);
  EXPECT_TRUE(std::isfinite(r.report.final_l2));
}

}  // namespace
