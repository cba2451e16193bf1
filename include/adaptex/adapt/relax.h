#pragma once
/// \file relax.h
/// Iterative grid optimization of thesis §3.7.1: every interior point of the uniform grid G is moved,
/// in turn (Gauss–Seidel), to the L_s²-weighted average of its 1-ring,
///     Ñ_i = Σ_{N' ∈ ring(N_i)} L_s²(N') N' / Σ L_s²(N'),
/// with L_s² sampled at the points' *current* positions, until the largest move is below ε.
/// Points gather where L_s² is high (low signal) and spread where it is low (high signal), so after
/// the remap (§3.7.2) high-signal content receives more texels. Boundary points stay fixed.
/// Parallel red–black (4-ring) / four-colour (8-ring) ordering: still Gauss–Seidel (each point sees
/// the newest positions of its neighbours) and deterministic. See docs/adaptive.md.
#include "adaptex/adapt/grid.h"
#include "adaptex/core/image.h"
#include "adaptex/core/progress.h"

namespace adaptex {

/// Neighbourhood of a grid point used by the relaxation.
enum class GridRing {
  Four,   ///< Left, right, down, up.
  Eight,  ///< The 8 surrounding points (the 1-ring of the quad grid's vertex), all weighted alike.
};

/// Settings of relax_grid().
struct RelaxOptions {
  GridRing ring = GridRing::Eight;  ///< 1-ring used for the weighted average (docs/adaptive.md).
  double epsilon = 1e-4;            ///< Stop when the largest move of a sweep is below this (uv units).
  int max_iterations = 200;         ///< Cap on the number of sweeps.
  bool parallel = true;             ///< Use TBB for grids with many points (results are identical).
  /// Let the non-corner boundary points slide along their side of the square (weighted average of
  /// their ring projected on the side, kept between their side neighbours). Corners stay fixed.
  bool slide_boundary = false;
  ProgressCallback progress;        ///< Phase "relax", called every few sweeps; false cancels.
};

/// What relax_grid() did.
struct RelaxStats {
  int iterations = 0;        ///< Sweeps performed.
  double last_max_move = 0;  ///< Largest point move of the last sweep (uv units).
  bool converged = false;    ///< last_max_move < epsilon.
};

/// Relaxes \p grid in place against the weight field \p weights (L_s², strictly positive; the image
/// covers [0,1]^2 and is sampled bilinearly with clamp-to-edge at the points' current positions).
/// \pre weights non-empty with values > 0; grid.n >= 1
/// \throw InvalidInputError empty weight field or grid
/// \throw CancelledError the progress callback returned false
RelaxStats relax_grid(GridWarp& grid, const ImageF& weights, const RelaxOptions& options = {});

}  // namespace adaptex
