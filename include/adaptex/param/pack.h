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
/// \return as pack_rectangles(); each rectangle is at least min_side wide and high
/// \throw InvalidInputError padding or min_side out of range, no charts, or they cannot be packed
/// \throw CancelledError the progress callback returned false
std::vector<RectPlacement> pack_rectangles(const std::vector<Vec2>& sizes,
                                           const RectPackOptions& options,
                                           std::vector<char>* turned = nullptr);

}  // namespace adaptex
