// Flow-based density-equalizing map (Gastner, Seguy & More, PNAS 2018): one DCT Poisson solve, then
// every lattice point is advected through v = J / ρ_t with an adaptive Bogacki–Shampine RK3(2).
#include "adaptex/adapt/density_flow.h"

#include <fftw3.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <string>

#include "adaptex/core/errors.h"

namespace adaptex {

namespace {

constexpr double kPi = 3.14159265358979323846;

// FFTW's planner is not thread-safe; execution of distinct plans is.
std::mutex& fftw_planner_mutex() {
  static std::mutex m;
  return m;
}

/// φ on the L x L cell centres with ∇²_h φ = ρ̄ − ρ (5-point Laplacian, reflective sides), by DCT.
std::vector<double> solve_poisson_neumann(const ImageF& rho) {
  const int L = rho.width;
  std::vector<double> a(static_cast<size_t>(L) * L);
  for (size_t k = 0; k < a.size(); ++k) a[k] = rho.data[k];
  fftw_plan fwd, inv;
  {
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    fwd = fftw_plan_r2r_2d(L, L, a.data(), a.data(), FFTW_REDFT10, FFTW_REDFT10, FFTW_ESTIMATE);
    inv = fftw_plan_r2r_2d(L, L, a.data(), a.data(), FFTW_REDFT01, FFTW_REDFT01, FFTW_ESTIMATE);
  }
  fftw_execute(fwd);
  std::vector<double> lambda(L);
  for (int k = 0; k < L; ++k) {
    const double s = std::sin(kPi * k / (2.0 * L));
    lambda[k] = -4.0 * L * L * s * s;  // eigenvalue of the 1-D reflective 3-point Laplacian
  }
  const double norm = 4.0 * L * L;  // REDFT01(REDFT10(x)) = (2L)² x in 2-D
  for (int l = 0; l < L; ++l)
    for (int k = 0; k < L; ++k) {
      double& c = a[static_cast<size_t>(l) * L + k];
      c = (k == 0 && l == 0) ? 0.0 : -c / ((lambda[k] + lambda[l]) * norm);
    }
  fftw_execute(inv);
  {
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    fftw_destroy_plan(fwd);
    fftw_destroy_plan(inv);
  }
  return a;
}

}  // namespace

/// Flux J = −∇φ and ρ₀ on the (L+1)² corner lattice; v(x, t) = J / ((1−t)ρ₀ + tρ̄), bilinear.
struct DensityFlow::Field {
  /// One lattice corner: a velocity evaluation reads 4 corners in 2 adjacent pairs, so the three
  /// values are interleaved (two cache lines per evaluation instead of up to six).
  struct Corner {
    double jx = 0, jy = 0, rho = 0;
  };
  int L = 0;
  double mean = 1;
  std::vector<Corner> c;  // (L+1)², row-major (j * (L+1) + i)

  Field(const ImageF& density, const std::vector<double>& phi) : L(density.width) {
    const int S = L + 1;
    c.assign(static_cast<size_t>(S) * S, Corner{});
    double sum = 0;
    for (float v : density.data) sum += v;
    mean = sum / density.data.size();
    auto p = [&](int i, int j) { return phi[static_cast<size_t>(j) * L + i]; };
    for (int j = 0; j <= L; ++j)
      for (int i = 0; i <= L; ++i) {
        const int j0 = std::max(j - 1, 0), j1 = std::min(j, L - 1);
        const int i0 = std::max(i - 1, 0), i1 = std::min(i, L - 1);
        Corner& k = c[static_cast<size_t>(j) * S + i];
        // Face fluxes between cells (i-1, ·) and (i, ·), averaged over the rows meeting at the corner.
        if (i > 0 && i < L) k.jx = -0.5 * L * ((p(i, j0) - p(i - 1, j0)) + (p(i, j1) - p(i - 1, j1)));
        if (j > 0 && j < L) k.jy = -0.5 * L * ((p(i0, j) - p(i0, j - 1)) + (p(i1, j) - p(i1, j - 1)));
        k.rho = 0.25 * (density.at(i0, j0) + density.at(i1, j0) + density.at(i0, j1) + density.at(i1, j1));
      }
  }

  Vec2 velocity(const Vec2& x, double t) const {
    const double gx = std::clamp(x.x(), 0.0, 1.0) * L, gy = std::clamp(x.y(), 0.0, 1.0) * L;
    const int i = std::min(static_cast<int>(gx), L - 1), j = std::min(static_cast<int>(gy), L - 1);
    const double s = gx - i, u = gy - j;
    const size_t S = static_cast<size_t>(L) + 1, c00 = j * S + i;
    const Corner &a = c[c00], &b = c[c00 + 1], &d = c[c00 + S], &e = c[c00 + S + 1];
    const double w00 = (1 - s) * (1 - u), w10 = s * (1 - u), w01 = (1 - s) * u, w11 = s * u;
    const double fx = w00 * a.jx + w10 * b.jx + w01 * d.jx + w11 * e.jx;
    const double fy = w00 * a.jy + w10 * b.jy + w01 * d.jy + w11 * e.jy;
    const double r0 = w00 * a.rho + w10 * b.rho + w01 * d.rho + w11 * e.rho;
    const double inv = 1.0 / ((1 - t) * r0 + t * mean);
    return Vec2(fx * inv, fy * inv);
  }
};

namespace {

Vec2 clamp01(const Vec2& p) { return Vec2(std::clamp(p.x(), 0.0, 1.0), std::clamp(p.y(), 0.0, 1.0)); }

void check_density(const ImageF& density) {
  if (density.width != density.height || density.width < 2)
    throw InvalidInputError("density_equalizing_warp: the density must be a square raster of >= 2 cells, got " +
                            std::to_string(density.width) + "x" + std::to_string(density.height));
  for (float v : density.data)
    if (!(std::isfinite(v) && v > 0))
      throw InvalidInputError("density_equalizing_warp: densities must be finite and > 0");
}

/// ∛r to 1e-6 relative for r in [0.01, 100] (a step-size factor; libm's cbrt was 5 % of the
/// end-mode re-parameterization): an exponent-bit first guess, then two Newton steps.
inline double cbrt_approx(double r) {
  std::uint64_t bits;
  std::memcpy(&bits, &r, sizeof bits);
  bits = bits / 3 + 0x2A9F7893782DA1CEull;  // thirds the biased exponent
  double y;
  std::memcpy(&y, &bits, sizeof y);
  y -= (y * y * y - r) / (3 * y * y);
  y -= (y * y * y - r) / (3 * y * y);
  return y;
}

/// Advects one point from t = 0 to 1 (Bogacki–Shampine 3(2), FSAL, per-point step control).
/// \return the number of accepted steps
template <class Field>
int advect_point(const Field& f, Vec2& x, double tol, double max_move, int max_steps) {
  double t = 0, h = 0.02;
  Vec2 k1 = f.velocity(x, 0);
  int steps = 0;
  for (int guard = 0; t < 1.0 && guard < 4 * max_steps; ++guard) {
    const double speed = k1.norm();
    if (speed * h > max_move) h = max_move / speed;  // never jump over density features
    h = std::min(h, 1.0 - t);
    const Vec2 k2 = f.velocity(clamp01(x + 0.5 * h * k1), t + 0.5 * h);
    const Vec2 k3 = f.velocity(clamp01(x + 0.75 * h * k2), t + 0.75 * h);
    const Vec2 y = clamp01(x + h * (2.0 / 9 * k1 + 1.0 / 3 * k2 + 4.0 / 9 * k3));
    const Vec2 k4 = f.velocity(y, t + h);
    const Vec2 z = x + h * (7.0 / 24 * k1 + 0.25 * k2 + 1.0 / 3 * k3 + 0.125 * k4);
    const double err = (y - z).norm();
    if (err <= tol || steps >= max_steps) {
      x = y;
      t += h;
      k1 = k4;
      ++steps;
    }
    // 0.9·cbrt(tol/err) clamped to [0.2, 4]: cbrt only where the clamp does not decide (most steps
    // are limited by max_move and have err far below tol).
    const double ratio = err > 0 ? tol / err : 1e300;
    const double factor = ratio >= 87.8 ? 4.0 : ratio <= 0.011 ? 0.2 : 0.9 * cbrt_approx(ratio);
    h *= std::clamp(factor, 0.2, 4.0);
    h = std::max(h, 1e-9);
  }
  return steps;
}

double cell_signed_area(const GridWarp& g, int i, int j) {
  const Vec2 a = g.at(i, j), b = g.at(i + 1, j), c = g.at(i + 1, j + 1), d = g.at(i, j + 1);
  const auto cross = [](const Vec2& p, const Vec2& q) { return p.x() * q.y() - p.y() * q.x(); };
  return 0.5 * (cross(a, b) + cross(b, c) + cross(c, d) + cross(d, a));
}

/// What advect_lattice() did.
struct LatticeAdvection {
  long total_steps = 0;
  int most_steps = 0;
  long advected = 0;
};

/// Advects the lattice points g.points[idx[k]] (uniform positions on entry) through \p flow, in
/// parallel when o.parallel; adds the step counts to \p out.
void advect_points(const DensityFlow& flow, const DensityFlowOptions& o, GridWarp& g, const std::vector<size_t>& idx,
                   LatticeAdvection& out) {
  const double tol = o.tolerance / o.cells, max_move = o.max_step_cells / o.cells;
  std::atomic<long> total{0};
  std::atomic<int> most{0};
  auto run = [&](size_t k0, size_t k1) {
    long local = 0;
    int local_most = 0;
    for (size_t k = k0; k < k1; ++k) {
      int s = 0;
      Vec2& p = g.points[idx[k]];
      p = flow.advect(p, tol, max_move, o.max_steps, &s);
      local += s;
      local_most = std::max(local_most, s);
    }
    total += local;
    int cur = most.load();
    while (local_most > cur && !most.compare_exchange_weak(cur, local_most)) {
    }
  };
  if (o.parallel)
    tbb::parallel_for(tbb::blocked_range<size_t>(0, idx.size(), 256),
                      [&](const tbb::blocked_range<size_t>& r) { run(r.begin(), r.end()); });
  else
    run(0, idx.size());
  out.total_steps += total;
  out.most_steps = std::max(out.most_steps, most.load());
  out.advected += static_cast<long>(idx.size());
}

/// Cubic interpolation at the midpoint of coarse interval [I, I + 1] of a lattice with m cells (m >= 3):
/// the first of the four coarse points used and their weights (centred inside, one-sided at the sides).
struct MidpointStencil {
  int first;
  double w[4];
};
MidpointStencil midpoint_stencil(int I, int m) {
  if (I == 0) return {0, {5.0 / 16, 15.0 / 16, -5.0 / 16, 1.0 / 16}};
  if (I + 1 == m) return {m - 3, {1.0 / 16, -5.0 / 16, 15.0 / 16, 5.0 / 16}};
  return {I - 1, {-1.0 / 16, 9.0 / 16, 9.0 / 16, -1.0 / 16}};
}

/// Per cell of the coarse lattice \p c (m cells per side, m >= 4): true where cubic interpolation of
/// its points is within \p tol (uv units). The estimate is 5/64 of the largest fourth difference
/// |Δ⁴X| along either axis at the coarse points around the cell (the stencil shifted inward at the
/// sides): the midpoint error of a cubic through four equispaced points is 3/128 |Δ⁴X| inside and
/// 5/128 one-sided, doubled as a margin for a map that is not a polynomial.
std::vector<char> smooth_coarse_cells(const GridWarp& c, double tol) {
  const int m = c.n;
  std::vector<double> d4(static_cast<size_t>(m + 1) * (m + 1));
  for (int J = 0; J <= m; ++J)
    for (int I = 0; I <= m; ++I) {
      const int ci = std::clamp(I, 2, m - 2), cj = std::clamp(J, 2, m - 2);
      const double dx = (c.at(ci - 2, J) - 4.0 * c.at(ci - 1, J) + 6.0 * c.at(ci, J) - 4.0 * c.at(ci + 1, J) + c.at(ci + 2, J)).norm();
      const double dy = (c.at(I, cj - 2) - 4.0 * c.at(I, cj - 1) + 6.0 * c.at(I, cj) - 4.0 * c.at(I, cj + 1) + c.at(I, cj + 2)).norm();
      d4[static_cast<size_t>(J) * (m + 1) + I] = std::max(dx, dy);
    }
  std::vector<char> smooth(static_cast<size_t>(m) * m);
  for (int J = 0; J < m; ++J)
    for (int I = 0; I < m; ++I) {
      double e = 0;
      for (int b = std::max(J - 1, 0); b <= std::min(J + 2, m); ++b)
        for (int a = std::max(I - 1, 0); a <= std::min(I + 2, m); ++a) e = std::max(e, d4[static_cast<size_t>(b) * (m + 1) + a]);
      smooth[static_cast<size_t>(J) * m + I] = e * 5.0 / 64 <= tol;
    }
  return smooth;
}

/// The point (i, j) of the fine lattice (2m cells) interpolated from the coarse lattice \p c by
/// cubics: along the coarse row or column for an edge midpoint, their tensor product for a centre.
Vec2 cubic_from_coarse(const GridWarp& c, int i, int j) {
  const int m = c.n;
  if (j % 2 == 0) {  // on coarse row j/2
    const MidpointStencil sx = midpoint_stencil(i / 2, m);
    Vec2 p(0, 0);
    for (int a = 0; a < 4; ++a) p += sx.w[a] * c.at(sx.first + a, j / 2);
    return p;
  }
  const MidpointStencil sy = midpoint_stencil(j / 2, m);
  if (i % 2 == 0) {  // on coarse column i/2
    Vec2 p(0, 0);
    for (int b = 0; b < 4; ++b) p += sy.w[b] * c.at(i / 2, sy.first + b);
    return p;
  }
  const MidpointStencil sx = midpoint_stencil(i / 2, m);
  Vec2 p(0, 0);
  for (int b = 0; b < 4; ++b)
    for (int a = 0; a < 4; ++a) p += sx.w[a] * sy.w[b] * c.at(sx.first + a, sy.first + b);
  return p;
}

/// Advects the (uniform) lattice \p g through \p flow: every point, or coarse-to-fine
/// (DensityFlowOptions::interpolation_tolerance, \p tol in uv units): the lattice of the even points
/// first (recursively, down to 8 cells), then the other points of each coarse cell are interpolated
/// (cubic_from_coarse) where smooth_coarse_cells() allows it and advected elsewhere.
LatticeAdvection advect_lattice(const DensityFlow& flow, const DensityFlowOptions& o, GridWarp& g, double tol) {
  LatticeAdvection out;
  const int n = g.n, S = n + 1;
  std::vector<size_t> idx;
  if (!(tol > 0) || n % 2 != 0 || n < 16) {
    idx.resize(g.points.size());
    for (size_t k = 0; k < idx.size(); ++k) idx[k] = k;
    advect_points(flow, o, g, idx, out);
    return out;
  }
  const int m = n / 2;
  GridWarp coarse = GridWarp::uniform(m);
  out = advect_lattice(flow, o, coarse, tol);
  const std::vector<char> smooth = smooth_coarse_cells(coarse, tol);
  auto cell_smooth = [&](int I, int J) { return I < 0 || J < 0 || I >= m || J >= m || smooth[static_cast<size_t>(J) * m + I]; };
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      if (i % 2 == 0 && j % 2 == 0) {
        g.at(i, j) = coarse.at(i / 2, j / 2);
        continue;
      }
      // The coarse cells that contain (i, j): one for a cell centre, two for an edge midpoint.
      const bool ok = cell_smooth(i / 2, j / 2) && (j % 2 == 1 || cell_smooth(i / 2, j / 2 - 1)) &&
                      (i % 2 == 1 || cell_smooth(i / 2 - 1, j / 2));
      if (ok) g.at(i, j) = clamp01(cubic_from_coarse(coarse, i, j));
      else idx.push_back(static_cast<size_t>(j) * S + i);
    }
  advect_points(flow, o, g, idx, out);
  return out;
}

}  // namespace

DensityFlow::DensityFlow(const ImageF& density) {
  check_density(density);
  field_ = std::make_shared<const Field>(density, solve_poisson_neumann(density));
}

int DensityFlow::cells() const { return field_->L; }

Vec2 DensityFlow::advect(const Vec2& x, double tolerance, double max_move, int max_steps, int* steps) const {
  Vec2 p = clamp01(x);
  const int s = advect_point(*field_, p, tolerance, max_move, max_steps);
  if (steps) *steps = s;
  return p;
}

Vec2 DensityFlow::advect(const Vec2& x, const DensityFlowOptions& o, int* steps) const {
  const double cell = 1.0 / field_->L;
  return advect(x, o.direct_tolerance * cell, o.direct_max_step_cells * cell, o.max_steps, steps);
}

Vec2 FlowWarp::apply(const Vec2& uv, int* steps) const {
  constexpr double eps = 1e-12;
  if (steps) *steps = 0;
  for (const Part& part : parts) {
    if (uv.x() < part.lo.x() - eps || uv.x() > part.hi.x() + eps || uv.y() < part.lo.y() - eps ||
        uv.y() > part.hi.y() + eps)
      continue;
    if (!part.flow) return uv;
    const Vec2 size = part.hi - part.lo;
    const Vec2 local = (uv - part.lo).cwiseQuotient(size);
    return part.lo + part.flow->advect(local, options, steps).cwiseProduct(size);
  }
  return uv;
}

long FlowWarp::apply_all(std::vector<Vec2>& uv) const {
  std::atomic<long> total{0};
  tbb::parallel_for(tbb::blocked_range<size_t>(0, uv.size(), 64), [&](const tbb::blocked_range<size_t>& r) {
    long local = 0;
    for (size_t k = r.begin(); k < r.end(); ++k) {
      int s = 0;
      uv[k] = apply(uv[k], &s);
      local += s;
    }
    total += local;
  });
  return total;
}

FlowShape flow_shape(const ImageF& density, const std::function<Vec2(const Vec2&)>& map, int n, double threshold) {
  check_density(density);
  if (n < 1 || !(threshold > 0)) throw InvalidInputError("flow_shape: n must be >= 1 and the threshold > 0");
  GridWarp g = GridWarp::uniform(n);
  tbb::parallel_for(size_t(0), g.points.size(), [&](size_t k) { g.points[k] = map(g.points[k]); });
  double mean = 0;
  for (float v : density.data) mean += v;
  mean /= static_cast<double>(density.data.size());
  FlowShape fs;
  double aniso = 0;
  const double n2 = double(n) * n;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double area = cell_signed_area(g, i, j);
      const double target = sample_bilinear(density, (i + 0.5) / n, (j + 0.5) / n) / mean;
      fs.density_error += std::abs(area * n2 - target) / n2;
      fs.folded_cells += area <= 0;
      if (target <= threshold) continue;
      fs.dense_target += target / n2;
      fs.dense_area += area;
      // Singular values of the cell's Jacobian (mean of its two edge pairs), scaled by n.
      const Vec2 du = 0.5 * n * (g.at(i + 1, j) - g.at(i, j) + g.at(i + 1, j + 1) - g.at(i, j + 1));
      const Vec2 dv = 0.5 * n * (g.at(i, j + 1) - g.at(i, j) + g.at(i + 1, j + 1) - g.at(i + 1, j));
      const double a = du.squaredNorm(), c = dv.squaredNorm(), b = du.dot(dv);
      const double root = std::sqrt(std::max(0.0, 0.25 * (a - c) * (a - c) + b * b));
      const double s1 = std::sqrt(0.5 * (a + c) + root), s2 = std::sqrt(std::max(0.0, 0.5 * (a + c) - root));
      aniso += std::max(area, 0.0) * (s2 > 0 ? std::min(s1 / s2, 50.0) : 50.0);
    }
  fs.dense_anisotropy = fs.dense_area > 0 ? aniso / fs.dense_area : 0;
  return fs;
}

GridWarp density_equalizing_warp(const ImageF& density, const DensityFlowOptions& o, DensityFlowStats* stats) {
  check_density(density);
  if (o.cells < 1 || o.cells > 8192) throw InvalidInputError("density_equalizing_warp: cells must be in [1, 8192]");
  if (!(o.tolerance > 0) || o.max_steps < 1 || !(o.max_step_cells > 0) || !(o.direct_tolerance > 0) ||
      !(o.direct_max_step_cells > 0) || !(o.interpolation_tolerance >= 0))
    throw InvalidInputError(
        "density_equalizing_warp: tolerances and step limits must be > 0 (the interpolation tolerance >= 0) "
        "and max_steps >= 1");

  const DensityFlow flow(density);
  double mean = 0;
  for (float v : density.data) mean += v;
  mean /= static_cast<double>(density.data.size());
  GridWarp g = GridWarp::uniform(o.cells);
  const LatticeAdvection adv = advect_lattice(flow, o, g, o.interpolation_tolerance / o.cells);
  // Round-off can move a side point off its side by ~1e-17: put it back exactly.
  for (int k = 0; k <= o.cells; ++k) {
    g.at(0, k).x() = 0;
    g.at(o.cells, k).x() = 1;
    g.at(k, 0).y() = 0;
    g.at(k, o.cells).y() = 1;
  }
  const int tangled = untangle_lattice(g);
  if (stats) {
    stats->tangled_cells = tangled;
    stats->total_steps = adv.total_steps;
    stats->max_steps = adv.most_steps;
    stats->advected_points = adv.advected;
    stats->max_displacement = g.max_displacement();
    stats->inverted_cells = 0;
    const double n2 = double(o.cells) * o.cells;
    // Per row, then summed in row order: the same figures with or without threads.
    std::vector<double> row_err(static_cast<size_t>(o.cells), 0.0);
    std::vector<int> row_inverted(static_cast<size_t>(o.cells), 0);
    auto row = [&](int j) {
      for (int i = 0; i < o.cells; ++i) {
        const double a = cell_signed_area(g, i, j);
        if (!cell_convex(g, i, j)) ++row_inverted[static_cast<size_t>(j)];
        const double target = sample_bilinear(density, (i + 0.5) / o.cells, (j + 0.5) / o.cells) / mean;
        row_err[static_cast<size_t>(j)] += std::abs(a * n2 - target);
      }
    };
    if (o.parallel) {
      tbb::parallel_for(0, o.cells, row);
    } else {
      for (int j = 0; j < o.cells; ++j) row(j);
    }
    double err = 0;
    for (int j = 0; j < o.cells; ++j) {
      err += row_err[static_cast<size_t>(j)];
      stats->inverted_cells += row_inverted[static_cast<size_t>(j)];
    }
    stats->density_error = err / n2;
  }
  return g;
}

}  // namespace adaptex
