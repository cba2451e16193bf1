#pragma once
/// \file amg.h
/// Internal: smoothed-aggregation algebraic multigrid preconditioner (Vaněk, Mandel, Brezina 1996)
/// for the large non-symmetric Tutte systems of floater.cpp (§2.2). The aggregates (and so every
/// sparsity pattern) are computed once; update() recomputes the Galerkin operators for new values,
/// which is what the Yoshizawa iterations need. Used as the preconditioner of BiCGSTAB.
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <memory>
#include <vector>

namespace adaptex::detail {

class AmgPreconditioner {
 public:
  using RowMat = Eigen::SparseMatrix<double, Eigen::RowMajor>;

  /// Builds the hierarchy for \p a (square, non-zero diagonal, structurally symmetric pattern).
  void setup(const RowMat& a);
  /// Recomputes all level operators for new values of a matrix with the pattern given to setup().
  void update(const RowMat& a);
  /// Two right-hand sides at once (u and v), row-major for locality.
  using Block = Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>;
  /// One V(1,1)-cycle (forward Gauss–Seidel before, backward after) from a zero guess: z ≈ A⁻¹ r.
  Block apply(const Block& r) const;
  int num_levels() const { return static_cast<int>(levels_.size()); }

 private:
  struct Level {
    RowMat a;                    ///< Operator of this level.
    std::vector<int> diag_pos;   ///< Position of the diagonal entry in each row of a.
    std::vector<int> aggregate;  ///< Aggregate (coarse unknown) of each unknown.
    int num_coarse = 0;
    RowMat p, r;                 ///< Smoothed prolongator and restriction (= pᵀ) to the next level.
  };
  void build_operators(size_t from);
  void vcycle(size_t l, const Block& b, Block& x) const;
  std::vector<Level> levels_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> coarse_;
};

/// y = A x, parallel over rows.
void multiply(const AmgPreconditioner::RowMat& a, const AmgPreconditioner::Block& x,
              AmgPreconditioner::Block& y);

/// BiCGSTAB (van der Vorst 1992) on both columns of \p b at once, right-preconditioned by \p m,
/// starting from \p x. Stops when ||b - A x|| <= tol ||b|| for both columns.
/// \return iterations performed, or -1 (x holds the last iterate) when the columns did not both
/// converge within max_iterations or the iteration broke down (non-finite values).
int bicgstab(const AmgPreconditioner::RowMat& a, const AmgPreconditioner& m,
             const AmgPreconditioner::Block& b, AmgPreconditioner::Block& x, double tol,
             int max_iterations);

}  // namespace adaptex::detail
