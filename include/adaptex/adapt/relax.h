#pragma once
/// \file relax.h
/// Grid relaxation of thesis §3.7.1: points move to the L_s²-weighted mean of their ring (Gauss–Seidel).
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
  /// Non-corner boundary points slide along their side (between their side neighbours).
  bool slide_boundary = false;
  ProgressCallback progress;        ///< Phase "relax", called every few sweeps; false cancels.
};

/// What relax_grid() did.
struct RelaxStats {
  int iterations = 0;        ///< Sweeps performed.
  double last_max_move = 0;  ///< Largest point move of the last sweep (uv units).
  bool converged = false;    ///< last_max_move < epsilon.
};

/// Relaxes \p grid in place against \p weights (L_s² > 0 over [0,1]², sampled bilinearly).
/// \pre weights > 0; grid.n >= 1 \throw InvalidInputError empty weight field or grid
/// \throw CancelledError the progress callback returned false
RelaxStats relax_grid(GridWarp& grid, const ImageF& weights, const RelaxOptions& options = {});

}  // namespace adaptex
