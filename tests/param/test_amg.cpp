// Direct tests of the smoothed-aggregation AMG preconditioner and BiCGSTAB (src/param/amg.h), on
// Tutte-like systems built here: boundary rows are the identity, an interior row i is
// x_i - sum_j w_ij x_j with positive weights w_ij summing to 1 over the grid neighbours (non-symmetric,
// like the shape-preserving / mean-value rows of floater.cpp). Reference solutions come from a
// sparse direct LU solve.
#include <gtest/gtest.h>

#include <Eigen/SparseLU>
#include <random>

#include "adaptex/core/errors.h"
#include "amg.h"

namespace adaptex::detail {
namespace {

using RowMat = AmgPreconditioner::RowMat;
using Block = AmgPreconditioner::Block;

/// The Tutte matrix of an n x n vertex grid (4-neighbour interior rows, random weights from \p seed).
RowMat tutte_grid(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.2, 1.0);
  std::vector<Eigen::Triplet<double>> t;
  auto id = [n](int i, int j) { return j * n + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int r = id(i, j);
      t.emplace_back(r, r, 1.0);
      if (i == 0 || j == 0 || i == n - 1 || j == n - 1) continue;
      const int nb[4] = {id(i - 1, j), id(i + 1, j), id(i, j - 1), id(i, j + 1)};
      double w[4], sum = 0;
      for (double& x : w) sum += (x = u(rng));
      for (int k = 0; k < 4; ++k) t.emplace_back(r, nb[k], -w[k] / sum);
    }
  RowMat a(n * n, n * n);
  a.setFromTriplets(t.begin(), t.end());
  a.makeCompressed();
  return a;
}

/// Right-hand side of the Tutte system: boundary rows carry a boundary position (u, v).
Block boundary_rhs(int n) {
  Block b = Block::Zero(n * n, 2);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      if (i == 0 || j == 0 || i == n - 1 || j == n - 1) b.row(j * n + i) << double(i) / (n - 1), double(j) / (n - 1);
  return b;
}

Block direct_solve(const RowMat& a, const Block& b) {
  Eigen::SparseMatrix<double> c = a;
  c.makeCompressed();
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.analyzePattern(c);
  lu.factorize(c);
  EXPECT_EQ(lu.info(), Eigen::Success);
  const Eigen::MatrixX2d rhs = b;
  const Eigen::MatrixX2d x = lu.solve(rhs);
  return x;
}

/// BiCGSTAB + AMG from a zero guess; returns the iterations (-1: did not converge).
int solve(const RowMat& a, const AmgPreconditioner& m, const Block& b, Block& x) {
  x = Block::Zero(b.rows(), 2);
  return bicgstab(a, m, b, x, 1e-10, 500);
}

TEST(Amg, SmallSystemIsOneLevelAndSolvedExactly) {
  const RowMat a = tutte_grid(20, 1);  // 400 unknowns: below the coarsest size, a direct solve
  AmgPreconditioner m;
  m.setup(a);
  EXPECT_EQ(m.num_levels(), 1);
  const Block b = boundary_rhs(20);
  const Block z = m.apply(b);
  EXPECT_LT((z - direct_solve(a, b)).norm(), 1e-10 * z.norm());
}

TEST(Amg, BicgstabMatchesTheDirectSolveOnAMultiLevelHierarchy) {
  const int n = 120;  // 14,400 unknowns
  const RowMat a = tutte_grid(n, 2);
  AmgPreconditioner m;
  m.setup(a);
  EXPECT_GE(m.num_levels(), 2);
  const Block b = boundary_rhs(n);
  Block x;
  const int its = solve(a, m, b, x);
  ASSERT_GT(its, 0);
  Block ax(b.rows(), 2);
  multiply(a, x, ax);
  EXPECT_LE((ax - b).col(0).norm(), 1e-10 * b.col(0).norm());
  EXPECT_LE((ax - b).col(1).norm(), 1e-10 * b.col(1).norm());
  EXPECT_LT((x - direct_solve(a, b)).cwiseAbs().maxCoeff(), 1e-8);
}

TEST(Amg, IterationCountsStayFlatAsTheGridIsRefined) {
  // The point of multigrid: the iterations do not grow with the problem size (no preconditioner, or
  // Jacobi, needs O(n) iterations on these grids).
  int its[2];
  const int sizes[2] = {60, 180};
  for (int k = 0; k < 2; ++k) {
    const RowMat a = tutte_grid(sizes[k], 5);
    AmgPreconditioner m;
    m.setup(a);
    Block x;
    its[k] = solve(a, m, boundary_rhs(sizes[k]), x);
    ASSERT_GT(its[k], 0) << sizes[k];
  }
  std::printf("AMG + BiCGSTAB iterations: n=%d: %d, n=%d: %d\n", sizes[0], its[0], sizes[1], its[1]);
  EXPECT_LE(its[1], 2 * its[0]);  // 9x the unknowns (measured: 7 and 8 iterations)
  EXPECT_LE(its[1], 25);
}

TEST(Amg, UpdateUsesTheNewValues) {
  const int n = 90;
  const RowMat a1 = tutte_grid(n, 6), a2 = tutte_grid(n, 7);  // same pattern, other weights
  const Block b = boundary_rhs(n);
  AmgPreconditioner m;
  m.setup(a1);
  m.update(a2);
  Block x;
  ASSERT_GT(solve(a2, m, b, x), 0);
  const Block x2 = direct_solve(a2, b), x1 = direct_solve(a1, b);
  EXPECT_LT((x - x2).cwiseAbs().maxCoeff(), 1e-8);
  ASSERT_GT((x1 - x2).cwiseAbs().maxCoeff(), 1e-3);  // the two systems really differ
}

TEST(Amg, MissingDiagonalIsASolverError) {
  RowMat a = tutte_grid(10, 8);
  a.coeffRef(55, 55) = 0.0;
  a.prune([](int r, int c, double) { return !(r == 55 && c == 55); });
  AmgPreconditioner m;
  EXPECT_THROW(m.setup(a), SolverError);
}

}  // namespace
}  // namespace adaptex::detail
