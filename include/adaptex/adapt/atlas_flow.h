#pragma once
/// \file atlas_flow.h
/// density-flow on multi-chart layouts (docs/error_model.md §5): 1. re-pack the charts' rectangles
/// sized by their density share (Sander et al. 2002, §5); 2. one flow per rectangle, onto itself.
#include <vector>

#include "adaptex/adapt/density_flow.h"
#include "adaptex/adapt/grid.h"
#include "adaptex/core/image.h"
#include "adaptex/core/parameterization.h"

namespace adaptex {

/// Axis-aligned rectangle [lo, hi] of the unit square.
struct UvRect {
  Vec2 lo = Vec2(0, 0), hi = Vec2(0, 0);
  Vec2 size() const { return hi - lo; }
  double area() const { return size().x() * size().y(); }
};

/// Where one chart goes: uv' = dst_lo + scale * (uv - src.lo).
struct ChartMove {
  UvRect src;            ///< The chart's rectangle before (its UV bounding box).
  Vec2 dst_lo = Vec2(0, 0);  ///< Lower-left corner after.
  double scale = 1;      ///< Uniform scale (> 0).
  UvRect dst() const { return {dst_lo, dst_lo + scale * src.size()}; }
  Vec2 apply(const Vec2& uv) const { return dst_lo + scale * (uv - src.lo); }
};

/// The UV bounding box of every chart (empty at the origin for a chart without faces).
/// \pre param.face_chart has one entry per face, in [0, num_charts)
std::vector<UvRect> chart_boxes(const Parameterization& param);

/// Smallest gap between two boxes (< 0: overlap; +infinity for fewer than two).
double smallest_box_gap(const std::vector<UvRect>& boxes);

/// Settings of repack_charts_by_density().
struct ChartRepackOptions {
  double padding = 8.0 / 1024;  ///< Gap between rectangles and to the sides, share of the square, [0, 0.25).
  int samples_per_cell = 2;      ///< Density samples per raster cell and axis when integrating ρ; 2.
};

/// Step 1 above: new rectangles for the charts, sized by their integral of \p density.
/// \return one move per box; dst() rectangles disjoint, padded, in [0,1]², aspect kept
/// \throw InvalidInputError empty density, bad padding, or boxes that cannot be packed
std::vector<ChartMove> repack_charts_by_density(const std::vector<UvRect>& boxes, const ImageF& density,
                                                const ChartRepackOptions& options = {});

/// Step 1 with the error model choosing the resize: sizes ∝ (mean ρ)^(γ/2), γ ∈ {1, ¾, ½, ¼, 0}, or the
/// charts left in place (if already padded); the least predicted_chart_error() wins (ties: the earlier).
/// \param chosen_gamma if given: the chosen γ, −1 for in place \throw InvalidInputError as above, or not L x L
std::vector<ChartMove> allocate_charts_by_error(const std::vector<UvRect>& boxes, const ImageF& density,
                                                const ImageF& error, const ImageF& exponent,
                                                const ChartRepackOptions& options = {}, double* chosen_gamma = nullptr);

/// The model's error after \p moves and a flow per chart: Σ q·(s_c²·ρ / mean_c ρ)^(−p/2) over painted cells.
/// \throw InvalidInputError rasters of different sizes, or empty
double predicted_chart_error(const std::vector<ChartMove>& moves, const ImageF& density, const ImageF& error,
                             const ImageF& exponent, const ChartRepackOptions& options = {});

/// \p param with every chart moved by its move (exact; faces and wedges unchanged).
/// \pre moves.size() == param.num_charts; face_chart valid
Parameterization move_charts(const Parameterization& param, const std::vector<ChartMove>& moves);

/// The move whose source rectangle contains a point (bucket grid). Thread-safe after construction.
class ChartMoveLocator {
 public:
  explicit ChartMoveLocator(std::vector<ChartMove> moves);  ///< \pre src rectangles pairwise disjoint
  Vec2 apply(const Vec2& uv) const;  ///< The moved point (unchanged outside every src rectangle).

 private:
  std::vector<ChartMove> moves_;
  int n_ = 1;
  std::vector<std::vector<int>> buckets_;
};

/// Lattice cells per side of every chart's flow: its longer side times \p cells, clamped to
/// [min(min_cells, cells), cells], scaled so all points total at most one (cells+1)² lattice; from 16
/// cells on rounded to a multiple of 4. Returns moves.size() values.
/// \throw InvalidInputError cells < 1 or min_cells < 1
std::vector<int> chart_lattice_cells(const std::vector<ChartMove>& moves, int cells, int min_cells);

/// Step 2: one density-equalizing GridWarp per chart on its dst() rectangle, from \p density over its src.
/// \param stats if given: the charts' stats summed \throw InvalidInputError empty density or bad options
std::vector<GridWarp> chart_flow_warps(const std::vector<ChartMove>& moves, const ImageF& density,
                                       const DensityFlowOptions& flow, int min_cells = 8,
                                       DensityFlowStats* stats = nullptr);

}  // namespace adaptex
