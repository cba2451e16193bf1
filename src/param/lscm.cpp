/// \file lscm.cpp
/// Least-squares conformal maps (lscm.h).
#include "adaptex/param/lscm.h"

#include <array>
#include <cmath>
#include <vector>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

namespace adaptex {

namespace {

/// Two vertices far apart (3-D): the farthest from vertex 0, and the farthest from that one.
std::array<int, 2> far_pair(const TriMesh& disk) {
  auto farthest = [&](int from) {
    int best = from;
    double d = -1;
    for (int v = 0; v < disk.num_vertices(); ++v) {
      const double dv = (disk.positions[v] - disk.positions[from]).squaredNorm();
      if (dv > d) d = dv, best = v;
    }
    return best;
  };
  const int a = farthest(0);
  return {a, farthest(a)};
}

}  // namespace

std::optional<PolygonLayout> lscm_layout(const TriMesh& disk) {
  check_layout_mesh(disk, "lscm_layout");
  const int nv = disk.num_vertices();
  if (disk.faces.empty() || nv < 3) return std::nullopt;
  const auto [pa, pb] = far_pair(disk);
  const double d = (disk.positions[pa] - disk.positions[pb]).norm();
  if (!(d > 0)) return std::nullopt;

  // Unknowns u_0..u_{n-1}, v_0..v_{n-1}; the pinned ones are moved to the right-hand side.
  // Per face, in an orthonormal frame of its plane, the gradient of a linear function is
  // sum_i f_i g_i with g_i = rot(x_{i+2} - x_{i+1}) / (2A); the Cauchy–Riemann residuals
  // u_y + v_x and v_y - u_x, weighted by sqrt(A), are the rows of M.
  std::vector<int> col(2 * nv, -1);
  int nfree = 0;
  for (int v = 0; v < nv; ++v)
    if (v != pa && v != pb) col[v] = nfree++, col[nv + v] = nfree++;
  Eigen::VectorXd pinned = Eigen::VectorXd::Zero(2 * nv);
  pinned[pb] = d;  // pa at (0, 0), pb at (d, 0)
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(disk.faces.size() * 12);
  Eigen::VectorXd rhs_rows = Eigen::VectorXd::Zero(2 * static_cast<long>(disk.faces.size()));
  int row = 0;
  for (const Face& t : disk.faces) {
    const Vec3 e1 = disk.positions[t[1]] - disk.positions[t[0]];
    const Vec3 e2 = disk.positions[t[2]] - disk.positions[t[0]];
    const double l1 = e1.norm(), area2 = e1.cross(e2).norm();
    if (!(l1 > 0 && area2 > 0)) continue;
    const std::array<Vec2, 3> x = {Vec2(0, 0), Vec2(l1, 0), Vec2(e2.dot(e1) / l1, area2 / l1)};
    const double w = std::sqrt(0.5 * area2);
    for (int i = 0; i < 3; ++i) {
      const Vec2 e = x[(i + 2) % 3] - x[(i + 1) % 3];
      const double gx = -e.y() / area2 * w, gy = e.x() / area2 * w;  // sqrt(A) * grad of hat i
      // row: u_y + v_x;  row + 1: v_y - u_x
      const std::array<std::array<double, 3>, 2> coef = {{{gy, gx, 0}, {-gx, gy, 0}}};
      for (int r = 0; r < 2; ++r) {
        const double cu = coef[r][0], cv = coef[r][1];
        const int iu = t[i], iv = nv + t[i];
        if (col[iu] >= 0) trip.emplace_back(row + r, col[iu], cu);
        else rhs_rows[row + r] -= cu * pinned[iu];
        if (col[iv] >= 0) trip.emplace_back(row + r, col[iv], cv);
        else rhs_rows[row + r] -= cv * pinned[iv];
      }
    }
    row += 2;
  }
  if (row == 0 || nfree == 0) return std::nullopt;
  Eigen::SparseMatrix<double> m(row, nfree);
  m.setFromTriplets(trip.begin(), trip.end());
  const Eigen::SparseMatrix<double> mt = m.transpose();
  const Eigen::SparseMatrix<double> normal = mt * m;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal);
  if (solver.info() != Eigen::Success) return std::nullopt;
  const Eigen::VectorXd x = solver.solve(mt * rhs_rows.head(row));
  if (solver.info() != Eigen::Success || !x.allFinite()) return std::nullopt;
  std::vector<Vec2> uv(nv);
  for (int v = 0; v < nv; ++v)
    uv[v] = col[v] >= 0 ? Vec2(x[col[v]], x[col[nv + v]]) : Vec2(pinned[v], pinned[nv + v]);
  return fit_to_rectangle(disk, std::move(uv));
}

}  // namespace adaptex
