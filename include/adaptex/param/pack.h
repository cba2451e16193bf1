#pragma once
/// \file pack.h
/// Chart packing (thesis §3.2, the last step of the surgery: one chart per connected component,
/// all in the unit square). Every chart arrives as a square (its UVs in [0,1]^2, as the disk
/// parameterization returns them); the squares are sized in proportion to the square root of the
/// chart's 3-D area (so that all charts get the same texel density), shelf-packed, and the whole
/// layout is scaled uniformly into [0,1]^2. Charts cannot overlap: the squares are disjoint by
/// construction, and each chart stays inside its square.
#include <vector>

#include "adaptex/core/progress.h"
#include "adaptex/core/types.h"

namespace adaptex {

/// Placement of one chart: uv' = offset + scale * uv, for uv in [0,1]^2.
struct ChartPlacement {
  Vec2 offset = Vec2::Zero();  ///< Lower-left corner of the chart's square in [0,1]^2.
  double scale = 1.0;          ///< Side of the chart's square.
};

/// Packs one unit square per chart into [0,1]^2.
/// \param areas 3-D surface area of every chart (C values, > 0; zero/negative areas get the
///        smallest positive size)
/// \param padding minimum gap between two squares and between a square and the border of the
///        unit square, as a fraction of the unit square, in [0, 0.25). A single chart fills the
///        whole unit square (no padding): the adaptive re-parameterization keeps the square boundary.
/// \return C placements; the squares [offset, offset + scale]^2 are pairwise disjoint, at least
///         \p padding apart, and inside [0,1]^2
/// \throw InvalidInputError padding out of range or no charts
std::vector<ChartPlacement> pack_charts(const std::vector<double>& areas, double padding);

/// Placement of one rectangular chart: uv' = offset + size.cwiseProduct(uv), for uv in [0,1]^2.
struct RectPlacement {
  Vec2 offset = Vec2::Zero();  ///< Lower-left corner of the chart's rectangle in [0,1]^2.
  Vec2 size = Vec2::Ones();    ///< Width and height of the chart's rectangle.
};

/// Packs one rectangle per chart into [0,1]^2 (multi-chart layouts, docs/charts.md): rectangle i
/// has the shape of \p sizes[i] (width, height; only the ratios between all the sizes matter), all
/// scaled by the same factor, the largest at which one of these packings fits with gap \p padding
/// between rectangles and to the border (bisection on the factor, relative accuracy 1e-4): a shelf
/// packing (tallest first, rows left to right) and, for at most 500 rectangles, MaxRects (Jylänki
/// 2010, "A thousand ways to pack the bin") with the bottom-left and the best-short-side-fit rules,
/// each with the rectangles sorted by height, area, longest side and width. If the gaps alone do
/// not fit (thousands of rectangles), the gap is halved until they do. Above 500 rectangles the
/// shelves of pack_rectangles(sizes, options). A single rectangle fills the unit square.
/// Rectangles are never turned.
/// \param sizes C positive (width, height) pairs (non-positive entries get the smallest size)
/// \param padding as in pack_charts()
/// \return C placements: pairwise disjoint rectangles at least \p padding apart, inside [0,1]^2;
///         placement i has the shape of sizes[i]
/// \throw InvalidInputError padding out of range, no charts, or they cannot be packed
std::vector<RectPlacement> pack_rectangles(const std::vector<Vec2>& sizes, double padding);

/// pack_rectangles() where the MaxRects packings may also turn a rectangle by 90° (whichever
/// orientation scores better for the free box it goes to).
/// \param turned receives C flags: 1 if placement i has the shape (sizes[i].y(), sizes[i].x())
/// \return as pack_rectangles(), with the turned shapes
/// \throw InvalidInputError as pack_rectangles()
std::vector<RectPlacement> pack_rectangles_turning(const std::vector<Vec2>& sizes, double padding,
                                                   std::vector<char>& turned);

/// Settings of pack_rectangles(sizes, options, turned).
struct RectPackOptions {
  /// Gap between rectangles and to the border, as in pack_charts(); default 0.
  double padding = 0;
  /// Smallest side of a placed rectangle, as a fraction of the unit square (a minimum texel
  /// floor: 2 texels of a 1024² texture = 2.0 / 1024). A rectangle whose shorter side would come
  /// out smaller is enlarged uniformly (its shape kept) to this side. Where the gaps and these
  /// sides alone cannot fit (thousands of rectangles), both are halved until they do. Default 0
  /// (none); in [0, 0.25).
  double min_side = 0;
  /// Rectangles may be turned by 90° (the flags go to \p turned). Default false.
  bool may_turn = false;
  /// Progress ("pack", fraction of the scale search) and cancel.
  ProgressCallback progress;
};

/// pack_rectangles() with a minimum side, optional turning and progress. With min_side = 0 the
/// result is exactly that of pack_rectangles() (no turning) or pack_rectangles_turning(). Up to
/// 500 rectangles: the MaxRects and shelf strategies (0.5 s of CPU at 500). With more, every
/// scale tried costs O(n log n): shelves filled first
/// fit by decreasing height (FFDH, a max-tree over the shelves' free widths; turned rectangles
/// lie landscape when turning is allowed) and shelves in one row (next fit); the scale is found
/// by bisection (a fixed number of steps), so the whole packing is O(n log n) (10^4 rectangles in
/// tens of milliseconds). Non-finite or non-positive sizes get the smallest size.
/// \param turned if not null, receives C flags (1: placement i has the shape (sizes[i].y(), sizes[i].x()))
/// \param gap_used if not null, receives the gap the packing kept (padding, or halved)
/// \return as pack_rectangles(); each rectangle is at least min_side wide and high
/// \throw InvalidInputError padding or min_side out of range, no charts, or they cannot be packed
/// \throw CancelledError the progress callback returned false
std::vector<RectPlacement> pack_rectangles(const std::vector<Vec2>& sizes,
                                           const RectPackOptions& options,
                                           std::vector<char>* turned = nullptr,
                                           double* gap_used = nullptr);

/// One chart for pack_shapes(): its UV triangles, in a frame where every chart has the texel
/// density it should get (only the ratios between the charts' sizes matter).
struct ChartShape {
  std::vector<Vec2> uv;     ///< Vertex positions (finite).
  std::vector<Face> faces;  ///< Triangles, indices into uv (none: the chart is a point).
};

/// Placement of one shape: uv' = offset + scale * R(turns * 90°) uv (a rotation, never a mirror).
struct ShapePlacement {
  Vec2 offset = Vec2::Zero();  ///< Translation in [0,1]^2 units.
  double scale = 1.0;          ///< Uniform scale (the common one, or larger for min_side).
  int turns = 0;               ///< Counter-clockwise quarter turns, 0-3.
  /// The placed position of \p uv.
  Vec2 apply(const Vec2& uv) const;
};

/// Settings of pack_shapes().
struct ShapePackOptions {
  /// Smallest gap between the triangles of two charts and to the border of [0,1]^2 (a gutter);
  /// in [0, 0.25). Default 0.
  double padding = 0;
  /// Minimum texel floor: a chart whose bounding box would have a side shorter than this is
  /// enlarged uniformly to it (a sliver only until its longer side is 16 times this); as
  /// RectPackOptions::min_side, and both it and the gap are halved while they alone do not fit.
  /// In [0, 0.25). Default 0.
  double min_side = 0;
  /// Charts may be turned by quarter turns (4 orientations). Default true.
  bool may_turn = true;
  /// Side of the atlas raster in cells; 0 (default) = 1024 up to 64 charts, 2048 up to 4096
  /// charts, 8192 from 7169 to 12288 charts, 4096 otherwise. In [64, 16384].
  int resolution = 0;
  /// Packings tried to find the scale (each one O(cells + resolution * chart widths)). Default 6.
  int trials = 6;
  /// Progress ("pack", fraction of the trials) and cancel.
  ProgressCallback progress;
};

/// Packs charts by their shapes (horizon packing, Lévy et al. 2002, "Least squares conformal maps",
/// §5): each chart is rasterized conservatively (every raster cell its closed triangles touch,
/// held as the lowest and highest cell of every column), dilated by the gap, and dropped into the
/// atlas from above at the column and quarter turn of the lowest score, its height plus the empty
/// area it leaves between the atlas' horizon (the top of every column) and its bottom; charts of
/// the longest side first. Irregular charts thus nest where rectangles would not. The empty cells a
/// chart encloses between the horizon and its bottom are kept as rectangles (holes, each the
/// largest in its columns), and a later chart whose dilated raster fits one goes into the
/// smallest such hole instead of onto the horizon. All charts share one scale, the largest of
/// \p trials packings (scale search from the filled height, not a bisection). O(trials · (raster
/// cells + triangles + resolution · Σ chart widths)).
/// \pre every index in \p charts[i].faces is in [0, uv.size()), every uv finite
/// \return C placements: the placed triangles of two charts are at least \p padding apart (so
/// never overlap), inside [padding, 1 - padding]^2, with the charts' relative sizes except those
/// raised to min_side
/// \param gap_used if not null, receives the gap the packing kept (padding, or halved)
/// \throw InvalidInputError no charts, an option out of range, a bad index or a non-finite uv,
/// or they cannot be packed
/// \throw CancelledError the progress callback returned false
std::vector<ShapePlacement> pack_shapes(const std::vector<ChartShape>& charts,
                                        const ShapePackOptions& options, double* gap_used = nullptr);

}  // namespace adaptex
