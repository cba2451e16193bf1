#pragma once
/// \file grid.h
/// The uniform grid of thesis §3.7.1 and its warp (§3.7.2): (n+1)² points, point (i, j) starting at
/// (i/n, j/n); a point maps to the bilinear interpolation of its cell's moved corners.
#include <vector>

#include "adaptex/core/image.h"
#include "adaptex/core/types.h"

namespace adaptex {

/// A grid warp of [0,1]² or of a rectangle [lo, hi] of it; points row-major (j·(n+1) + i), local coordinates.
struct GridWarp {
  int n = 0;                 ///< Cells per side (>= 1).
  std::vector<Vec2> points;  ///< (n+1)^2 optimized point positions, in [0,1]^2 (local coordinates).
  Vec2 lo = Vec2(0, 0), hi = Vec2(1, 1);  ///< The rectangle it maps onto itself (identity outside).

  /// The identity warp with \p cells cells per side. \pre cells >= 1 \throw InvalidInputError
  static GridWarp uniform(int cells);
  int side() const { return n + 1; }
  Vec2& at(int i, int j) { return points[static_cast<size_t>(j) * (n + 1) + i]; }
  const Vec2& at(int i, int j) const { return points[static_cast<size_t>(j) * (n + 1) + i]; }
  /// Bilinear interpolation of the moved corners of the uniform cell containing \p uv (§3.7.2).
  Vec2 apply(const Vec2& uv) const;
  /// The lattice map alone, in local coordinates (\p uv clamped to [0,1]^2).
  Vec2 apply_lattice(const Vec2& uv) const;
  bool contains(const Vec2& uv) const;  ///< \p uv in [lo, hi] within 1e-12: the points apply() moves.
  bool whole_square() const { return lo == Vec2(0, 0) && hi == Vec2(1, 1); }
  GridWarp blended(double t) const;     ///< (1 − t)·identity + t·this, same rectangle.
  double max_displacement() const;      ///< Largest distance of a point from its uniform position.
};

/// Warps applied in turn; with disjoint rectangles apply() finds the one that moves a point in a
/// bucket grid (the same result as in turn).
class WarpChain {
 public:
  static constexpr double kMinGap = 1e-9;  ///< Gap between rectangles above which buckets are used.
  explicit WarpChain(std::vector<const GridWarp*> warps);  ///< In this order; pointers must outlive the chain.
  Vec2 apply(const Vec2& uv) const;        ///< warps[k-1](...warps[0](uv)).
  bool bucketed() const { return n_ > 0; }

 private:
  std::vector<const GridWarp*> warps_;
  int n_ = 0;                         ///< Buckets per side (0: apply in turn).
  std::vector<int> start_, entries_;  ///< CSR: bucket b holds warps entries_[start_[b] .. start_[b+1]).
};

/// \p field pulled back through \p warp on a res x res raster: texel q gets field(p), warp.apply(p) = q
/// (two-stage composition, §3.8; uncovered texels keep field(q)).
/// \pre res >= 1; warp points inside [0,1]^2
ImageF pull_back_field(const ImageF& field, const GridWarp& warp, int res);

/// Cell (i, j) is a strictly convex, positive quad (its bilinear map is one-to-one). \pre 0 <= i, j < g.n
bool cell_convex(const GridWarp& g, int i, int j);
/// cell_convex() of every cell of \p g, row-major (index j * n + i). Parallel over rows.
std::vector<char> convex_cells(const GridWarp& g);

/// Smooths a fresh lattice's non-convex cells and a growing halo (≤ 200 rounds). \return their count before
int untangle_lattice(GridWarp& g);
/// Smooths the cells a motion turned (convex in \p convex, not now). \return those left (\p turned: before)
/// \pre convex.size() == g.n * g.n
size_t untangle_turned_cells(GridWarp& g, const std::vector<char>& convex, int* turned = nullptr);

/// Gaussian blur of an n x n cell raster \p f (row-major), in place: separable, radius
/// max(1, ceil(3 sigma)) cells, sides reflected; sigma <= 0 leaves \p f unchanged. Parallel over rows,
/// the same result with or without threads. \pre f.size() == n * n, n >= 1
void gaussian_blur(std::vector<double>& f, int n, double sigma);
}  // namespace adaptex
