/// \file amg.cpp
/// Smoothed-aggregation AMG preconditioner for the Tutte systems (§2.2); see amg.h.
#include "amg.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "adaptex/core/errors.h"

namespace adaptex::detail {

namespace {

constexpr int kCoarsest = 2000;      // direct solve below this many unknowns
constexpr int kMaxLevels = 16;
constexpr double kStrength = 0.08;   // strong connection: |a_ij| >= θ sqrt(|a_ii a_jj|)

std::vector<int> diagonal_positions(const AmgPreconditioner::RowMat& a) {
  std::vector<int> pos(a.rows(), -1);
  for (int i = 0; i < a.outerSize(); ++i)
    for (int k = a.outerIndexPtr()[i]; k < a.outerIndexPtr()[i + 1]; ++k)
      if (a.innerIndexPtr()[k] == i) pos[i] = k;
  for (int p : pos)
    if (p < 0) throw SolverError("AMG: a row of the Tutte matrix has no diagonal entry");
  return pos;
}

/// Greedy aggregation on the strong-connection graph (Vaněk et al. 1996, passes 1-3).
std::vector<int> aggregate(const AmgPreconditioner::RowMat& a, const std::vector<int>& diag, int& nc) {
  const int n = static_cast<int>(a.rows());
  const int* outer = a.outerIndexPtr();
  const int* inner = a.innerIndexPtr();
  const double* val = a.valuePtr();
  auto strong = [&](int i, int k) {
    const int j = inner[k];
    return j != i && std::abs(val[k]) >= kStrength * std::sqrt(std::abs(val[diag[i]] * val[diag[j]]));
  };
  std::vector<int> agg(n, -1);
  nc = 0;
  for (int i = 0; i < n; ++i) {  // pass 1: whole free neighbourhoods
    if (agg[i] >= 0) continue;
    bool free = true;
    for (int k = outer[i]; k < outer[i + 1] && free; ++k)
      if (strong(i, k) && agg[inner[k]] >= 0) free = false;
    if (!free) continue;
    agg[i] = nc;
    for (int k = outer[i]; k < outer[i + 1]; ++k)
      if (strong(i, k)) agg[inner[k]] = nc;
    ++nc;
  }
  std::vector<int> pass1 = agg;
  for (int i = 0; i < n; ++i) {  // pass 2: join a neighbouring aggregate
    if (agg[i] >= 0) continue;
    for (int k = outer[i]; k < outer[i + 1]; ++k)
      if (strong(i, k) && pass1[inner[k]] >= 0) {
        agg[i] = pass1[inner[k]];
        break;
      }
  }
  for (int i = 0; i < n; ++i) {  // pass 3: whatever is left
    if (agg[i] >= 0) continue;
    agg[i] = nc;
    for (int k = outer[i]; k < outer[i + 1]; ++k)
      if (strong(i, k) && agg[inner[k]] < 0) agg[inner[k]] = nc;
    ++nc;
  }
  return agg;
}

}  // namespace

void AmgPreconditioner::setup(const RowMat& a) {
  levels_.clear();
  levels_.push_back(Level{});
  levels_[0].a = a;
  levels_[0].diag_pos = diagonal_positions(a);
  while (static_cast<int>(levels_.back().a.rows()) > kCoarsest &&
         static_cast<int>(levels_.size()) < kMaxLevels) {
    Level& l = levels_.back();
    l.aggregate = aggregate(l.a, l.diag_pos, l.num_coarse);
    if (l.num_coarse > 0.8 * static_cast<double>(l.a.rows()) || l.num_coarse < 1) {
      l.aggregate.clear();
      break;
    }
    levels_.push_back(Level{});
    build_operators(levels_.size() - 2);
  }
  coarse_.compute(Eigen::SparseMatrix<double>(levels_.back().a));
  if (coarse_.info() != Eigen::Success) throw SolverError("AMG: coarsest-level factorization failed");
}

void AmgPreconditioner::update(const RowMat& a) {
  if (levels_.empty() || a.nonZeros() != levels_[0].a.nonZeros()) {
    setup(a);
    return;
  }
  std::copy(a.valuePtr(), a.valuePtr() + a.nonZeros(), levels_[0].a.valuePtr());
  for (size_t l = 0; l + 1 < levels_.size(); ++l) build_operators(l);
  coarse_.compute(Eigen::SparseMatrix<double>(levels_.back().a));
  if (coarse_.info() != Eigen::Success) throw SolverError("AMG: coarsest-level factorization failed");
}

/// P = (I - ω D⁻¹ A) P_tent, R = Pᵀ, A_c = R A P for level \p l -> l+1.
void AmgPreconditioner::build_operators(size_t l) {
  Level& lv = levels_[l];
  const RowMat& a = lv.a;
  const int n = static_cast<int>(a.rows());
  const int* outer = a.outerIndexPtr();
  const int* inner = a.innerIndexPtr();
  const double* val = a.valuePtr();
  double rho = 0;  // Gershgorin bound of ρ(D⁻¹A)
  for (int i = 0; i < n; ++i) {
    double s = 0;
    for (int k = outer[i]; k < outer[i + 1]; ++k) s += std::abs(val[k]);
    rho = std::max(rho, s / std::abs(val[lv.diag_pos[i]]));
  }
  const double omega = 4.0 / (3.0 * std::max(rho, 1e-300));
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(a.nonZeros());
  std::vector<std::pair<int, double>> row;
  auto add = [&row](int c, double v) {
    for (auto& e : row)
      if (e.first == c) {
        e.second += v;
        return;
      }
    row.emplace_back(c, v);
  };
  for (int i = 0; i < n; ++i) {
    row.clear();
    const double dinv = 1.0 / val[lv.diag_pos[i]];
    add(lv.aggregate[i], 1.0);
    for (int k = outer[i]; k < outer[i + 1]; ++k) add(lv.aggregate[inner[k]], -omega * dinv * val[k]);
    for (const auto& [c, v] : row) trip.emplace_back(i, c, v);
  }
  lv.p.resize(n, lv.num_coarse);
  lv.p.setFromTriplets(trip.begin(), trip.end());
  lv.r = lv.p.transpose();
  Level& next = levels_[l + 1];
  next.a = lv.r * (a * lv.p);
  next.a.makeCompressed();
  next.diag_pos = diagonal_positions(next.a);
}

void multiply(const AmgPreconditioner::RowMat& a, const AmgPreconditioner::Block& x,
              AmgPreconditioner::Block& y) {
  const int n = static_cast<int>(a.rows());
  y.resize(n, 2);
  const int* outer = a.outerIndexPtr();
  const int* inner = a.innerIndexPtr();
  const double* val = a.valuePtr();
  tbb::parallel_for(tbb::blocked_range<int>(0, n, 8192), [&](const tbb::blocked_range<int>& r) {
    for (int i = r.begin(); i != r.end(); ++i) {
      double s0 = 0, s1 = 0;
      for (int k = outer[i]; k < outer[i + 1]; ++k) {
        s0 += val[k] * x(inner[k], 0);
        s1 += val[k] * x(inner[k], 1);
      }
      y(i, 0) = s0;
      y(i, 1) = s1;
    }
  });
}

void AmgPreconditioner::vcycle(size_t l, const Block& b, Block& x) const {
  if (l + 1 == levels_.size()) {
    x = Eigen::MatrixX2d(coarse_.solve(Eigen::MatrixX2d(b)));
    return;
  }
  const Level& lv = levels_[l];
  const int n = static_cast<int>(lv.a.rows());
  const int* outer = lv.a.outerIndexPtr();
  const int* inner = lv.a.innerIndexPtr();
  const double* val = lv.a.valuePtr();
  auto relax = [&](int i) {
    double s0 = b(i, 0), s1 = b(i, 1);
    for (int k = outer[i]; k < outer[i + 1]; ++k) {
      s0 -= val[k] * x(inner[k], 0);
      s1 -= val[k] * x(inner[k], 1);
    }
    const double d = 1.0 / val[lv.diag_pos[i]];
    x(i, 0) += s0 * d;
    x(i, 1) += s1 * d;
  };
  x.setZero(n, 2);
  for (int i = 0; i < n; ++i) relax(i);  // forward Gauss–Seidel
  Block ax;
  multiply(lv.a, x, ax);
  const Block res = b - ax;
  const Block bc = lv.r * res;
  Block xc;
  vcycle(l + 1, bc, xc);
  Block px;
  multiply(lv.p, xc, px);
  x += px;
  for (int i = n - 1; i >= 0; --i) relax(i);  // backward Gauss–Seidel
}

AmgPreconditioner::Block AmgPreconditioner::apply(const Block& r) const {
  Block x;
  vcycle(0, r, x);
  return x;
}

int bicgstab(const AmgPreconditioner::RowMat& a, const AmgPreconditioner& m,
             const AmgPreconditioner::Block& b, AmgPreconditioner::Block& x, double tol,
             int max_iterations) {
  using Block = AmgPreconditioner::Block;
  using Row = Eigen::RowVector2d;
  const int n = static_cast<int>(a.rows());
  Block r, v = Block::Zero(n, 2), p = Block::Zero(n, 2), y, z, t, s;
  multiply(a, x, t);
  r = b - t;
  Block r0 = r;
  const Row bnorm = b.colwise().norm().cwiseMax(Row::Constant(1e-300));
  Row rho = Row::Ones(), alpha = Row::Ones(), omega = Row::Ones();
  auto converged = [&](const Block& res) {
    const Row rel = res.colwise().norm().cwiseQuotient(bnorm);
    return rel[0] <= tol && rel[1] <= tol;
  };
  if (converged(r)) return 0;
  for (int it = 1; it <= max_iterations; ++it) {
    const Row rho_new = (r0.cwiseProduct(r)).colwise().sum();
    for (int c = 0; c < 2; ++c) {
      if (std::abs(rho_new[c]) < 1e-300) {  // breakdown: restart this column
        r0.col(c) = r.col(c);
        p.col(c).setZero();
        v.col(c).setZero();
        rho[c] = alpha[c] = omega[c] = 1;
      }
    }
    const Row rho_cur = (r0.cwiseProduct(r)).colwise().sum();
    const Row beta = rho_cur.cwiseQuotient(rho).cwiseProduct(alpha.cwiseQuotient(omega));
    for (int c = 0; c < 2; ++c) p.col(c) = r.col(c) + beta[c] * (p.col(c) - omega[c] * v.col(c));
    y = m.apply(p);
    multiply(a, y, v);
    const Row r0v = (r0.cwiseProduct(v)).colwise().sum();
    for (int c = 0; c < 2; ++c) alpha[c] = r0v[c] != 0 ? rho_cur[c] / r0v[c] : 0.0;
    s = r;
    for (int c = 0; c < 2; ++c) s.col(c) -= alpha[c] * v.col(c);
    if (converged(s)) {
      for (int c = 0; c < 2; ++c) x.col(c) += alpha[c] * y.col(c);
      return it;
    }
    z = m.apply(s);
    multiply(a, z, t);
    const Row ts = (t.cwiseProduct(s)).colwise().sum();
    const Row tt = t.colwise().squaredNorm();
    for (int c = 0; c < 2; ++c) {
      omega[c] = tt[c] > 0 ? ts[c] / tt[c] : 0.0;
      x.col(c) += alpha[c] * y.col(c) + omega[c] * z.col(c);
      r.col(c) = s.col(c) - omega[c] * t.col(c);
      if (omega[c] == 0) omega[c] = 1e-300;  // avoid 0/0 in beta; restart happens via rho
    }
    rho = rho_cur;
    if (converged(r)) return it;
    if (!r.allFinite()) return -1;  // breakdown with non-finite values
  }
  return -1;
}

}  // namespace adaptex::detail
