#pragma once
/// \file error_polish.h
/// Polishing a warp lattice by the error model itself, with the texel grid's anisotropy counted
/// (`--adapt density-flow`, after the flow; derivation and measurements in docs/error_model.md §11, §12).
///
/// The density-equalizing flow (density_flow.h) reaches a target *area* density: it controls only
/// det J of the warp's Jacobian J. Around a painted dot the flow magnifies radially less than
/// tangentially wherever the target density varies, and the dot's edge lies exactly there: measured on
/// the lattice of venus `dots` at 256², the worse direction's texel density gains 0.4–1.3 dB less than
/// the area density. Error model with direction: an edge of unit normal
/// n, in a layout whose Jacobian (old uv → new uv, in texels) is J, leaves an error per unit length
/// ∝ |J⁻ᵀn|^p (p as measured by error_density.h: 1 for hard edges); averaged over edge directions
/// (dots, curved strokes), |J⁻ᵀn|² → |J⁻¹|²_F / 2, so the polish minimizes
///
///     E(X) = Σ_cells q_c · mean over the cell's 4 corner triangles of (|J|²_F / (2 det² J))^(p_c/2)
///          + κ Σ_unpainted cells max(0, ρ_floor / det J − 1)²,
///
/// over the lattice points X (boundary points slide along their side, corners stay). For a conformal J
/// (J = s·R) the first term is q·s^(−p) = q·ρ^(−p/2), the isotropic model the density came from;
/// otherwise it is larger. It is a barrier at det J → 0, so a polished cell never folds. The square
/// maps onto itself, so the texel budget is fixed without a multiplier; the floor term keeps the
/// unpainted cells at the density the model gave them. Minimized by nonlinear Gauss–Seidel: each point
/// takes a damped Newton step on its own energy (exact 2 × 2 gradient and Hessian), with a line
/// search that only accepts a lower energy and convex cells; the four point colours (i mod 2, j mod 2)
/// are swept one after the other, points of one colour in parallel (they share no cell), so the
/// result does not depend on the thread count.
///
/// Where the paint has edges (docs/error_model.md §12), the mean over directions is replaced by the paint's own
/// edge directions where it has edges, |J⁻ᵀ|²_T = tr(T·J⁻¹J⁻ᵀ) with T the cell's direction tensor
/// blended with I/2 (PolishFields::txx, add_edge_directions(), ErrorPolishOptions::isotropy), so
/// texels get fine across edges and may stretch along them; the flow's lattice is polished through a
/// coarser one (polish_warp(), ErrorPolishOptions::cells); and every chart's lattice is polished.
#include <vector>

#include "adaptex/adapt/grid.h"
#include "adaptex/core/image.h"
#include "adaptex/core/progress.h"

namespace adaptex {

/// Settings of polish_warp_by_error(). Why each default: docs/decisions.md ("The flow lattice is
/// polished by the anisotropic error model", "A three-level coarse-to-fine polish", "settle_cells",
/// "Warm start of the polish: off").
struct ErrorPolishOptions {
  int sweeps = 20;  ///< Gauss–Seidel sweeps over the lattice (0: no polish).
  /// Coarse to fine: where the polish lattice has at least 32 cells, first this many sweeps on a
  /// lattice of 2^-prepass_levels as many cells, then sweeps_after_prepass on each finer one (0: none).
  int prepass_sweeps = 20;
  int sweeps_after_prepass = 3;  ///< Sweeps on each finer level after the prepass's coarsest.
  int prepass_levels = 2;        ///< Coarser levels of the prepass, each halving the cells (≥ 16), in [1, 4].
  /// Sweeps on the full lattice, without a prepass, when the polish starts from the previous cycle's
  /// (add_polish_correction(); PaintSessionOptions::warm_start).
  int warm_sweeps = 5;
  double tolerance = 1e-4;     ///< Stop when a sweep lowers E by less than this fraction of E.
  double floor_weight = 10.0;  ///< κ of the floor term, relative to the mean q of the painted cells.
  /// Weight μ, relative to the mean q of the painted cells, of a shape term μ·|J|²_F / (2 det J) in
  /// every cell: keeps the unpainted cells from taking the compression in cracks of extreme shear.
  double shape_weight = 0.01;
  /// Only points within this many cells of a painted cell move (polish_warp() scales it).
  int reach_cells = 12;
  bool charts = true;  ///< Also polish the per-chart lattices of a re-packed atlas (atlas_flow.h).
  /// A point is relaxed again only if it or a neighbour moved by more than this many lattice cells in
  /// the sweep before (0: every point in every sweep).
  double settle_cells = 1e-3;
  /// ω of the Newton step (over-relaxation; the line search still only accepts a lower energy), in (0, 2).
  double over_relaxation = 1.8;
  /// Cells per side of the square of the lattice the polish runs on (polish_cells(), polish_warp()):
  /// a finer warp lattice is sampled there, polished, and follows. 0: the warp's own lattice.
  int cells = 128;
  /// Weight of the isotropic model against the paint's own edge directions (add_edge_directions()),
  /// in (0, 1]: 1 makes texels round, lower values let them stretch along the paint's edges.
  double isotropy = 0.25;
  bool parallel = true;  ///< Sweep points and charts' lattices with TBB (the same result either way).
  ProgressCallback progress;  ///< Called with ("polish", sweeps done / sweeps) after every sweep.
};

/// \throw InvalidInputError an option outside its range (sweeps, tolerance, weights, reach or cells
///        < 0, over_relaxation outside (0, 2), isotropy outside (0, 1])
void check_polish_options(const ErrorPolishOptions& options);

/// What polish_warp_by_error() did.
struct ErrorPolishStats {
  int sweeps = 0;             ///< Sweeps run.
  double energy_before = 0;   ///< E before (error part and floor part).
  double energy_after = 0;    ///< E after.
  /// The model's error part (Σ q·Ψ) before and after: 10·log10 of their ratio is the polish's gain
  /// as the anisotropic model sees it.
  double error_before = 0, error_after = 0;
  /// polish_warp() through a coarser lattice: the fraction of the interpolated displacement the warp
  /// took (1; halved until no cell of the warp that was convex stops being convex, 0: none).
  double transfer_scale = 1;
  /// polish_warp() through a coarser lattice: cells of the warp that the full motion made non-convex
  /// (then untangled, or the motion halved).
  int turned_cells = 0;
};

/// The error fields of one lattice: per lattice cell, in the lattice's local coordinates.
struct PolishFields {
  ImageF error;     ///< n x n, >= 0: the model's q (0 where unpainted), any common scale.
  ImageF exponent;  ///< n x n: p where error > 0.
  ImageF floor;     ///< n x n: least area density (cell area × n²) of unpainted cells; 0: none.
  /// Width / height of the rectangle the lattice covers in uv: texels are round in uv, not in the
  /// lattice's local coordinates.
  double aspect = 1;
  /// n x n each, or all empty: the paint's edge-direction tensor T per cell (symmetric, positive
  /// definite, trace 1, in uv; add_edge_directions()). The error term then measures the texel spacing
  /// across the edges, |J⁻ᵀ|²_T = tr(T·J⁻¹J⁻ᵀ), instead of its mean over all directions (T = I/2), so
  /// texels may stretch along an edge. Empty: T = I/2.
  ImageF txx, txy, tyy;
};

/// The paint's edge directions per texel of a texture: the structure tensor Σ g gᵀ of its colour
/// gradient g (central differences per texel, summed over R, G and B; one-sided at the borders).
struct EdgeTensor {
  ImageF xx, xy, yy;  ///< W x H each.
  /// Summed-area tables of xx, xy, yy ((W+1) x (H+1), row-major, entry (x, y) = the sum over texels
  /// [0, x) x [0, y)), built once by edge_tensor(): add_edge_directions() runs once per chart lattice.
  std::vector<double> sum_xx, sum_xy, sum_yy;
};

/// \pre texture not empty \throw InvalidInputError it is empty
EdgeTensor edge_tensor(const ImageRGBA8& texture);

/// Sets \p fields' txx, txy, tyy (n x n, n = fields.error's size) for a lattice over [lo, hi]: per
/// cell, \p edges summed over the texels of the cell and of the ring of cells around it (a box three
/// cells wide), normalized to trace 1 and blended with the isotropic tensor:
/// T = (1 − isotropy)·T_edges + isotropy·I/2 (I/2 where the sum is 0).
/// \pre isotropy in (0, 1]; lo < hi inside [0,1]²; fields.error n x n, n >= 1; \p edges from
///      edge_tensor() (three rasters of one non-empty size and their tables)
/// \throw InvalidInputError a precondition fails
void add_edge_directions(PolishFields& fields, const EdgeTensor& edges, const Vec2& lo, const Vec2& hi,
                         double isotropy);

/// \p error, \p exponent and \p density of error_density.h (L x L over the square) sampled on an
/// n x n lattice over the rectangle [lo, hi] of the square: error bilinearly, exponent as the
/// error-weighted mean of the same taps, floor = the density normalized to mean 1 over the rectangle
/// where the sampled error is 0; aspect = the rectangle's. \p scale: the chart's scale when it was
/// re-packed (atlas_flow.h, ChartMove::scale): its texel spacing is h_N / scale, so the error there
/// is q·scale^(−p), which changes the weight of smooth cells (p = 4) against edges (p = 1).
/// \pre error, exponent, density L x L, L >= 1; n >= 1; lo < hi inside [0,1]²; scale > 0
/// \throw InvalidInputError a precondition fails
PolishFields polish_fields(const ImageF& error, const ImageF& exponent, const ImageF& density, const Vec2& lo,
                           const Vec2& hi, int n, double scale = 1);

/// Moves the points of \p warp (in its local coordinates) to lower E above. Every cell that was convex
/// stays convex; side points stay on their side and corners stay.
/// \pre fields' rasters are warp.n x warp.n; every cell of warp convex (density_equalizing_warp()
///      guarantees it); exponent in [0, 8]
/// \throw InvalidInputError a precondition fails or check_polish_options() does
/// \throw CancelledError options.progress returned false
ErrorPolishStats polish_warp_by_error(GridWarp& warp, const PolishFields& fields,
                                      const ErrorPolishOptions& options = {});

/// Warm start of a polish: \p warp, a flow lattice of this cycle, takes the
/// correction the polish made to the previous cycle's flow lattice, t·(prev_polished − prev_flow), in
/// the lattices' local coordinates: at point (i, j) of \p warp, the difference of the previous
/// lattices' maps (GridWarp::apply_lattice) at (i/n, j/n), so a lattice of another size gets the
/// correction resampled (a chart's lattice size follows its re-packed rectangle, atlas_flow.h). A
/// stroke changes the target density only near it, so elsewhere this cycle's flow is close to the
/// previous one and the correction still fits; the polish then needs ErrorPolishOptions::warm_sweeps
/// instead of its prepass and sweeps. Cells of \p warp that were convex and are not are untangled as in
/// polish_warp() when there are at most 32 of them; t = 1, halved (at most 3 times) while some stay
/// turned. Side points keep their side coordinate, corners stay.
/// \return t in (0, 1] if the correction was added; 0 if a lattice is empty or malformed, the previous
///         two differ in size, or no t kept every convex cell convex (\p warp is then unchanged)
double add_polish_correction(GridWarp& warp, const GridWarp& prev_flow, const GridWarp& prev_polished);

/// The model's error part Σ q·Ψ of \p warp under \p fields and options' shape and floor weights
/// (ErrorPolishStats::error_before of a polish without sweeps): what polish_warp() lowers, measured on
/// the warp's own lattice.
/// \pre as polish_warp_by_error() \throw InvalidInputError a precondition fails
double polish_model_error(const GridWarp& warp, const PolishFields& fields, const ErrorPolishOptions& options = {});

/// The cells per side of the lattice polish_warp() runs on for a warp of \p warp_cells cells whose
/// longer side is \p extent of the unit square's (1: the whole square; a chart's rectangle after
/// the re-pack, atlas_flow.h): ErrorPolishOptions::cells per side of the square, so
/// min(warp_cells, max(4, round(options.cells · extent))); warp_cells when options.cells is 0.
/// \pre warp_cells >= 1, extent in (0, 1] \throw InvalidInputError a precondition fails, or options.cells < 0
int polish_cells(int warp_cells, const ErrorPolishOptions& options, double extent = 1);

/// The polish of \p warp through a lattice of m cells, 1 <= m <= warp.n: the size of \p fields
/// (polish_cells() gives the one ErrorPolishOptions::cells asks for). m = warp.n is
/// polish_warp_by_error() itself. Otherwise the m-cell
/// lattice takes the warp's positions at its points (GridWarp::apply_lattice), is polished by
/// polish_warp_by_error() with \p fields (reach_cells scaled by m / n), and every point of \p warp
/// moves by the map of the polished points composed with the inverse of their map before the polish (bilinear per
/// coarse cell): points move by where they are, not by their index, so the warp's own fine structure
/// moves with them. Side points stay on their side and corners stay. Cells of \p warp that this
/// makes non-convex (ErrorPolishStats::turned_cells; a few, where the warp's cells are far smaller
/// than the coarse lattice's) are untangled by Laplacian smoothing of their corners; if some stay
/// turned, the motion is halved until none does (ErrorPolishStats::transfer_scale; at most 6
/// halvings, then none). Every cell of \p warp that was convex stays convex.
/// The returned energies and errors are those of the m-cell lattice (polish_model_error() measures the
/// warp's own).
/// \pre fields' rasters are m x m, 1 <= m <= warp.n; warp.n >= 1 and (n+1)² points; the rest as
///      polish_warp_by_error()
/// \throw InvalidInputError a precondition fails or check_polish_options() does
/// \throw CancelledError options.progress returned false
ErrorPolishStats polish_warp(GridWarp& warp, const PolishFields& fields, const ErrorPolishOptions& options = {});

}  // namespace adaptex
