// A coarse lattice's polish moved onto the warp (polish_warp(), error_polish.h).
#include "adaptex/adapt/error_polish.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "adaptex/core/errors.h"
#include "adaptex/core/predicates.h"

namespace adaptex {

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
        const double det = cross2d(da, db);
        if (!(std::abs(det) > 1e-300)) break;
        const double sa = cross2d(r, db) / det, sb = cross2d(da, r) / det;
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

}  // namespace adaptex
