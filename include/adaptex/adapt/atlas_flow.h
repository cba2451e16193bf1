#pragma once
/// \file atlas_flow.h
/// density-flow on multi-chart layouts (docs/error_model.md §6). One flow over the whole square moves
/// chart borders, which are straight UV edges, across the gutters; the remap then has to damp the warp
/// wherever two charts meet, and on layouts of 30–60 charts it kept only 3–46 % of it. Here every chart
/// keeps its own axis-aligned rectangle instead:
///  1. **Re-pack by density** (inter-chart): each chart's rectangle is scaled by the square root of
///     its share of the target density (the texel budget the error model gives it, ∫ρ over the
///     rectangle, relative to the rectangle's area) and the rectangles are packed again
///     (pack_rectangles, the layout's own gutter). This is the chart-level step of signal-specialized
///     parameterization (Sander, Gortler, Snyder, Hoppe 2002, §5: charts sized by their signal
///     stretch). Each chart moves by a similarity (scale + translation): exact, no flip, no overlap.
///  2. **One flow per rectangle** (intra-chart): the density-equalizing map (density_flow.h) of the
///     density restricted to the chart's rectangle, as a GridWarp with that rectangle (grid.h). It
///     maps the rectangle onto itself, so charts stay in disjoint rectangles whatever the warp does.
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

/// The UV bounding box of every chart of \p param (C = num_charts entries; a chart without faces
/// gets an empty box at the origin).
/// \pre param.face_chart has one entry per face, in [0, num_charts)
std::vector<UvRect> chart_boxes(const Parameterization& param);

/// The smallest gap between two of \p boxes: the larger of their separations along u and v;
/// negative if two boxes overlap. +infinity for fewer than two boxes.
double smallest_box_gap(const std::vector<UvRect>& boxes);

/// Settings of repack_charts_by_density().
struct ChartRepackOptions {
  /// Gap between re-packed rectangles and to the square's sides, as a fraction of the square
  /// (the layout's own smallest gap is the usual choice). In [0, 0.25).
  double padding = 8.0 / 1024;
  /// Density samples per density-raster cell and axis when integrating ρ over a rectangle.
  int samples_per_cell = 2;
};

/// Step 1 above: new rectangles for the charts, sized by their integral of \p density.
/// \param boxes C chart rectangles (chart_boxes()), pairwise disjoint
/// \param density L x L target density over the square (error_density.h; > 0)
/// \return C moves; the dst() rectangles are pairwise disjoint, at least options.padding apart,
///         inside [0,1]^2, each with the aspect ratio of its box
/// \throw InvalidInputError empty density, bad padding, or boxes that cannot be packed
std::vector<ChartMove> repack_charts_by_density(const std::vector<UvRect>& boxes, const ImageF& density,
                                                const ChartRepackOptions& options = {});

/// Step 1 with the error model choosing how strongly the charts are resized. Candidates: the charts
/// re-packed with sizes ∝ (mean ρ)^(γ/2) for γ = 1 (repack_charts_by_density()), 3/4, 1/2, 1/4 and 0,
/// and the charts left where they are (only if \p boxes are already options.padding apart and from the
/// square's sides). Each is scored by the error the model predicts after the
/// flows, Σ q·ρ_real^(−p/2) over the painted cells (error_density.h), where a chart scaled by s gets
/// ρ_real = s²·ρ / mean_c(ρ) in its cells (its flow spreads its texels as the density asks); the
/// smallest wins (ties: the earlier). Texels that a packing loses to gaps thus count against a strong
/// resize: re-packing 4 charts of very different sizes covered 0.56 of the square where the unwrap's
/// packing covered 0.91 (spot, dots at 256²).
/// \param error, exponent L x L: the model's q (0 where unpainted) and p, as in ErrorDensity
/// \param chosen_gamma if given: the chosen γ, or −1 for the charts left in place
/// \return as repack_charts_by_density()
/// \throw InvalidInputError as repack_charts_by_density(), or error / exponent not L x L
std::vector<ChartMove> allocate_charts_by_error(const std::vector<UvRect>& boxes, const ImageF& density,
                                                const ImageF& error, const ImageF& exponent,
                                                const ChartRepackOptions& options = {}, double* chosen_gamma = nullptr);

/// The error the model predicts after moving the charts by \p moves and equalizing the density
/// inside every chart: Σ q·(s_c²·ρ / mean_c ρ)^(−p/2) over the cells with q > 0 whose centre lies in a
/// chart's src box (s_c: its move's scale, mean_c: the mean of ρ over that box). What
/// allocate_charts_by_error() minimizes.
/// \pre density, error, exponent L x L; moves' src boxes pairwise disjoint
/// \throw InvalidInputError rasters of different sizes, or empty
double predicted_chart_error(const std::vector<ChartMove>& moves, const ImageF& density, const ImageF& error,
                             const ImageF& exponent, const ChartRepackOptions& options = {});

/// \p param with every chart moved by its move (exact; faces and wedges unchanged).
/// \pre moves.size() == param.num_charts; face_chart valid
Parameterization move_charts(const Parameterization& param, const std::vector<ChartMove>& moves);

/// Finds the move whose source rectangle contains a point (boxes pairwise disjoint), by a uniform
/// bucket grid. Thread-safe after construction.
class ChartMoveLocator {
 public:
  /// Keeps a copy of \p moves. \pre the moves' src rectangles are pairwise disjoint
  explicit ChartMoveLocator(std::vector<ChartMove> moves);
  /// The moved point; points outside every source rectangle are returned unchanged.
  Vec2 apply(const Vec2& uv) const;

 private:
  std::vector<ChartMove> moves_;
  int n_ = 1;
  std::vector<std::vector<int>> buckets_;
};

/// Lattice cells per side of every chart's flow (chart_flow_warps): the longer side of the larger of
/// its src and dst rectangles times \p cells, in [min(min_cells, cells), cells], all scaled down
/// together when their (n+1)² points would add up to more than one (cells+1)² lattice (the flow's
/// cost is per point; measured: the former per-chart max(dst·cells, src·256) made the 4-16-chart
/// flows of the shared meshes 3.2-4.7 square lattices). From 16 cells on, a chart's count is rounded to
/// the nearest multiple of 4 (coarse-to-fine advection needs even counts). Returns moves.size() values.
/// \throw InvalidInputError cells < 1 or min_cells < 1
std::vector<int> chart_lattice_cells(const std::vector<ChartMove>& moves, int cells, int min_cells);

/// Step 2 above: one density-equalizing GridWarp per chart, on its dst() rectangle, from \p density
/// sampled over the chart's src rectangle, with chart_lattice_cells(moves, flow.cells, min_cells)
/// cells per side. Charts in parallel.
/// \param stats if given: sums of the per-chart stats (tangled / inverted cells, steps), max of max_*
/// \throw InvalidInputError empty density or bad flow options
std::vector<GridWarp> chart_flow_warps(const std::vector<ChartMove>& moves, const ImageF& density,
                                       const DensityFlowOptions& flow, int min_cells = 8,
                                       DensityFlowStats* stats = nullptr);

/// The exact flows that chart_flow_warps() samples on lattices (density_flow.h, FlowWarp): one part
/// per chart on its dst() rectangle, solved on \p density over its src rectangle, resampled at the
/// density raster's resolution along the rectangle's longer side (at least \p min_cells, at most
/// twice the raster's). Degenerate charts get no flow (the identity). Charts in parallel.
/// \param flow the integration settings the FlowWarp keeps (direct_tolerance, direct_max_step_cells)
/// \throw InvalidInputError empty density or min_cells < 2
FlowWarp chart_flows(const std::vector<ChartMove>& moves, const ImageF& density, const DensityFlowOptions& flow,
                     int min_cells = 8);

}  // namespace adaptex
