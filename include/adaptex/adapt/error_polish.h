#pragma once
/// \file error_polish.h
/// Polish of a warp lattice by the error model with the texels' anisotropy and the paint's edge
/// directions T counted: minimizes Σ q_c·mean(tr(T·J⁻¹J⁻ᵀ))^(p_c/2) + κ·Σ_unpainted max(0, ρ_floor/det J − 1)²
/// by coloured Gauss–Seidel Newton steps that keep cells convex. docs/error_model.md §11–12.
#include <vector>

#include "adaptex/adapt/grid.h"
#include "adaptex/core/image.h"
#include "adaptex/core/progress.h"

namespace adaptex {

/// Settings of polish_warp_by_error() (docs/decisions.md: why each default).
struct ErrorPolishOptions {
  int sweeps = 20;               ///< Gauss–Seidel sweeps over the lattice (0: no polish); 20.
  int prepass_sweeps = 20;       ///< Lattices ≥ 32 cells: sweeps on the coarsest prepass level (0: none); 20.
  int sweeps_after_prepass = 3;  ///< Sweeps on each finer level after the prepass's coarsest; 3.
  int prepass_levels = 2;        ///< Coarser levels of the prepass, each halving the cells (≥ 16), in [1, 4]; 2.
  double tolerance = 1e-4;       ///< Stop when a sweep lowers E by less than this fraction of E; 1e-4.
  double floor_weight = 10.0;    ///< κ of the floor term, relative to the painted cells' mean q; 10.
  double shape_weight = 0.01;    ///< μ of a shape term μ·|J|²_F / (2 det J) in every cell (vs. shear); 0.01.
  int reach_cells = 12;          ///< Only points this many cells from a painted cell move; 12.
  bool charts = true;            ///< Also polish the per-chart lattices of a re-packed atlas; true.
  double over_relaxation = 1.8;  ///< ω of the Newton step, in (0, 2); 1.8.
  int cells = 128;               ///< Cells per side of the square of the polish lattice (0: the warp's); 128.
  double isotropy = 0.25;        ///< Weight of round texels against the paint's edge directions, in (0, 1]; 0.25.
  bool parallel = true;          ///< Sweep with TBB (the same result either way); true.
  ProgressCallback progress;     ///< ("polish", sweeps done / sweeps) after every sweep.
};

/// \throw InvalidInputError an option outside its range (sweeps, tolerance, weights, reach or cells
///        < 0, over_relaxation outside (0, 2), isotropy outside (0, 1])
void check_polish_options(const ErrorPolishOptions& options);

/// What polish_warp_by_error() did.
struct ErrorPolishStats {
  int sweeps = 0;             ///< Sweeps run.
  double energy_before = 0;   ///< E before (error part and floor part).
  double energy_after = 0;    ///< E after.
  double error_before = 0, error_after = 0;  ///< The error part Σ q·Ψ before / after (gain = 10·log10 ratio).
  double transfer_scale = 1;  ///< polish_warp() via a coarser lattice: share of the motion taken (halved on turns).
  int turned_cells = 0;       ///< polish_warp() via a coarser lattice: warp cells the full motion turned.
};

/// The error fields of one lattice: per lattice cell, in the lattice's local coordinates.
struct PolishFields {
  ImageF error;     ///< n x n, >= 0: the model's q (0 where unpainted), any common scale.
  ImageF exponent;  ///< n x n: p where error > 0.
  ImageF floor;     ///< n x n: least area density (cell area × n²) of unpainted cells; 0: none.
  double aspect = 1;  ///< Width / height in uv of the lattice's rectangle (texels are round in uv).
  ImageF txx, txy, tyy;  ///< n x n or empty (T = I/2): edge-direction tensor T per cell (add_edge_directions()).
};

/// The paint's edge directions per texel: the structure tensor Σ g gᵀ of the RGB gradients.
struct EdgeTensor {
  ImageF xx, xy, yy;  ///< W x H each.
  std::vector<double> sum_xx, sum_xy, sum_yy;  ///< (W+1) x (H+1) summed-area tables of xx, xy, yy.
};

/// \pre texture not empty \throw InvalidInputError it is empty
EdgeTensor edge_tensor(const ImageRGBA8& texture);

/// The same into \p out, reusing its storage: a session's cycles then write the same pages again
/// instead of taking fresh ones from the kernel (docs/benchmarks.md, "the four-channel cycle").
/// \pre texture not empty \throw InvalidInputError it is empty
void edge_tensor(const ImageRGBA8& texture, EdgeTensor& out);

/// Sets \p fields' txx, txy, tyy for a lattice over [lo, hi]: \p edges summed over each cell and its
/// ring, normalized to trace 1, T = (1 − isotropy)·T_edges + isotropy·I/2 (I/2 where the sum is 0).
/// \pre isotropy in (0, 1]; lo < hi in [0,1]²; \p edges from edge_tensor() \throw InvalidInputError otherwise
void add_edge_directions(PolishFields& fields, const EdgeTensor& edges, const Vec2& lo, const Vec2& hi,
                         double isotropy);

/// error_density.h's \p error, \p exponent, \p density (L x L) sampled on an n x n lattice over [lo, hi];
/// \p scale: the chart's re-pack scale (ChartMove::scale; the error there is q·scale^(−p)).
/// \pre rasters L x L, n >= 1, lo < hi in [0,1]², scale > 0 \throw InvalidInputError otherwise
PolishFields polish_fields(const ImageF& error, const ImageF& exponent, const ImageF& density, const Vec2& lo,
                           const Vec2& hi, int n, double scale = 1);

/// Moves \p warp's points to lower E; convex cells stay convex, side points on their side.
/// \pre fields warp.n x warp.n, every cell convex, exponent in [0, 8] \throw InvalidInputError otherwise
/// \throw CancelledError options.progress returned false
ErrorPolishStats polish_warp_by_error(GridWarp& warp, const PolishFields& fields,
                                      const ErrorPolishOptions& options = {});

/// The model's error part Σ q·Ψ of \p warp under \p fields (what polish_warp() lowers).
/// \pre as polish_warp_by_error() \throw InvalidInputError a precondition fails
double polish_model_error(const GridWarp& warp, const PolishFields& fields, const ErrorPolishOptions& options = {});

/// Cells of polish_warp()'s lattice for a warp of \p warp_cells cells spanning \p extent of the square:
/// min(warp_cells, max(4, round(options.cells · extent))); warp_cells when options.cells is 0.
/// \pre warp_cells >= 1, extent in (0, 1] \throw InvalidInputError a precondition fails, or options.cells < 0
int polish_cells(int warp_cells, const ErrorPolishOptions& options, double extent = 1);

/// The polish of \p warp through an m-cell lattice (m = fields' size) that \p warp's points follow;
/// convex cells stay convex. Energies returned are the m-cell lattice's.
/// \pre fields m x m, 1 <= m <= warp.n; as polish_warp_by_error() \throw InvalidInputError otherwise
/// \throw CancelledError options.progress returned false
ErrorPolishStats polish_warp(GridWarp& warp, const PolishFields& fields, const ErrorPolishOptions& options = {});

}  // namespace adaptex
