// Polishing a warp lattice by the anisotropic error model (error_polish.h, docs/error_model.md §7).
#include "adaptex/adapt/error_polish.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "adaptex/core/errors.h"
#include "adaptex/core/predicates.h"

namespace adaptex {

namespace {

/// A point is relaxed again only if its ring moved more than this many lattice cells in the sweep
/// before: 1e-3 relaxes nearly every point (docs/decisions.md, "settle_cells").
constexpr double kSettleCells = 1e-3;


/// x^e for x > 0: exact at the exponents the error model clamps to (p = 1 and 4: e = 0.5, 2), else in
/// single precision (relative error ~1e-6, plenty for an energy that is minimized; double exp / log took
/// 40 % of an end-mode re-parameterization of `mixed` on venus at 256²: polish 460 -> 315 ms). Short
/// double-precision series (range reduction, degree 9 / 11) were slower still: 315 -> 440 ms.
inline double power(double x, double e) {
  if (e == 0.5) return std::sqrt(x);
  if (e == 2.0) return x * x;
  if (e == 1.0) return x;
  const float l = static_cast<float>(e) * std::log2(static_cast<float>(x));
  if (!(std::abs(l) < 120.0f)) return std::exp2(e * std::log2(x));  // beyond float's range
  return std::exp2(l);
}

/// Coefficients of a point in the edge vectors of a cell's corner triangles: the point is corner k
/// (0 = A (i, j), 1 = B (i+1, j), 2 = C (i+1, j+1), 3 = D (i, j+1)) of the cell, and corner triangle t
/// has edges ex (along i) and ey (along j): t0 at A (B−A, D−A), t1 at B (B−A, C−B), t2 at C (C−D, C−B),
/// t3 at D (C−D, D−A). kS[k][t] = {coefficient in ex, coefficient in ey}.
constexpr int kS[4][4][2] = {
    {{-1, -1}, {-1, 0}, {0, 0}, {0, -1}},  // A
    {{1, 0}, {1, -1}, {0, -1}, {0, 0}},    // B
    {{0, 0}, {0, 1}, {1, 1}, {1, 0}},      // C
    {{0, 1}, {0, 0}, {-1, 0}, {-1, 1}},    // D
};

/// The energy of one point and its exact gradient and Hessian.
struct Local {
  double e = 0;
  Vec2 g = Vec2::Zero();
  Eigen::Matrix2d h = Eigen::Matrix2d::Zero();
};

class Polisher {
 public:
  Polisher(GridWarp& w, const PolishFields& f, const ErrorPolishOptions& o)
      : w_(w), f_(f), o_(o), n_(w.n), nn_(double(w.n) * w.n),
        cx_(1 / (f.aspect * f.aspect)), cy_(f.aspect * f.aspect), aspect_(f.aspect) {
    double qs = 0;
    int qn = 0;
    for (float q : f.error.data)
      if (q > 0) qs += q, ++qn;
    kappa_ = qn ? o.floor_weight * qs / qn : 0.0;
    mu_ = qn ? o.shape_weight * qs / qn : 0.0;
  }

  /// |S·J·S⁻¹|²_F of the corner triangle with edges ex, ey (see cx_, cy_).
  double frobenius(const Vec2& ex, const Vec2& ey) const {
    return nn_ * (ex.x() * ex.x() + cx_ * ex.y() * ex.y() + cy_ * ey.x() * ey.x() + ey.y() * ey.y());
  }

  /// The edges' direction tensor of cell (ci, cj) (PolishFields::txx, ...; I/2 without them).
  struct Tensor {
    double xx = 0.5, xy = 0, yy = 0.5;
  };
  Tensor tensor(int ci, int cj) const {
    if (f_.txx.data.empty()) return {};
    return {f_.txx.at(ci, cj), f_.txy.at(ci, cj), f_.tyy.at(ci, cj)};
  }

  /// F_T = 2·tr(T·adj(J) adj(J)ᵀ) of the corner triangle with edges ex, ey, J = S·J·S⁻¹ in uv
  /// (= (a b; c d), a = n·ex.x, b = n·r·ey.x, c = n·ex.y / r, d = n·ey.y, r = aspect): 2·|J⁻ᵀ|²_T·det²J,
  /// frobenius() for T = I/2. With \p Derivs its gradient \p gF and diagonal Hessian \p hF in the
  /// point that enters ex and ey with coefficients sx, sy (kS).
  template <bool Derivs>
  double frobenius_t(const Vec2& ex, const Vec2& ey, const Tensor& T, int sx, int sy, Vec2& gF, Vec2& hF) const {
    const double n = std::sqrt(nn_), r = aspect_;
    const double a = n * ex.x(), b = n * r * ey.x(), c = n * ex.y() / r, d = n * ey.y();
    if constexpr (Derivs) {
      const double fa = 4 * (T.yy * a - T.xy * b), fb = 4 * (T.xx * b - T.xy * a);
      const double fc = 4 * (T.yy * c - T.xy * d), fd = 4 * (T.xx * d - T.xy * c);
      gF = Vec2(fa * n * sx + fb * n * r * sy, fc * n * sx / r + fd * n * sy);
      const double ua = n * sx, ub = n * r * sy, uc = n * sx / r, ud = n * sy;
      hF = 4 * Vec2(T.yy * ua * ua + T.xx * ub * ub - 2 * T.xy * ua * ub, T.yy * uc * uc + T.xx * ud * ud - 2 * T.xy * uc * ud);
    }
    return 2 * (T.xx * (d * d + b * b) - 2 * T.xy * (c * d + a * b) + T.yy * (a * a + c * c));
  }

  /// The two power terms of one corner triangle: the error term we·(F_e / (2·D²))^he and the shape
  /// term ws·F_s / (2·D), with their gradient and Hessian from those of F_e, F_s (gradients ge, gs; their
  /// Hessians are diagonal: he2, hs2) and of D (gD; D is affine in the point). With f = gF / F and
  /// d = gD / D, ∇ log ψ = h·(f − a·d) and ∇² log ψ = h·(diag(hF) / F − f fᵀ + a·d dᵀ) (a = 2, h = he
  /// for the error term; a = 1, h = 1 for the shape term).
  template <bool Derivs>
  static void add_triangle_terms(double we, double he, double Fe, const Vec2& ge, const Vec2& he2, double ws,
                                 double Fs, const Vec2& gs, const Vec2& hs2, double D, const Vec2& gD, Local& out) {
    const double iD = 1 / D;
    const double pe = we > 0 ? we * power(0.5 * Fe * iD * iD, he) : 0.0, ps = ws * 0.5 * Fs * iD;
    out.e += pe + ps;
    if constexpr (Derivs) {
      const double dx = gD.x() * iD, dy = gD.y() * iD, dxx = dx * dx, dxy = dx * dy, dyy = dy * dy;
      double gx = 0, gy = 0, hxx = 0, hxy = 0, hyy = 0;
      if (pe > 0) {
        const double iF = 1 / Fe, fx = ge.x() * iF, fy = ge.y() * iF;
        const double ux = fx - 2 * dx, uy = fy - 2 * dy, k = pe * he, kk = k * he;
        gx += k * ux, gy += k * uy;
        hxx += kk * ux * ux + k * (he2.x() * iF - fx * fx + 2 * dxx);
        hxy += kk * ux * uy + k * (-fx * fy + 2 * dxy);
        hyy += kk * uy * uy + k * (he2.y() * iF - fy * fy + 2 * dyy);
      }
      if (ps > 0) {
        const double iF = 1 / Fs, fx = gs.x() * iF, fy = gs.y() * iF;
        const double ux = fx - dx, uy = fy - dy;
        gx += ps * ux, gy += ps * uy;
        hxx += ps * (ux * ux + hs2.x() * iF - fx * fx + dxx);
        hxy += ps * (ux * uy - fx * fy + dxy);
        hyy += ps * (uy * uy + hs2.y() * iF - fy * fy + dyy);
      }
      out.g += Vec2(gx, gy);
      out.h(0, 0) += hxx, out.h(0, 1) += hxy, out.h(1, 0) += hxy, out.h(1, 1) += hyy;
    }
  }

  /// Terms of cell (ci, cj) that depend on its corner k at \p x (the other corners from the lattice).
  /// false: a corner triangle is not positive (x is not allowed).
  template <bool Derivs>
  bool cell_terms(int ci, int cj, int k, const Vec2& x, Local& out) const {
    Vec2 c[4] = {w_.at(ci, cj), w_.at(ci + 1, cj), w_.at(ci + 1, cj + 1), w_.at(ci, cj + 1)};
    c[k] = x;
    const Vec2 ex[4] = {c[1] - c[0], c[1] - c[0], c[2] - c[3], c[2] - c[3]};
    const Vec2 ey[4] = {c[3] - c[0], c[2] - c[1], c[2] - c[1], c[3] - c[0]};
    const double q = f_.error.at(ci, cj), p = f_.exponent.at(ci, cj), lo = f_.floor.at(ci, cj);
    const Tensor T = tensor(ci, cj);
    const bool directed = !f_.txx.data.empty();
    double dsum = 0;
    Vec2 gd_sum = Vec2::Zero();
    for (int t = 0; t < 4; ++t) {
      const double D = nn_ * cross2d(ex[t], ey[t]);
      if (!(D > 0)) return false;
      dsum += D;
      const int sx = kS[k][t][0], sy = kS[k][t][1];
      if (sx == 0 && sy == 0) continue;
      Vec2 gD = Vec2::Zero();
      if constexpr (Derivs) {
        gD = nn_ * (sx * Vec2(ey[t].y(), -ey[t].x()) + sy * Vec2(-ex[t].y(), ex[t].x()));
        gd_sum += gD;
      }
      if (!(q > 0) && !(mu_ > 0)) continue;
      const double F = frobenius(ex[t], ey[t]);
      Vec2 gF = Vec2::Zero(), hF = Vec2::Zero();
      if constexpr (Derivs) {
        gF = 2 * nn_ * (sx * Vec2(ex[t].x(), cx_ * ex[t].y()) + sy * Vec2(cy_ * ey[t].x(), ey[t].y()));
        hF = 2 * nn_ * Vec2(sx * sx + sy * sy * cy_, sx * sx * cx_ + sy * sy);
      }
      // The error term (F_T / 2D²)^(p/2), with the edges' directions when there are any (F_T = F for
      // T = I/2), and the shape term F / 2D (round).
      const double we = q > 0 ? 0.25 * q : 0.0, ws = mu_ > 0 ? 0.25 * mu_ : 0.0;
      if (!directed || !(q > 0)) {
        add_triangle_terms<Derivs>(we, 0.5 * p, F, gF, hF, ws, F, gF, hF, D, gD, out);
        continue;
      }
      Vec2 gT = Vec2::Zero(), hT = Vec2::Zero();
      const double FT = frobenius_t<Derivs>(ex[t], ey[t], T, sx, sy, gT, hT);
      add_triangle_terms<Derivs>(we, 0.5 * p, FT, gT, hT, ws, F, gF, hF, D, gD, out);
    }
    if (lo > 0 && kappa_ > 0) {
      const double d = 0.25 * dsum;
      if (d < lo) {
        const double r = lo / d - 1;
        out.e += kappa_ * r * r;
        if constexpr (Derivs) {
          const Vec2 gd = 0.25 * gd_sum;
          const double d1 = -2 * kappa_ * r * lo / (d * d);
          const double d2 = 2 * kappa_ * (lo * lo / (d * d * d * d) + 2 * r * lo / (d * d * d));
          out.g += d1 * gd;
          out.h += d2 * gd * gd.transpose();
        }
      }
    }
    return true;
  }

  /// The energy of point (i, j) at \p x (+inf where a triangle is not positive).
  template <bool Derivs>
  Local point(int i, int j, const Vec2& x) const {
    Local l;
    // Point (i, j) is A of cell (i, j), B of (i−1, j), C of (i−1, j−1), D of (i, j−1).
    const int ci[4] = {i, i - 1, i - 1, i}, cj[4] = {j, j, j - 1, j - 1};
    for (int k = 0; k < 4; ++k) {
      if (ci[k] < 0 || cj[k] < 0 || ci[k] >= n_ || cj[k] >= n_) continue;
      if (!cell_terms<Derivs>(ci[k], cj[k], k, x, l)) {
        l.e = std::numeric_limits<double>::infinity();
        return l;
      }
    }
    return l;
  }

  /// One damped Newton step of point (i, j); returns the decrease of E.
  double relax(int i, int j) {
    const bool fix_u = i == 0 || i == n_, fix_v = j == 0 || j == n_;
    if (fix_u && fix_v) return 0;
    Vec2& x = w_.at(i, j);
    const Vec2 x0 = x;
    const Local l0 = point<true>(i, j, x0);
    if (!std::isfinite(l0.e) || l0.e <= 0) return 0;
    Vec2 g = l0.g;
    Eigen::Matrix2d h = l0.h;
    if (fix_u) g.x() = 0, h(0, 1) = h(1, 0) = 0, h(0, 0) = 1;
    if (fix_v) g.y() = 0, h(0, 1) = h(1, 0) = 0, h(1, 1) = 1;
    if (!g.allFinite() || !h.allFinite() || g.squaredNorm() == 0) return 0;
    // Shift the Hessian to positive definite if needed (its smallest eigenvalue, closed form).
    const double a = h(0, 0), b = h(0, 1), c = h(1, 1);
    const double mid = 0.5 * (a + c), rad = std::sqrt(0.25 * (a - c) * (a - c) + b * b);
    const double scale = std::abs(a) + std::abs(c) + 1e-300;
    if (mid - rad <= 1e-9 * scale) h += (rad - mid + 1e-6 * scale) * Eigen::Matrix2d::Identity();
    Vec2 step = -o_.over_relaxation * h.ldlt().solve(g);
    if (fix_u) step.x() = 0;
    if (fix_v) step.y() = 0;
    const double cap = 0.5 * o_.over_relaxation / n_;  // at most half a lattice cell per step (× ω)
    if (!step.allFinite()) return 0;
    if (step.norm() > cap) step *= cap / step.norm();
    for (double t = 1; t > 1.0 / 64; t *= 0.5) {
      Vec2 y = x0 + t * step;
      y = y.cwiseMax(Vec2(0, 0)).cwiseMin(Vec2(1, 1));
      const double e = point<false>(i, j, y).e;
      if (e < l0.e) {
        x = y;
        return l0.e - e;
      }
    }
    return 0;
  }

  /// E over every cell (error part and floor part; cells with a non-positive triangle are skipped).
  void energy(double& error_part, double& total) const {
    // Rows in parallel, their sums added in row order: the same result on any number of threads.
    std::vector<double> row_error(n_, 0.0), row_total(n_, 0.0);
    tbb::parallel_for(0, n_, [&](int cj) {
      for (int ci = 0; ci < n_; ++ci) {
        // Corner 0 at its own position: every triangle's terms (not only those that contain corner 0).
        const Vec2 c[4] = {w_.at(ci, cj), w_.at(ci + 1, cj), w_.at(ci + 1, cj + 1), w_.at(ci, cj + 1)};
        const Vec2 ex[4] = {c[1] - c[0], c[1] - c[0], c[2] - c[3], c[2] - c[3]};
        const Vec2 ey[4] = {c[3] - c[0], c[2] - c[1], c[2] - c[1], c[3] - c[0]};
        const double q = f_.error.at(ci, cj), p = f_.exponent.at(ci, cj), lo = f_.floor.at(ci, cj);
        double dsum = 0, e = 0, shape = 0;
        bool ok = true;
        for (int t = 0; t < 4; ++t) {
          const double D = nn_ * cross2d(ex[t], ey[t]);
          if (!(D > 0)) ok = false;
          dsum += D;
          if (ok && q > 0) {
            Vec2 unused_g, unused_h;
            const double F = f_.txx.data.empty() ? frobenius(ex[t], ey[t])
                                                 : frobenius_t<false>(ex[t], ey[t], tensor(ci, cj), 0, 0, unused_g, unused_h);
            e += 0.25 * q * power(F / (2 * D * D), 0.5 * p);
          }
          if (ok && mu_ > 0) shape += 0.25 * mu_ * frobenius(ex[t], ey[t]) / (2 * D);
        }
        if (!ok) continue;
        row_error[cj] += e;
        row_total[cj] += e + shape;
        const double d = 0.25 * dsum;
        if (lo > 0 && kappa_ > 0 && d < lo) row_total[cj] += kappa_ * (lo / d - 1) * (lo / d - 1);
      }
    });
    error_part = total = 0;
    for (int cj = 0; cj < n_; ++cj) error_part += row_error[cj], total += row_total[cj];
  }

  /// The points that may move, by colour (i mod 2, j mod 2).
  std::vector<std::vector<int>> active_points() const {
    const int R = std::max(0, o_.reach_cells);
    // Cells within R of a painted cell: a separable dilation (rows, then columns).
    std::vector<char> row(static_cast<size_t>(n_) * n_, 0), near(row.size(), 0);
    for (int cj = 0; cj < n_; ++cj) {
      int last = -1 - R;  // last painted cell seen to the left
      for (int ci = 0; ci < n_; ++ci) {
        if (f_.error.at(ci, cj) > 0) last = ci;
        if (ci - last <= R) row[static_cast<size_t>(cj) * n_ + ci] = 1;
      }
      last = n_ + R;
      for (int ci = n_ - 1; ci >= 0; --ci) {
        if (f_.error.at(ci, cj) > 0) last = ci;
        if (last - ci <= R) row[static_cast<size_t>(cj) * n_ + ci] = 1;
      }
    }
    for (int ci = 0; ci < n_; ++ci) {
      int last = -1 - R;
      for (int cj = 0; cj < n_; ++cj) {
        if (row[static_cast<size_t>(cj) * n_ + ci]) last = cj;
        if (cj - last <= R) near[static_cast<size_t>(cj) * n_ + ci] = 1;
      }
      last = n_ + R;
      for (int cj = n_ - 1; cj >= 0; --cj) {
        if (row[static_cast<size_t>(cj) * n_ + ci]) last = cj;
        if (last - cj <= R) near[static_cast<size_t>(cj) * n_ + ci] = 1;
      }
    }
    std::vector<std::vector<int>> colours(4);
    for (int j = 0; j <= n_; ++j)
      for (int i = 0; i <= n_; ++i) {
        bool any = false;
        for (int b = j - 1; b <= j && !any; ++b)
          for (int a = i - 1; a <= i; ++a)
            if (a >= 0 && b >= 0 && a < n_ && b < n_ && near[static_cast<size_t>(b) * n_ + a]) any = true;
        if (any) colours[(i & 1) + 2 * (j & 1)].push_back(j * (n_ + 1) + i);
      }
    return colours;
  }

  ErrorPolishStats run() {
    ErrorPolishStats s;
    energy(s.error_before, s.energy_before);
    s.error_after = s.error_before, s.energy_after = s.energy_before;
    if (o_.sweeps <= 0 || !(s.error_before > 0)) return s;
    const std::vector<std::vector<int>> colours = active_points();
    const size_t points = static_cast<size_t>(n_ + 1) * (n_ + 1);
    std::vector<double> gain(points, 0.0);
    // A point is relaxed again only if it or one of its 8 neighbours moved by more than
    // kSettleCells in the previous sweep (the others already sit at their local minimum).
    std::vector<char> moved(points, 1), moved_now(points, 0);
    const double settle = kSettleCells / n_;
    auto wants = [&](int i, int j) {
      for (int b = std::max(0, j - 1); b <= std::min(n_, j + 1); ++b)
        for (int a = std::max(0, i - 1); a <= std::min(n_, i + 1); ++a)
          if (moved[static_cast<size_t>(b) * (n_ + 1) + a]) return true;
      return false;
    };
    double e = s.energy_before;
    for (int sweep = 0; sweep < o_.sweeps; ++sweep) {
      std::fill(gain.begin(), gain.end(), 0.0);
      std::fill(moved_now.begin(), moved_now.end(), char(0));
      for (const std::vector<int>& pts : colours) {
        auto body = [&](size_t a, size_t b) {
          for (size_t k = a; k < b; ++k) {
            const int i = pts[k] % (n_ + 1), j = pts[k] / (n_ + 1);
            if (!wants(i, j)) continue;
            const Vec2 before = w_.at(i, j);
            gain[pts[k]] = relax(i, j);
            moved_now[pts[k]] = (w_.at(i, j) - before).norm() > settle;
          }
        };
        if (o_.parallel)
          tbb::parallel_for(tbb::blocked_range<size_t>(0, pts.size(), 256),
                            [&](const tbb::blocked_range<size_t>& r) { body(r.begin(), r.end()); });
        else
          body(0, pts.size());
      }
      moved.swap(moved_now);
      double drop = 0;  // in a fixed order: the stop does not depend on the threads
      for (const std::vector<int>& pts : colours)
        for (int k : pts) drop += gain[k];
      ++s.sweeps;
      report_progress(o_.progress, "polish", double(s.sweeps) / o_.sweeps);
      e -= drop;
      if (drop <= o_.tolerance * e) break;
    }
    energy(s.error_after, s.energy_after);
    return s;
  }

 private:
  GridWarp& w_;
  const PolishFields& f_;
  const ErrorPolishOptions& o_;
  int n_;
  double nn_;
  // A lattice over a w x h rectangle: its Jacobian in uv is S·J·S⁻¹, S = diag(w, h), whose squared
  // Frobenius norm is n²(ex.x² + cx·ex.y² + cy·ey.x² + ey.y²) with cx = (h/w)², cy = (w/h)² (the
  // determinant is J's own).
  double cx_, cy_, aspect_;
  double kappa_ = 0, mu_ = 0;
};

}  // namespace

void check_polish_options(const ErrorPolishOptions& options) {
  if (!(options.over_relaxation > 0 && options.over_relaxation < 2))
    throw InvalidInputError("polish options: over_relaxation must be in (0, 2)");
  if (options.prepass_levels < 1 || options.prepass_levels > 4)
    throw InvalidInputError("polish options: prepass_levels must be in [1, 4]");
  if (options.sweeps < 0 || options.prepass_sweeps < 0 || options.sweeps_after_prepass < 0 ||
      !(options.tolerance >= 0) || !(options.floor_weight >= 0) ||
      !(options.shape_weight >= 0) || options.reach_cells < 0 || options.cells < 0 ||
      !(options.isotropy > 0 && options.isotropy <= 1))
    throw InvalidInputError(
        "polish options: sweeps (all four), tolerance, floor_weight, shape_weight, reach_cells and cells must be >= 0, "
        "isotropy in (0, 1]");
}

ErrorPolishStats polish_warp_by_error(GridWarp& warp, const PolishFields& fields, const ErrorPolishOptions& options) {
  const int n = warp.n;
  if (n < 1 || warp.points.size() != static_cast<size_t>(n + 1) * (n + 1))
    throw InvalidInputError("polish_warp_by_error: the warp needs n >= 1 and (n+1)^2 points");
  for (const ImageF* img : {&fields.error, &fields.exponent, &fields.floor})
    if (img->width != n || img->height != n)
      throw InvalidInputError("polish_warp_by_error: the error fields must be n x n, n = " + std::to_string(n));
  for (size_t k = 0; k < fields.error.data.size(); ++k) {
    const float q = fields.error.data[k], p = fields.exponent.data[k], lo = fields.floor.data[k];
    if (!(q >= 0 && std::isfinite(q)) || !(lo >= 0 && std::isfinite(lo)) || !(p >= 0 && p <= 8))
      throw InvalidInputError("polish_warp_by_error: error and floor must be finite and >= 0, exponent in [0, 8]");
  }
  const bool directed = !fields.txx.data.empty() || !fields.txy.data.empty() || !fields.tyy.data.empty();
  for (const ImageF* img : {&fields.txx, &fields.txy, &fields.tyy})
    if (directed && (img->width != n || img->height != n))
      throw InvalidInputError("polish_warp_by_error: the direction tensor must be n x n or empty, n = " + std::to_string(n));
  for (size_t k = 0; directed && k < fields.txx.data.size(); ++k) {
    const float a = fields.txx.data[k], b = fields.txy.data[k], c = fields.tyy.data[k];
    if (!(std::isfinite(a) && std::isfinite(b) && std::isfinite(c) && a > 0 && c > 0 && a * c > b * b))
      throw InvalidInputError("polish_warp_by_error: the direction tensor must be finite and positive definite");
  }
  if (!(fields.aspect > 0) || !std::isfinite(fields.aspect))
    throw InvalidInputError("polish_warp_by_error: the aspect must be finite and > 0");
  check_polish_options(options);
  return Polisher(warp, fields, options).run();
}

double polish_model_error(const GridWarp& warp, const PolishFields& fields, const ErrorPolishOptions& options) {
  GridWarp copy = warp;
  ErrorPolishOptions o = options;
  o.sweeps = 0;
  o.progress = nullptr;
  return polish_warp_by_error(copy, fields, o).error_before;
}

int polish_cells(int warp_cells, const ErrorPolishOptions& options, double extent) {
  if (warp_cells < 1) throw InvalidInputError("polish_cells: the warp needs >= 1 cells");
  if (options.cells < 0) throw InvalidInputError("polish_cells: options.cells must be >= 0");
  if (!(extent > 0 && extent <= 1)) throw InvalidInputError("polish_cells: extent must be in (0, 1]");
  if (options.cells == 0) return warp_cells;
  return std::min(warp_cells, std::max(4, static_cast<int>(std::lround(options.cells * extent))));
}

}  // namespace adaptex
