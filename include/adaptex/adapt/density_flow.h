#pragma once
/// \file density_flow.h
/// Flow-based density-equalizing map of the unit square (Gastner, Seguy & More, "Fast flow-based
/// algorithm for creating density-equalizing map projections", PNAS 115(10), 2018).
///
/// Given a density ρ₀ > 0 on an L x L cell raster of [0,1]² (mean ρ̄), the map X: [0,1]² → [0,1]²
/// has Jacobian determinant det ∇X(x) = ρ₀(x) / ρ̄: a cell of density 4ρ̄ becomes 4 times larger.
/// Construction: ρ_t = (1 − t)ρ₀ + tρ̄ for t ∈ [0,1]; the flux J = −∇φ with ∇²φ = ρ̄ − ρ₀ and zero
/// normal flux on the sides (one DCT Poisson solve, FFTW REDFT10/REDFT01) satisfies ∂ρ_t/∂t + ∇·J = 0,
/// so advecting points with v(x, t) = J(x) / ρ_t(x) from t = 0 to 1 pushes ρ₀ forward to ρ̄.
/// The flow of a smooth velocity field is a diffeomorphism: the map cannot fold, and because the
/// normal velocity vanishes on the sides, boundary points slide along their side and corners stay.
///
/// The result is a GridWarp (grid.h): the advected (n+1)² lattice points; GridWarp::apply then
/// interpolates the map bilinearly between them, which is how remap.h consumes every warp. Where the
/// flow bends a cell so much that the quad of its advected corners is not convex (sharp density
/// contrast at the scale of one cell), the lattice is untangled locally by Laplacian smoothing, so
/// that every cell is convex and the bilinear warp is one-to-one.
#include "adaptex/adapt/grid.h"
#include "adaptex/core/image.h"

namespace adaptex {

/// Settings of density_equalizing_warp().
struct DensityFlowOptions {
  /// Cells per side n of the output GridWarp (lattice of (n+1)² points). 128 against 256 on the
  /// default 256² density raster (4 shared meshes × lines/dots/mixed × 128²/256², 24 cases): median
  /// texel saving 4.06 / 3.41 / 4.12 against 3.95 / 3.24 / 3.99, a third less flow time (docs/quality.md).
  int cells = 128;
  double tolerance = 1e-2;     ///< Local error bound of the adaptive integration, in output cells.
  int max_steps = 4000;        ///< Cap on integration steps per point (never reached on sane input).
  /// Longest move of a point in one integration step, in cells of the output lattice (the step-size
  /// control adds its own limit). Session 4 measured it in cells of the finer of the density raster
  /// and the lattice (2: a quarter of the steps of 0.5 at the same density error); session 5 counts
  /// lattice cells, which on the default 128-cell lattice over a 256² density doubles the step of a
  /// one-chart flow (venus lines 256²: 703k -> 403k steps, density error 0.175 -> 0.184; the texel
  /// saving within noise, docs/benchmarks.md). Per-chart flows were already counted this way.
  double max_step_cells = 2.0;
  bool parallel = true;        ///< Advect points with TBB (results are identical either way).
};

/// What density_equalizing_warp() did.
struct DensityFlowStats {
  long total_steps = 0;        ///< Accepted integration steps over all points.
  int max_steps = 0;           ///< Most steps any point took.
  double max_displacement = 0; ///< Largest point displacement (uv units).
  /// Cells of the advected lattice whose corner quad was not convex (the flow bends or shears faster
  /// than one cell); they and their neighbours were Laplacian-smoothed until every cell was convex.
  int tangled_cells = 0;
  int inverted_cells = 0;      ///< Cells still not convex after that (0: the bilinear warp is one-to-one).
  /// Relative L1 error of the achieved cell areas against ρ₀/ρ̄, sampled on the output lattice
  /// (Σ |area·n² − ρ₀/ρ̄| / n²): how exactly the map reached the density.
  double density_error = 0;
};

/// The density-equalizing map of \p density (L x L, any L >= 2; rows are v, as images are).
/// \pre density.width == density.height >= 2, every value finite and > 0; options.cells >= 1
/// \throw InvalidInputError a precondition fails
GridWarp density_equalizing_warp(const ImageF& density, const DensityFlowOptions& options = {},
                                 DensityFlowStats* stats = nullptr);

}  // namespace adaptex
