#pragma once
/// \file error_polish.h
/// Polishing a warp lattice by the error model itself, with the texel grid's anisotropy counted
/// (`--adapt density-flow`, after the flow; derivation and measurements in docs/error_model.md §11, §12).
///
/// The density-equalizing flow (density_flow.h) reaches a target *area* density: it controls only
/// det J of the warp's Jacobian J. Around a painted dot the flow magnifies radially less than
/// tangentially wherever the target density varies, and the dot's edge lies exactly there: measured on
/// the lattice of venus `dots` at 256², the worse direction's texel density gains 0.4–1.3 dB less than
/// the area density (docs/quality.md, session 12). Error model with direction: an edge of unit normal
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
/// Session 14 (docs/error_model.md §12): the mean over directions is replaced by the paint's own
/// edge directions where it has edges, |J⁻ᵀ|²_T = tr(T·J⁻¹J⁻ᵀ) with T the cell's direction tensor
/// blended with I/2 (PolishFields::txx, add_edge_directions(), ErrorPolishOptions::isotropy), so
/// texels get fine across edges and may stretch along them; the flow's lattice is polished through a
/// coarser one (polish_warp(), ErrorPolishOptions::cells); and every chart's lattice is polished.
#include <vector>

#include "adaptex/adapt/grid.h"
#include "adaptex/core/image.h"
#include "adaptex/core/progress.h"

namespace adaptex {

/// Settings of polish_warp_by_error().
struct ErrorPolishOptions {
  /// Gauss–Seidel sweeps over the lattice (0: no polish). 20 with ω = 1.8: on the 4 one-chart shared
  /// meshes × lines / dots / mixed × 128² / 256² (2M samples) against no polish, mean +0.47 / +0.90 /
  /// +0.85 dB; 10 sweeps gave +0.42 / +0.73 / +0.72, 40 gave +0.47 / +0.97 / +0.81, ω = 1 with 30
  /// sweeps +0.38 / +0.77 / +0.74 (docs/quality.md, session 13, on the 256-cell lattice). Through the
  /// 128-cell lattice with the edge directions (session 14), 10 sweeps against 20: −0.07 / −0.10 /
  /// −0.26 dB on those meshes, −0.02 / +0.02 / −0.01 dB on the 5 multi-chart shared meshes.
  int sweeps = 20;
  /// Coarse-to-fine (the warp method's polish, warp_density_flow.cpp): where the polish lattice has
  /// at least 32 cells, first prepass_sweeps sweeps on a coarser lattice (half as many cells, or fewer:
  /// prepass_levels), then sweeps_after_prepass (instead of sweeps) on each finer one. Plain Gauss–Seidel leaves the slow,
  /// global modes of the warp unconverged (on venus `mixed` 256² the energy still fell 0.4 % per
  /// sweep at sweep 20); the half lattice moves them at a quarter of the cost per sweep. Session 15,
  /// against 20 sweeps on the full lattice (mean dB per case, lines / dots / mixed / blobs): the
  /// 9-mesh study (128²–512², seed 1) −0.03 / +0.00 / +0.14; out of sample (13 meshes, seed 3)
  /// +0.04 / +0.01 / +0.19 / +0.38; the polish 0.67× the time (docs/quality.md, "Session 15").
  /// 20 + 10 gave −0.02 / −0.05 / +0.20 on 6 meshes at 256². 0: no prepass.
  int prepass_sweeps = 20;
  /// Sweeps on each finer level after the prepass's coarsest (see prepass_sweeps, prepass_levels). 3
  /// since session 21 (5 before), with prepass_levels 2.
  int sweeps_after_prepass = 3;
  /// Coarser lattices of the prepass (with prepass_sweeps > 0): 1, the half lattice only; 2, a quarter
  /// of the cells first (prepass_sweeps), then the half (sweeps_after_prepass), then the full
  /// (sweeps_after_prepass); and so on, each level halving the cells, as long as the coarsest has at
  /// least 16 cells. In [1, 4]. Session 21: 2 levels with 3 sweeps after the prepass (20 + 3 + 3)
  /// against session 15's 1 level with 5 (20 + 5), mean dB per case (lines / dots / mixed / blobs):
  /// the 9-mesh study (128²–512², 2M samples) −0.03 / −0.00 / +0.00; 6 meshes at 256²–1024² −0.03 /
  /// +0.06 / −0.02; out of sample (11 meshes, seed 3, 128²–512²) −0.09 / +0.01 / +0.07 / +0.10; the
  /// polish 0.66–0.78× the time, the whole re-parameterization about 0.9× (docs/quality.md, "Session
  /// 21"). 3 levels gained no time; 2 levels with 2 sweeps lost 0.10 / 0.13 dB on lines / mixed.
  int prepass_levels = 2;
  /// Sweeps on the full lattice, without a prepass, when the polish starts from the previous cycle's
  /// polish (add_polish_correction(); a painting session's cycle after a stroke, warm_start in
  /// adapt_parameterization()). The hope was that the previous correction holds the slow modes the
  /// prepass is for. On one dot that moved (test_error_polish.cpp) 5 warm sweeps reach 0.02 dB of 30
  /// cold ones, but in real sessions they do not: PaintSessionOptions::warm_start is off by default.
  int warm_sweeps = 5;
  /// Stop early when a sweep lowers E by less than this fraction of E.
  double tolerance = 1e-4;
  /// κ of the floor term, relative to the mean q of the painted cells.
  double floor_weight = 10.0;
  /// Weight μ, relative to the mean q of the painted cells, of a shape term μ·|J|²_F / (2 det J) in every
  /// cell (≥ 1, 1 for a round texel at any size). Without it the unpainted cells, which only have the
  /// floor on their area, took the compression in one-cell-wide cracks of extreme shear. 0.01: on the
  /// 4 one-chart shared meshes × lines / dots / mixed × 128² / 256² −0.06 / +0.02 / +0.01 dB against 0,
  /// out of sample (seed 3, 6 meshes) +0.01 / +0.06 / +0.05 dB, and a third fewer refined faces.
  double shape_weight = 0.01;
  /// Only points within this many cells of the warp's lattice of a painted cell move (elsewhere E has
  /// no gradient except through the floor, which the flow already meets); polish_warp() scales it to
  /// its coarser lattice.
  int reach_cells = 12;
  /// Also polish the per-chart lattices of a re-packed atlas (atlas_flow.h). Session 13 left it off:
  /// with round texels (isotropy 1) the polished chart lattices lost 0.1–0.4 dB on `lines` and `mixed`
  /// (dino, bunny, spot, triceratops at 128² / 256²). With the edges' directions (isotropy below) they
  /// gain: docs/error_model.md §12.
  bool charts = true;
  /// A point is relaxed again only if it or a neighbour moved by more than this many lattice cells in
  /// the sweep before (0: every point in every sweep). At 1e-3 nearly every point is relaxed in every
  /// sweep. 0.05 took 40 % off the polish of `mixed` (venus, camelhead 256²) and was neutral on the 4
  /// one-chart meshes (+0.00 / +0.01 / +0.02 dB) but cost −0.01 / −0.08 / −0.05 dB out of sample
  /// (seed 3, 6 meshes): not adopted.
  double settle_cells = 1e-3;
  /// ω of the Newton step (over-relaxation; the line search still only accepts a lower energy), in
  /// (0, 2). 1.8: the model's gain after 10 sweeps as after 30 at ω = 1 (venus, spot, kitten,
  /// camelhead dots 256²).
  double over_relaxation = 1.8;
  /// Cells per side of the unit square of the lattice the polish runs on (polish_cells(),
  /// polish_warp(); a chart's lattice gets as many per side of the square): a finer warp lattice is
  /// sampled at this lattice's points, which are polished, and the warp's points follow them.
  /// 0: the warp's own lattice. 128 on the flow's
  /// 256-cell lattice: a quarter of the points and of the time (venus `mixed` 256²: 320 → 80 ms), and
  /// against polishing the 256 cells themselves, on the 4 one-chart shared meshes × lines / dots /
  /// mixed, mean +0.02 / +0.03 / +0.07 dB at 128² / 256² and +0.08 / +0.05 / +0.26 dB at 512² / 1024²
  /// (2M samples); 64 cells lost 0.09–0.11 dB (docs/error_model.md §12).
  int cells = 128;
  /// Weight of the isotropic model against the paint's own edge directions (PolishFields::txx;
  /// add_edge_directions()), in (0, 1]: 1 measures the texel spacing in every direction alike (texels
  /// become round), lower values let texels stretch along the paint's edges.
  double isotropy = 0.25;
  /// Sweep a colour's points with TBB, and (the warp method's polish) polish the charts' lattices in
  /// parallel; the same result either way.
  bool parallel = true;
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

/// Warm start of a polish (issue 10, deliverable 2): \p warp, a flow lattice of this cycle, takes the
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
