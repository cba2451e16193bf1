// Grid relaxation of thesis §3.7.1 (weighted 1-ring averaging, Gauss–Seidel, multi-colour order).
#include "adaptex/adapt/relax.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "adaptex/core/errors.h"

namespace adaptex {

namespace {

// Moves the interior points of row j with colour c; returns the largest move.
double relax_row(GridWarp& g, std::vector<double>& w, const ImageF& field, int j, int c, bool eight) {
  const int n = g.n, side = n + 1;
  double max_move = 0;
  for (int i = 1; i < n; ++i) {
    const int colour = eight ? (i & 1) + 2 * (j & 1) : (i + j) & 1;
    if (colour != c) continue;
    const size_t k = static_cast<size_t>(j) * side + i;
    double ws = 0;
    Vec2 acc(0, 0);
    auto add = [&](size_t m) {
      ws += w[m];
      acc += w[m] * g.points[m];
    };
    add(k - 1);
    add(k + 1);
    add(k - side);
    add(k + side);
    if (eight) {
      add(k - side - 1);
      add(k - side + 1);
      add(k + side - 1);
      add(k + side + 1);
    }
    const Vec2 p = acc / ws;
    max_move = std::max(max_move, (p - g.points[k]).norm());
    g.points[k] = p;
    w[k] = sample_bilinear(field, p.x(), p.y());
  }
  return max_move;
}

// Slides the non-corner boundary points of colour c along their side: the weighted average of the
// ring (points outside the grid skipped), projected on the side and clamped between the two
// neighbours on the side, so the order along the side (and the square) is preserved.
double slide_boundary(GridWarp& g, std::vector<double>& w, const ImageF& field, int c, bool eight) {
  const int n = g.n, side = n + 1;
  double max_move = 0;
  auto visit = [&](int i, int j, bool horizontal) {
    const int colour = eight ? (i & 1) + 2 * (j & 1) : (i + j) & 1;
    if (colour != c) return;
    const size_t k = static_cast<size_t>(j) * side + i;
    double ws = 0, acc = 0;
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        if ((di == 0 && dj == 0) || (!eight && di != 0 && dj != 0)) continue;
        const int x = i + di, y = j + dj;
        if (x < 0 || x > n || y < 0 || y > n) continue;
        const size_t m = static_cast<size_t>(y) * side + x;
        ws += w[m];
        acc += w[m] * (horizontal ? g.points[m].x() : g.points[m].y());
      }
    double v = acc / ws;
    const size_t a = horizontal ? k - 1 : k - side, b = horizontal ? k + 1 : k + side;
    const double lo = horizontal ? g.points[a].x() : g.points[a].y();
    const double hi = horizontal ? g.points[b].x() : g.points[b].y();
    v = std::clamp(v, lo, hi);
    Vec2 p = g.points[k];
    (horizontal ? p.x() : p.y()) = v;
    max_move = std::max(max_move, (p - g.points[k]).norm());
    g.points[k] = p;
    w[k] = sample_bilinear(field, p.x(), p.y());
  };
  for (int i = 1; i < n; ++i) {
    visit(i, 0, true);
    visit(i, n, true);
  }
  for (int j = 1; j < n; ++j) {
    visit(0, j, false);
    visit(n, j, false);
  }
  return max_move;
}

}  // namespace

RelaxStats relax_grid(GridWarp& grid, const ImageF& weights, const RelaxOptions& options) {
  if (weights.width <= 0 || weights.height <= 0 || weights.data.empty())
    throw InvalidInputError("relax_grid: empty weight field");
  if (grid.n < 1 || grid.points.size() != static_cast<size_t>(grid.n + 1) * (grid.n + 1))
    throw InvalidInputError("relax_grid: grid of " + std::to_string(grid.n) + " cells has " +
                            std::to_string(grid.points.size()) + " points");
  if (!(options.epsilon >= 0) || options.max_iterations < 0)
    throw InvalidInputError("relax_grid: epsilon must be >= 0 and max_iterations >= 0");
  RelaxStats stats;
  const int n = grid.n;
  if (n < 2) {  // no interior point
    stats.converged = true;
    return stats;
  }
  std::vector<double> w(grid.points.size());
  for (size_t k = 0; k < w.size(); ++k) w[k] = sample_bilinear(weights, grid.points[k].x(), grid.points[k].y());
  const bool eight = options.ring == GridRing::Eight;
  const int colours = eight ? 4 : 2;
  const bool parallel = options.parallel && n >= 64;
  for (int it = 0; it < options.max_iterations; ++it) {
    double max_move = 0;
    for (int c = 0; c < colours; ++c) {
      if (parallel) {
        max_move = std::max(max_move, tbb::parallel_reduce(
            tbb::blocked_range<int>(1, n, 8), 0.0,
            [&](const tbb::blocked_range<int>& r, double m) {
              for (int j = r.begin(); j < r.end(); ++j) m = std::max(m, relax_row(grid, w, weights, j, c, eight));
              return m;
            },
            [](double a, double b) { return std::max(a, b); }));
      } else {
        for (int j = 1; j < n; ++j) max_move = std::max(max_move, relax_row(grid, w, weights, j, c, eight));
      }
      if (options.slide_boundary) max_move = std::max(max_move, slide_boundary(grid, w, weights, c, eight));
    }
    stats.iterations = it + 1;
    stats.last_max_move = max_move;
    if ((it & 15) == 15) report_progress(options.progress, "relax", double(it + 1) / options.max_iterations);
    if (max_move < options.epsilon) {
      stats.converged = true;
      break;
    }
  }
  return stats;
}

}  // namespace adaptex
