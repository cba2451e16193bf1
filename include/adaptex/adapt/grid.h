#pragma once
/// \file grid.h
/// The uniform grid G of thesis §3.7.1 and the warp it defines (§3.7.2): an (n+1) x (n+1) lattice of
/// points over [0,1]^2 whose point (i, j) starts at (i/n, j/n). After optimization the points have
/// moved; the warp maps a point of uniform cell (i, j) to the bilinear interpolation of that cell's four
/// moved corners. n counts *cells* per side, so a 16-cell coarse grid nests in a 256-cell fine grid.
#include <vector>

#include "adaptex/core/image.h"
#include "adaptex/core/types.h"

namespace adaptex {

/// A grid warp of [0,1]^2, or of one axis-aligned rectangle [lo, hi] of it (multi-chart layouts,
/// atlas_flow.h: one warp per chart rectangle). points has (n+1)^2 entries, row-major: index
/// j * (n+1) + i, in the rectangle's local coordinates (uv - lo) / (hi - lo), i.e. in [0,1]^2.
struct GridWarp {
  int n = 0;                 ///< Cells per side (>= 1).
  std::vector<Vec2> points;  ///< (n+1)^2 optimized point positions, in [0,1]^2 (local coordinates).
  /// The rectangle the warp acts on: apply() maps it onto itself and is the identity outside it.
  /// (0,0)-(1,1), the default, is the whole square.
  Vec2 lo = Vec2(0, 0), hi = Vec2(1, 1);

  /// The identity warp with \p cells cells per side. \pre cells >= 1 \throw InvalidInputError
  static GridWarp uniform(int cells);
  int side() const { return n + 1; }
  Vec2& at(int i, int j) { return points[static_cast<size_t>(j) * (n + 1) + i]; }
  const Vec2& at(int i, int j) const { return points[static_cast<size_t>(j) * (n + 1) + i]; }
  /// Bilinear interpolation, in the uniform cell containing \p uv (clamped to [0,1]^2), of the cell's
  /// four moved corners (thesis §3.7.2). The identity for a uniform grid. With a rectangle: \p uv
  /// outside [lo, hi] is returned unchanged; inside, the lattice acts in local coordinates.
  Vec2 apply(const Vec2& uv) const;
  /// The lattice map alone, in local coordinates (\p uv clamped to [0,1]^2).
  Vec2 apply_lattice(const Vec2& uv) const;
  /// True if \p uv lies in [lo, hi] within 1e-12 (round-off of the move that placed a wedge on a
  /// side): the points apply() moves.
  bool contains(const Vec2& uv) const;
  /// True if the warp acts on the whole square (lo = (0,0), hi = (1,1)).
  bool whole_square() const { return lo == Vec2(0, 0) && hi == Vec2(1, 1); }
  /// (1 - t) * identity + t * this: the damped warp (t = 1 full warp, t = 0 identity), same rectangle.
  GridWarp blended(double t) const;
  /// Largest distance of a point from its uniform position.
  double max_displacement() const;
};

/// Warps applied in turn, each the identity outside its rectangle (GridWarp::apply): the map from
/// the start layout through every warp (refinement and remap of multi-chart layouts, one warp per
/// chart, atlas_flow.h). When every warp acts on a rectangle and the rectangles are at least
/// kMinGap apart, a point moves under at most one of them, so apply() finds that one in a bucket
/// grid instead of testing them all (armadillo's 15 charts); the result is the same as in turn.
class WarpChain {
 public:
  /// Gap between rectangles (in uv) above which they are looked up in buckets.
  static constexpr double kMinGap = 1e-9;
  /// \p warps: applied in this order; the pointers must outlive the chain (null entries skipped).
  explicit WarpChain(std::vector<const GridWarp*> warps);
  /// warps[k-1](...warps[0](uv)), the same value as applying them in turn.
  Vec2 apply(const Vec2& uv) const;
  /// True if apply() looks the rectangle up instead of applying every warp.
  bool bucketed() const { return n_ > 0; }

 private:
  std::vector<const GridWarp*> warps_;
  int n_ = 0;                         ///< Buckets per side (0: apply in turn).
  std::vector<int> start_, entries_;  ///< CSR: bucket b holds warps entries_[start_[b] .. start_[b+1]).
};

/// Inverse of a grid warp sampled on a res x res raster: for each texel centre q
/// ((i+0.5)/res, (j+0.5)/res), finds p with warp.apply(p) = q (Newton on the bilinear cell map) and
/// returns field sampled bilinearly at p. Used to pull a weight field back into the domain warped by
/// the coarse stage (two-stage composition, §3.8). Texels no cell covers (only possible for a folded
/// warp) keep the value at q itself. Parallel over rows.
/// \pre res >= 1; warp points inside [0,1]^2
ImageF pull_back_field(const ImageF& field, const GridWarp& warp, int res);

/// True if cell (i, j) of \p g is a strictly convex, positively oriented quad (its four corner
/// triangles have positive area): then its bilinear map is one-to-one. \pre 0 <= i, j < g.n
bool cell_convex(const GridWarp& g, int i, int j);
/// cell_convex() of every cell of \p g, row-major (index j * n + i). Parallel over rows.
std::vector<char> convex_cells(const GridWarp& g);

/// Untangles a freshly built lattice (the advected flow lattice): Laplacian-smooths the points of
/// every non-convex cell and a halo around them (1 + round/10 points wide, 4 sweeps per round, side
/// points slide along their side, corners stay), the region only growing, until every cell is convex
/// or 200 rounds passed. \return the number of non-convex cells before
int untangle_lattice(GridWarp& g);
/// Untangles the cells a motion turned: the interior corners of every cell that was convex
/// (\p convex, from convex_cells()) and is not now, and the points within `ring` of them, move to the
/// mean of their four neighbours in index order, round after round. The ring starts at 0 and widens by
/// one whenever 20 rounds did not lower the number of such cells, up to 4; at most 1000 rounds.
/// \return the number of such cells left; \p turned (if set) gets their number before.
/// \pre convex.size() == g.n * g.n
size_t untangle_turned_cells(GridWarp& g, const std::vector<char>& convex, int* turned = nullptr);
}  // namespace adaptex
