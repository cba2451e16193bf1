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

namespace adaptex {

PolishFields polish_fields(const ImageF& error, const ImageF& exponent, const ImageF& density, const Vec2& lo,
                           const Vec2& hi, int n, double scale) {
  const int L = error.width;
  if (L < 1 || error.height != L || exponent.width != L || exponent.height != L || density.width != L ||
      density.height != L)
    throw InvalidInputError("polish_fields: error, exponent and density must be L x L, L >= 1");
  if (n < 1) throw InvalidInputError("polish_fields: n must be >= 1");
  if (!(scale > 0) || !std::isfinite(scale)) throw InvalidInputError("polish_fields: scale must be finite and > 0");
  if (!(lo.x() < hi.x() && lo.y() < hi.y() && lo.minCoeff() >= 0 && hi.maxCoeff() <= 1))
    throw InvalidInputError("polish_fields: the rectangle must be non-empty and inside the unit square");
  PolishFields f;
  f.error = ImageF(n, n, 0.0f);
  f.exponent = ImageF(n, n, 0.0f);
  f.floor = ImageF(n, n, 0.0f);
  std::vector<BilinearTap> tu(n), tv(n);
  for (int i = 0; i < n; ++i) {
    tu[i] = bilinear_tap(L, lo.x() + (i + 0.5) / n * (hi.x() - lo.x()));
    tv[i] = bilinear_tap(L, lo.y() + (i + 0.5) / n * (hi.y() - lo.y()));
  }
  std::vector<double> row_density(n, 0.0);  // summed in row order below: thread-independent
  tbb::parallel_for(0, n, [&](int j) {
    for (int i = 0; i < n; ++i) {
      const int xs[2] = {tu[i].i0, tu[i].i1}, ys[2] = {tv[j].i0, tv[j].i1};
      const double wx[2] = {1 - tu[i].f, tu[i].f}, wy[2] = {1 - tv[j].f, tv[j].f};
      double q = 0, qp = 0, rho = 0;
      for (int b = 0; b < 2; ++b)
        for (int a = 0; a < 2; ++a) {
          const double w = wx[a] * wy[b], e = error.at(xs[a], ys[b]);
          q += w * e, qp += w * e * exponent.at(xs[a], ys[b]), rho += w * density.at(xs[a], ys[b]);
        }
      const double p = q > 0 ? qp / q : 0.0;
      f.error.at(i, j) = static_cast<float>(scale == 1 ? q : q * std::pow(scale, -p));
      f.exponent.at(i, j) = static_cast<float>(p);
      f.floor.at(i, j) = static_cast<float>(rho);
      row_density[j] += rho;
    }
  });
  double density_sum = 0;
  for (double r : row_density) density_sum += r;
  f.aspect = (hi.x() - lo.x()) / (hi.y() - lo.y());
  const double mean = density_sum / (double(n) * n);
  for (size_t k = 0; k < f.floor.data.size(); ++k)
    f.floor.data[k] = f.error.data[k] > 0 || !(mean > 0) ? 0.0f : static_cast<float>(f.floor.data[k] / mean);
  return f;
}

EdgeTensor edge_tensor(const ImageRGBA8& texture) {
  const int W = texture.width, H = texture.height;
  if (texture.empty()) throw InvalidInputError("edge_tensor: the texture is empty");
  EdgeTensor t{ImageF(W, H), ImageF(W, H), ImageF(W, H)};
  tbb::parallel_for(0, H, [&](int j) {
    const int j0 = std::max(0, j - 1), j1 = std::min(H - 1, j + 1);
    for (int i = 0; i < W; ++i) {
      const int i0 = std::max(0, i - 1), i1 = std::min(W - 1, i + 1);
      double xx = 0, xy = 0, yy = 0;
      for (int ch = 0; ch < 3; ++ch) {
        const double gx = (double(texture.texel(i1, j)[ch]) - texture.texel(i0, j)[ch]) / std::max(1, i1 - i0);
        const double gy = (double(texture.texel(i, j1)[ch]) - texture.texel(i, j0)[ch]) / std::max(1, j1 - j0);
        xx += gx * gx, xy += gx * gy, yy += gy * gy;
      }
      t.xx.at(i, j) = static_cast<float>(xx), t.xy.at(i, j) = static_cast<float>(xy), t.yy.at(i, j) = static_cast<float>(yy);
    }
  });
  // Summed-area tables (double: sums of up to W·H squared gradients): prefix sums along the rows,
  // rows in parallel, then down the columns, column blocks in parallel. The terms are multiples of
  // 1/4 below 2^20 (8-bit channels, central differences), so every partial sum is exact and the
  // table does not depend on the order of the additions.
  auto table = [&](const ImageF& img, std::vector<double>& s) {
    const size_t stride = static_cast<size_t>(W) + 1;
    s.assign(stride * (H + 1), 0.0);
    tbb::parallel_for(0, H, [&](int j) {
      double* row = &s[(static_cast<size_t>(j) + 1) * stride];
      for (int i = 0; i < W; ++i) row[i + 1] = row[i] + img.at(i, j);
    });
    tbb::parallel_for(tbb::blocked_range<size_t>(1, stride, 256), [&](const tbb::blocked_range<size_t>& cols) {
      for (int j = 1; j < H; ++j) {
        const double* above = &s[static_cast<size_t>(j) * stride];
        double* row = &s[(static_cast<size_t>(j) + 1) * stride];
        for (size_t i = cols.begin(); i < cols.end(); ++i) row[i] += above[i];
      }
    });
  };
  tbb::parallel_invoke([&] { table(t.xx, t.sum_xx); }, [&] { table(t.xy, t.sum_xy); }, [&] { table(t.yy, t.sum_yy); });
  return t;
}

void add_edge_directions(PolishFields& fields, const EdgeTensor& edges, const Vec2& lo, const Vec2& hi,
                         double isotropy) {
  const int n = fields.error.width, W = edges.xx.width, H = edges.xx.height;
  if (n < 1 || fields.error.height != n) throw InvalidInputError("add_edge_directions: the fields must be n x n, n >= 1");
  if (W < 1 || H < 1 || edges.xy.width != W || edges.yy.width != W || edges.xy.height != H || edges.yy.height != H)
    throw InvalidInputError("add_edge_directions: the edge tensor's rasters must have one non-empty size");
  if (!(isotropy > 0 && isotropy <= 1)) throw InvalidInputError("add_edge_directions: isotropy must be in (0, 1]");
  if (!(lo.x() < hi.x() && lo.y() < hi.y() && lo.minCoeff() >= 0 && hi.maxCoeff() <= 1))
    throw InvalidInputError("add_edge_directions: the rectangle must be non-empty and inside the unit square");
  const size_t table = static_cast<size_t>(W + 1) * (H + 1);
  if (edges.sum_xx.size() != table || edges.sum_xy.size() != table || edges.sum_yy.size() != table)
    throw InvalidInputError("add_edge_directions: the edge tensor has no summed-area tables of its size (edge_tensor())");
  const std::vector<double>&sxx = edges.sum_xx, &sxy = edges.sum_xy, &syy = edges.sum_yy;
  // Texel index range [a, b) of the cells c - 1 .. c + 1 along one axis (at least one texel).
  auto range = [&](int c, double l, double h, int size) {
    const double u0 = l + (c - 1.0) / n * (h - l), u1 = l + (c + 2.0) / n * (h - l);
    int a = std::clamp(static_cast<int>(std::floor(u0 * size)), 0, size - 1);
    int b = std::clamp(static_cast<int>(std::ceil(u1 * size)), a + 1, size);
    return std::pair<int, int>(a, b);
  };
  fields.txx = ImageF(n, n), fields.txy = ImageF(n, n), fields.tyy = ImageF(n, n);
  for (int j = 0; j < n; ++j) {
    const std::pair<int, int> ys = range(j, lo.y(), hi.y(), H);
    const int y0 = ys.first, y1 = ys.second;  // (clang 14 cannot capture structured bindings)
    for (int i = 0; i < n; ++i) {
      const std::pair<int, int> xs = range(i, lo.x(), hi.x(), W);
      const int x0 = xs.first, x1 = xs.second;
      auto box = [&](const std::vector<double>& s) {
        auto at = [&](int x, int y) { return s[static_cast<size_t>(y) * (W + 1) + x]; };
        return at(x1, y1) - at(x0, y1) - at(x1, y0) + at(x0, y0);
      };
      const double xx = box(sxx), xy = box(sxy), yy = box(syy), tr = xx + yy;
      const double w = tr > 0 ? (1 - isotropy) / tr : 0.0, iso = tr > 0 ? 0.5 * isotropy : 0.5;
      fields.txx.at(i, j) = static_cast<float>(w * xx + iso);
      fields.txy.at(i, j) = static_cast<float>(w * xy);
      fields.tyy.at(i, j) = static_cast<float>(w * yy + iso);
    }
  }
}

namespace {

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

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
      const double D = nn_ * cross(ex[t], ey[t]);
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
          const double D = nn_ * cross(ex[t], ey[t]);
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
    // options.settle_cells in the previous sweep (the others already sit at their local minimum).
    std::vector<char> moved(points, 1), moved_now(points, 0);
    const double settle = o_.settle_cells / n_;
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
  if (options.sweeps < 0 || options.prepass_sweeps < 0 || options.sweeps_after_prepass < 0 || options.warm_sweeps < 0 ||
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

namespace {

/// The m-cell lattice at \p warp's positions (GridWarp::apply_lattice); sides and corners exactly on
/// the square's.
GridWarp sample_lattice(const GridWarp& warp, int m) {
  GridWarp coarse = GridWarp::uniform(m);
  for (int J = 0; J <= m; ++J)
    for (int I = 0; I <= m; ++I) {
      Vec2 x = warp.apply_lattice(Vec2(double(I) / m, double(J) / m));
      if (I == 0 || I == m) x.x() = double(I) / m;
      if (J == 0 || J == m) x.y() = double(J) / m;
      coarse.at(I, J) = x;
    }
  return coarse;
}

/// The motion of every point of \p warp under B_after ∘ B_before⁻¹: the bilinear map of the coarse
/// lattice \p after composed with the inverse of \p before's (Newton, in the coarse cell the point's
/// index lies in, from the index's own fractions; those fractions when it does not converge). Moving
/// points by their position rather than by their index keeps the warp's own fine structure: where its
/// cells are compressed, so is their motion (a displacement interpolated by index folded many cells).
std::vector<Vec2> composed_motion(const GridWarp& warp, const GridWarp& before, const GridWarp& after) {
  const int n = warp.n, m = before.n;
  std::vector<Vec2> motion(warp.points.size());
  tbb::parallel_for(0, n + 1, [&](int j) {
    const double y = double(j) * m / n;
    const int J = std::min(static_cast<int>(y), m - 1);
    for (int i = 0; i <= n; ++i) {
      const double x = double(i) * m / n;
      const int I = std::min(static_cast<int>(x), m - 1);
      const Vec2 p00 = before.at(I, J), p10 = before.at(I + 1, J), p11 = before.at(I + 1, J + 1), p01 = before.at(I, J + 1);
      const Vec2 q = warp.at(i, j);
      double a = x - I, b = y - J;
      for (int it = 0; it < 8; ++it) {
        const Vec2 r = (1 - a) * (1 - b) * p00 + a * (1 - b) * p10 + a * b * p11 + (1 - a) * b * p01 - q;
        const Vec2 da = (1 - b) * (p10 - p00) + b * (p11 - p01), db = (1 - a) * (p01 - p00) + a * (p11 - p10);
        const double det = cross(da, db);
        if (!(std::abs(det) > 1e-300)) break;
        const double sa = cross(r, db) / det, sb = cross(da, r) / det;
        a -= sa, b -= sb;
        if (std::abs(sa) + std::abs(sb) < 1e-12) break;
      }
      if (!(std::isfinite(a) && std::isfinite(b) && a > -0.5 && a < 1.5 && b > -0.5 && b < 1.5)) a = x - I, b = y - J;
      motion[static_cast<size_t>(j) * (n + 1) + i] =
          (1 - a) * (1 - b) * after.at(I, J) + a * (1 - b) * after.at(I + 1, J) + a * b * after.at(I + 1, J + 1) +
          (1 - a) * b * after.at(I, J + 1) - q;
    }
  });
  return motion;
}

/// \p warp's points at start + t·motion, inside the square, side points on their side (corners stay).
void place_moved(GridWarp& warp, const std::vector<Vec2>& start, const std::vector<Vec2>& motion, double t) {
  const int n = warp.n;
  tbb::parallel_for(0, n + 1, [&](int j) {
    for (int i = 0; i <= n; ++i) {
      const size_t k = static_cast<size_t>(j) * (n + 1) + i;
      Vec2 p = (start[k] + t * motion[k]).cwiseMax(Vec2(0, 0)).cwiseMin(Vec2(1, 1));
      if (i == 0 || i == n) p.x() = start[k].x();
      if (j == 0 || j == n) p.y() = start[k].y();
      warp.points[k] = p;
    }
  });
}

}  // namespace

ErrorPolishStats polish_warp(GridWarp& warp, const PolishFields& fields, const ErrorPolishOptions& options) {
  const int n = warp.n;
  if (n < 1 || warp.points.size() != static_cast<size_t>(n + 1) * (n + 1))
    throw InvalidInputError("polish_warp: the warp needs n >= 1 and (n+1)^2 points");
  check_polish_options(options);
  const int m = fields.error.width;
  if (m < 1 || m > n || fields.error.height != m)
    throw InvalidInputError("polish_warp: the error fields must be m x m, 1 <= m <= n = " + std::to_string(n));
  if (m == n) return polish_warp_by_error(warp, fields, options);
  GridWarp coarse = sample_lattice(warp, m);
  const GridWarp before = coarse;
  ErrorPolishOptions co = options;  // the reach stays the same distance in uv
  if (co.reach_cells > 0) co.reach_cells = std::max(1, static_cast<int>(std::lround(options.reach_cells * double(m) / n)));
  ErrorPolishStats st = polish_warp_by_error(coarse, fields, co);
  if (st.sweeps == 0) return st;
  const std::vector<Vec2> start = warp.points, motion = composed_motion(warp, before, coarse);
  const std::vector<char> convex = convex_cells(warp);
  auto place = [&](double t) { place_moved(warp, start, motion, t); };
  // Where the motion still turns a cell of the warp (in strongly compressed spots, where the warp's
  // cells are much smaller than the coarse lattice's: 12–80 cells of 65k in the cases looked at), the
  // cell is untangled; if cells stay turned, the whole motion is halved.
  double t = 1;
  place(t);
  for (int halving = 0; untangle_turned_cells(warp, convex, halving == 0 ? &st.turned_cells : nullptr) > 0; ++halving) {
    if (halving == 6) {
      warp.points = start;
      t = 0;
      break;
    }
    t *= 0.5;
    place(t);
  }
  st.transfer_scale = t;
  return st;
}

/// Most turned cells add_polish_correction() untangles before it halves the correction instead.
constexpr size_t kWarmUntangleCells = 32;

double add_polish_correction(GridWarp& warp, const GridWarp& prev_flow, const GridWarp& prev_polished) {
  const int n = warp.n, m = prev_flow.n;
  const size_t count = static_cast<size_t>(n + 1) * (n + 1), prev = static_cast<size_t>(m + 1) * (m + 1);
  if (n < 1 || m < 1 || prev_polished.n != m || warp.points.size() != count || prev_flow.points.size() != prev ||
      prev_polished.points.size() != prev)
    return 0;
  // The correction at every point's own lattice coordinates (i/n, j/n): the previous lattices'
  // bilinear maps there, so lattices of another size get it resampled (the pointwise difference when
  // the sizes are equal).
  std::vector<Vec2> correction(count);
  tbb::parallel_for(0, n + 1, [&](int j) {
    for (int i = 0; i <= n; ++i) {
      const Vec2 u(double(i) / n, double(j) / n);
      correction[static_cast<size_t>(j) * (n + 1) + i] =
          m == n ? Vec2(prev_polished.at(i, j) - prev_flow.at(i, j))
                 : Vec2(prev_polished.apply_lattice(u) - prev_flow.apply_lattice(u));
    }
  });
  const std::vector<Vec2> start = warp.points;
  const std::vector<char> convex = convex_cells(warp);
  for (double t = 1; t >= 0.125; t *= 0.5) {
    place_moved(warp, start, correction, t);
    // A few turned cells are untangled; many mean the correction does not fit this flow (untangling
    // them took seconds on a 100-cell lattice): halve it.
    const std::vector<char> now = convex_cells(warp);
    size_t turned = 0;
    for (size_t c = 0; c < now.size(); ++c) turned += convex[c] && !now[c];
    if (turned == 0 || (turned <= kWarmUntangleCells && untangle_turned_cells(warp, convex) == 0)) return t;
  }
  warp.points = start;
  return 0;
}

}  // namespace adaptex
