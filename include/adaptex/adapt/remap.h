#pragma once
/// \file remap.h
/// Re-parameterization by the optimized grid (thesis §3.7.2): every wedge's new UV is the bilinear
/// interpolation, in its uniform-grid cell, of the cell's four optimized corners; two-stage warps are
/// applied in order (fine ∘ coarse). The warp is continuous and keeps [0,1]^2, but the mesh is
/// piecewise linear, so a strong warp could still flip a UV triangle or make two triangles overlap.
/// safe_remap() guarantees neither happens: it checks the result and, if needed, damps the warps
/// toward the identity (bisection on the blend factor t, t = 1 full warp, t = 0 the input itself).
#include <vector>

#include "adaptex/adapt/grid.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"

namespace adaptex {

/// New parameterization: param with every wedge mapped through \p warps in order (warps[0] first),
/// clamped to [0,1]^2. Parallel over wedges. Charts, faces and wedge_vertex are kept.
Parameterization remap_parameterization(const Parameterization& param,
                                        const std::vector<const GridWarp*>& warps);

/// Validity of a remapped parameterization relative to its input.
struct RemapCheck {
  int flipped = 0;      ///< Faces valid in the input, with negative UV area now.
  int degenerate = 0;   ///< Faces valid in the input, with UV area <= min_area now.
  long overlaps = 0;    ///< Overlapping UV triangle pairs beyond those of the input (0 if not checked).
  bool ok() const { return flipped == 0 && degenerate == 0 && overlaps == 0; }
};

/// Settings of safe_remap().
struct SafeRemapOptions {
  /// A UV triangle with signed area <= this (in [0,1]^2 units) counts as degenerate. 1e-12 is a
  /// triangle about 10^-6 of the square wide: far below a texel but above round-off.
  double min_area = 1e-12;
  /// Check for overlapping triangles (count_overlapping_triangles) as well; only pairs that were not
  /// already overlapping in the input count. Costs O(F log F).
  bool check_overlaps = true;
  int bisection_steps = 10;  ///< Bisection steps on t when the full warp is invalid (precision 2^-steps).
};

/// Result of safe_remap().
struct SafeRemapResult {
  Parameterization param;  ///< The accepted (possibly damped) parameterization.
  double damping = 1.0;    ///< Blend factor t applied: 1 = full warp, 0 = unchanged input.
  int checks = 0;          ///< Number of candidate warps checked.
  RemapCheck check;        ///< Check of the returned parameterization (always ok()).
};

/// Checks \p after against \p before (same faces).
RemapCheck check_remap(const Parameterization& before, const Parameterization& after,
                       const SafeRemapOptions& options = {});

/// Remaps \p param through \p warps, damping them (each blended toward the identity with the same t)
/// until no face flips, degenerates or overlaps. Never returns an invalid layout: t = 0 is the input.
/// \pre every warp's points are inside [0,1]^2
SafeRemapResult safe_remap(const Parameterization& param, const std::vector<const GridWarp*>& warps,
                           const SafeRemapOptions& options = {});

}  // namespace adaptex
