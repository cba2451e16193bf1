/// \file slim.cpp
/// Free-boundary, locally injective symmetric Dirichlet layouts (slim.h).
#include "adaptex/param/slim.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "adaptex/core/errors.h"

namespace adaptex {

namespace {

double slim_cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// One face's 3-D area and the gradients of its three hat functions in a frame of its plane.
struct SlimFace {
  double area = 0;         ///< 0 for a zero-area face (no energy, still kept from flipping)
  std::array<Vec2, 3> g{};  ///< ∇φ_i
};

std::vector<SlimFace> slim_faces(const TriMesh& disk) {
  std::vector<SlimFace> out(disk.faces.size());
  for (size_t f = 0; f < disk.faces.size(); ++f) {
    const Face& t = disk.faces[f];
    const Vec3 e1 = disk.positions[t[1]] - disk.positions[t[0]];
    const Vec3 e2 = disk.positions[t[2]] - disk.positions[t[0]];
    const double l1 = e1.norm(), area2 = e1.cross(e2).norm();
    if (!(l1 > 0 && area2 > 1e-300)) continue;
    const std::array<Vec2, 3> x = {Vec2(0, 0), Vec2(l1, 0), Vec2(e2.dot(e1) / l1, area2 / l1)};
    out[f].area = 0.5 * area2;
    for (int i = 0; i < 3; ++i) {
      const Vec2 e = x[(i + 2) % 3] - x[(i + 1) % 3];
      out[f].g[i] = Vec2(-e.y(), e.x()) / area2;
    }
  }
  return out;
}

/// J = Σ_i uv_i ∇φ_iᵀ of face \p f (row 0: ∇u, row 1: ∇v).
Eigen::Matrix2d jacobian(const Face& t, const SlimFace& d, const std::vector<Vec2>& uv) {
  Eigen::Matrix2d j = Eigen::Matrix2d::Zero();
  for (int i = 0; i < 3; ++i) j += uv[t[i]] * d.g[i].transpose();
  return j;
}

/// SLIM's local step for one Jacobian \p j = U Σ Vᵀ: the closest rotation R = U Vᵀ and the proxy's
/// metric M = Wᵀ W = U diag(w₁², w₂²) Uᵀ with w² = (σ − σ⁻³) / (σ − 1) (4 at σ = 1; 4 I for a
/// flipped or degenerate face).
struct SlimLocal {
  Eigen::Matrix2d rot, metric;
};

/// The singular values σ₁ = q + r >= σ₂ = q − r of \p j (q, r: the norms of its conformal and
/// anticonformal parts e, h and f, g).
struct SlimSingular {
  double e, h, f, g, s1, s2;
};

SlimSingular slim_singular(const Eigen::Matrix2d& j) {
  const double e = 0.5 * (j(0, 0) + j(1, 1)), h = 0.5 * (j(1, 0) - j(0, 1));
  const double f = 0.5 * (j(0, 0) - j(1, 1)), g = 0.5 * (j(1, 0) + j(0, 1));
  const double q = std::hypot(e, h), r = std::hypot(f, g);
  return {e, h, f, g, q + r, q - r};
}

/// The energy density σ₁² + σ₁⁻² + σ₂² + σ₂⁻² of \p sv (+inf when the face is flipped or
/// degenerate).
double slim_density(const SlimSingular& sv) {
  if (!(sv.s2 > 0)) return std::numeric_limits<double>::infinity();
  return sv.s1 * sv.s1 + 1 / (sv.s1 * sv.s1) + sv.s2 * sv.s2 + 1 / (sv.s2 * sv.s2);
}

SlimLocal slim_local(const Eigen::Matrix2d& j) {
  const SlimSingular sv = slim_singular(j);
  const double a1 = std::atan2(sv.g, sv.f), a2 = std::atan2(sv.h, sv.e);
  const auto rotation = [](double angle) {
    Eigen::Matrix2d m;
    m << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
    return m;
  };
  SlimLocal out;
  out.rot = rotation(a2);
  if (!(sv.s2 > 0)) {
    out.metric = 4 * Eigen::Matrix2d::Identity();
    return out;
  }
  const auto weight = [](double s) {
    return std::abs(s - 1) < 1e-8 ? 4.0 : (s - 1 / (s * s * s)) / (s - 1);
  };
  const Eigen::Matrix2d u = rotation(0.5 * (a2 + a1));
  out.metric = u * Eigen::Vector2d(weight(sv.s1), weight(sv.s2)).asDiagonal() * u.transpose();
  return out;
}

/// The energy needs no rotations: only the singular values (no atan2, sin or cos per face).
double slim_energy(const TriMesh& disk, const std::vector<SlimFace>& fd, const std::vector<Vec2>& uv) {
  double sum = 0;
  for (size_t f = 0; f < fd.size(); ++f)
    if (fd[f].area > 0) sum += fd[f].area * slim_density(slim_singular(jacobian(disk.faces[f], fd[f], uv)));
  return sum;
}

/// Largest t in [0, ∞] such that no face of \p uv + s · \p d, s in [0, t), has lost its positive area.
double flip_free_step(const TriMesh& disk, const std::vector<Vec2>& uv, const std::vector<Vec2>& d) {
  double tmax = std::numeric_limits<double>::infinity();
  for (const Face& t : disk.faces) {
    const Vec2 e1 = uv[t[1]] - uv[t[0]], e2 = uv[t[2]] - uv[t[0]];
    const Vec2 d1 = d[t[1]] - d[t[0]], d2 = d[t[2]] - d[t[0]];
    const double c = slim_cross(e1, e2), b = slim_cross(e1, d2) + slim_cross(d1, e2), a = slim_cross(d1, d2);
    double root = std::numeric_limits<double>::infinity();
    if (std::abs(a) <= 1e-14 * std::abs(b)) {
      if (b < 0) root = -c / b;
    } else {
      const double disc = b * b - 4 * a * c;
      if (disc >= 0) {
        const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
        for (const double r : {q / a, q != 0 ? c / q : -1.0})
          if (r > 0) root = std::min(root, r);
      }
    }
    tmax = std::min(tmax, root);
  }
  return tmax;
}

void check_slim_input(const TriMesh& disk, const std::vector<Vec2>& start) {
  check_layout_mesh(disk, "slim_relax");
  const int nv = disk.num_vertices();
  if (static_cast<int>(start.size()) != nv)
    throw InvalidInputError("slim_relax: the start layout has " + std::to_string(start.size()) +
                            " entries for " + std::to_string(nv) + " vertices");
  for (const Vec2& p : start)
    if (!p.allFinite()) throw InvalidInputError("slim_relax: a start coordinate is not finite");
}

/// \p start scaled to the 3-D area of \p fd; empty when a face is flipped or degenerate.
std::vector<Vec2> scaled_start(const TriMesh& disk, const std::vector<SlimFace>& fd,
                               const std::vector<Vec2>& start) {
  double a2 = 0, a3 = 0;
  for (size_t f = 0; f < fd.size(); ++f) {
    const Face& t = disk.faces[f];
    const double s = 0.5 * slim_cross(start[t[1]] - start[t[0]], start[t[2]] - start[t[0]]);
    if (!(s > 0)) return {};
    a2 += s, a3 += fd[f].area;
  }
  if (!(a2 > 0 && a3 > 0)) return {};
  const double k = std::sqrt(a3 / a2);
  std::vector<Vec2> uv(start.size());
  for (size_t v = 0; v < uv.size(); ++v) uv[v] = start[v] * k;
  return uv;
}

/// The minimizer of SLIM's proxy Σ_f A_f ‖W_f (J_f − R_f)‖² + μ ‖x − uv‖² (unknowns u then v):
/// per face the block A_f (M_f ⊗ G_f), G_f = (∇φ_i·∇φ_k), and the right-hand side A_f M_f R_f ∇φ_i.
/// The proximal term μ (1e-8 of the mean diagonal) fixes the translation and the vertices of
/// zero-area faces only. Empty when the factorization fails. The matrix's pattern is the same in
/// every iteration: the first builds it from triplets, the later ones add the same terms in the same
/// order straight into its values (the sums setFromTriplets() forms, bit for bit).
class SlimSolver {
 public:
  SlimSolver(const TriMesh& disk, const std::vector<SlimFace>& fd) : disk_(disk), fd_(fd) {}

  std::vector<Vec2> solve(const std::vector<Vec2>& uv) {
    const int nv = disk_.num_vertices();
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(2 * nv);
    if (!analyzed_) {
      assemble(uv, rhs, [&](int r, int c, double v) { trip_.emplace_back(r, c, v); });
      k_.resize(2 * nv, 2 * nv);
      k_.setFromTriplets(trip_.begin(), trip_.end());
      map_triplets();
      solver_.analyzePattern(k_);
      analyzed_ = true;
    } else {
      double* values = k_.valuePtr();
      size_t i = 0;
      assemble(uv, rhs, [&](int, int, double v) {
        const size_t p = slot_[i];
        values[p] = first_[i++] ? v : values[p] + v;
      });
    }
    solver_.factorize(k_);
    if (solver_.info() != Eigen::Success) return {};
    const Eigen::VectorXd x = solver_.solve(rhs);
    if (solver_.info() != Eigen::Success || !x.allFinite()) return {};
    std::vector<Vec2> out(nv);
    for (int v = 0; v < nv; ++v) out[v] = Vec2(x[v], x[nv + v]);
    return out;
  }

 private:
  /// Calls \p add(row, column, value) for every term of the matrix, in a fixed order, and adds up
  /// the right-hand side in \p rhs.
  template <class Add>
  void assemble(const std::vector<Vec2>& uv, Eigen::VectorXd& rhs, Add&& add) const {
    const int nv = disk_.num_vertices();
    Eigen::VectorXd diag = Eigen::VectorXd::Zero(2 * nv);
    for (size_t f = 0; f < fd_.size(); ++f) {
      const SlimFace& d = fd_[f];
      if (!(d.area > 0)) continue;
      const Face& t = disk_.faces[f];
      const SlimLocal l = slim_local(jacobian(t, d, uv));
      const Eigen::Matrix2d m = d.area * l.metric, mr = m * l.rot;
      for (int i = 0; i < 3; ++i) {
        const Vec2 b = mr * d.g[i];
        rhs[t[i]] += b.x(), rhs[nv + t[i]] += b.y();
        for (int k = 0; k < 3; ++k) {
          const double gik = d.g[i].dot(d.g[k]);
          for (int r = 0; r < 2; ++r)
            for (int c = 0; c < 2; ++c) add(r * nv + t[i], c * nv + t[k], m(r, c) * gik);
          if (i == k) diag[t[i]] += m(0, 0) * gik, diag[nv + t[i]] += m(1, 1) * gik;
        }
      }
    }
    const double mu = 1e-8 * std::max(diag.sum() / (2 * nv), 1e-300);
    for (int v = 0; v < nv; ++v) {
      add(v, v, mu), add(nv + v, nv + v, mu);
      rhs[v] += mu * uv[v].x(), rhs[nv + v] += mu * uv[v].y();
    }
  }

  /// The value slot of every triplet in k_, and whether it is the first triplet of its entry
  /// (setFromTriplets() sums duplicates left to right in the order given).
  void map_triplets() {
    slot_.resize(trip_.size());
    first_.assign(trip_.size(), 0);
    std::vector<char> seen(k_.nonZeros(), 0);
    const int* outer = k_.outerIndexPtr();
    const int* inner = k_.innerIndexPtr();
    for (size_t i = 0; i < trip_.size(); ++i) {
      const int c = trip_[i].col();
      const int* p = std::lower_bound(inner + outer[c], inner + outer[c + 1], trip_[i].row());
      slot_[i] = static_cast<size_t>(p - inner);
      first_[i] = !seen[slot_[i]];
      seen[slot_[i]] = 1;
    }
    std::vector<Eigen::Triplet<double>>().swap(trip_);
  }

  const TriMesh& disk_;
  const std::vector<SlimFace>& fd_;
  std::vector<Eigen::Triplet<double>> trip_;
  std::vector<size_t> slot_;
  std::vector<char> first_;
  Eigen::SparseMatrix<double> k_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver_;
  bool analyzed_ = false;
};

/// slim_relax() with max_iterations = caps[i] into out[i], for every i, from one run: the iterates
/// of a lower cap are the first ones of a higher cap's.
std::vector<std::vector<Vec2>> relax_capped(const TriMesh& disk, const std::vector<Vec2>& start,
                                            double tolerance, const std::vector<int>& caps) {
  check_slim_input(disk, start);
  std::vector<std::vector<Vec2>> out(caps.size());
  const std::vector<SlimFace> fd = slim_faces(disk);
  std::vector<Vec2> uv = scaled_start(disk, fd, start);
  if (uv.empty()) {
    out.assign(caps.size(), start);
    return out;
  }
  std::vector<char> kept(caps.size(), 0);
  const auto keep = [&](int done) {  // the caps reached after done iterations
    for (size_t i = 0; i < caps.size(); ++i)
      if (!kept[i] && caps[i] <= done) out[i] = uv, kept[i] = 1;
  };
  keep(0);
  double energy = slim_energy(disk, fd, uv);
  const int max_iterations = caps.empty() ? 0 : *std::max_element(caps.begin(), caps.end());
  if (std::isfinite(energy) && energy > 0) {
    SlimSolver solver(disk, fd);
    std::vector<Vec2> d(uv.size()), next(uv.size());
    for (int it = 0; it < max_iterations; ++it) {
      const std::vector<Vec2> target = solver.solve(uv);
      if (target.empty()) break;
      for (size_t v = 0; v < uv.size(); ++v) d[v] = target[v] - uv[v];
      double t = std::min(1.0, 0.9 * flip_free_step(disk, uv, d));
      double next_energy = energy;
      for (int halving = 0; halving < 8 && t > 0; ++halving, t *= 0.5) {
        for (size_t v = 0; v < uv.size(); ++v) next[v] = uv[v] + t * d[v];
        next_energy = slim_energy(disk, fd, next);
        if (next_energy < energy) break;
      }
      if (!(next_energy < energy)) break;
      const double drop = (energy - next_energy) / energy;
      uv.swap(next);
      energy = next_energy;
      keep(it + 1);
      if (drop < tolerance) break;
    }
  }
  for (size_t i = 0; i < caps.size(); ++i)
    if (!kept[i]) out[i] = uv;
  return out;
}

}  // namespace

std::vector<Vec2> slim_relax(const TriMesh& disk, const std::vector<Vec2>& start,
                             const SlimOptions& options) {
  return std::move(relax_capped(disk, start, options.tolerance, {options.max_iterations})[0]);
}

std::optional<PolygonLayout> slim_layout(const TriMesh& disk, const std::vector<Vec2>& start,
                                         const SlimOptions& options) {
  return fit_to_rectangle(disk, slim_relax(disk, start, options));
}

std::optional<PolygonLayout> slim_layout_halving(const TriMesh& disk, const std::vector<Vec2>& start,
                                                 const SlimOptions& options) {
  std::vector<int> caps;
  for (int n = options.max_iterations; n >= 1; n /= 2) caps.push_back(n);
  if (caps.empty()) {
    check_slim_input(disk, start);  // bad input is an error whatever the iteration count
    return std::nullopt;
  }
  std::vector<std::vector<Vec2>> runs = relax_capped(disk, start, options.tolerance, caps);
  // A run that stopped before a cap gives the next lower cap's layout too (rejected already).
  std::vector<char> repeat(runs.size(), 0);
  for (size_t i = 1; i < runs.size(); ++i) repeat[i] = runs[i] == runs[i - 1];
  for (size_t i = 0; i < runs.size(); ++i)
    if (!repeat[i])
      if (std::optional<PolygonLayout> u = fit_to_rectangle(disk, std::move(runs[i]))) return u;
  return std::nullopt;
}

}  // namespace adaptex
