#pragma once
/// \file remap.h
/// Re-parameterization through a warp (thesis §3.7.2): every wedge moves by the warp (bilinear per
/// lattice cell; warps in order). safe_remap() guarantees no flipped, degenerate or overlapping
/// triangle: it untangles failing wedges, damps them locally (halved round after round), and only then
/// damps the whole warp, new uv = old + t·(warped − old), t by bisection (t = 0: the input).
#include <vector>

#include "adaptex/adapt/grid.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"

namespace adaptex {

/// \p param with every wedge mapped through \p warps in order, clamped to [0,1]²; topology kept.
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
  double min_area = 1e-12;             ///< A UV triangle with signed area ≤ this counts as degenerate; 1e-12.
  bool check_overlaps = true;          ///< Also forbid new overlapping pairs (certificate first, then counted); true.
  bool damp_overlaps = true;           ///< Damp the faces of new overlapping pairs locally, like failing faces; true.
  int max_local_rounds = 24;           ///< Local damping rounds before the whole warp is damped; 24.
  int snap_round = 12;                 ///< From this local round, failing wedges snap back (< 0: never); 12.
  int extended_local_rounds = 100;     ///< If the global blend is needed, local damping also tried this long; 100.
  bool smooth_local_damping = false;   ///< Damp to half the 1-ring's mean displacement instead of halving; false.
  int chart_halvings = 0;              ///< Halvings of a failing chart's displacement before the global blend; 0.
  int bisection_steps = 10;            ///< Bisection steps on the global t; 10.
  int untangle_rounds = 500;           ///< Untangling rounds before any damping (0: damp only); 500.
  int untangle_patience = 200;         ///< Past untangle_rounds, go on while failures fell within this many; 200.
  int untangle_max_rounds = 2000;      ///< Hard cap of the untangling rounds; 2000.
  bool untangle_in_place = true;       ///< Gauss–Seidel untangling (a wedge reads its moved ring); true.
  double untangle_over_relaxation = 1.0;  ///< ω of the in-place untangling, in (0, 2); 1.
  bool untangle_rings = false;         ///< Also move the failing faces' 1-rings; false.
};

/// Result of safe_remap().
struct SafeRemapResult {
  Parameterization param;  ///< The accepted (possibly damped) parameterization.
  double damping = 1.0;    ///< Global blend factor t applied: 1 = full warp, 0 = unchanged input.
  double mean_damping = 1.0;  ///< t times the mean local factor over the wedges (1 = nothing damped).
  int locally_damped = 0;  ///< Wedges whose displacement was reduced locally.
  int checks = 0;          ///< Number of candidate warps checked.
  RemapCheck check;        ///< Check of the returned parameterization (always ok()).
};

/// True if \p param is one chart whose UV boundary edges all lie on the sides of [0,1]^2.
bool single_chart_on_square(const Parameterization& param);

/// Checks \p after against \p before (same faces).
RemapCheck check_remap(const Parameterization& before, const Parameterization& after,
                       const SafeRemapOptions& options = {});

/// Remaps \p param through \p warps, damping locally and then globally (see above) until no face
/// flips, degenerates or overlaps. Never returns an invalid layout: t = 0 is the input.
/// \pre every warp's points are inside [0,1]^2
SafeRemapResult safe_remap(const Parameterization& param, const std::vector<const GridWarp*>& warps,
                           const SafeRemapOptions& options = {});

/// safe_remap() with the fully warped layout \p warped given; damping blends toward it.
/// \pre warped has param's faces and wedges (same uv.size(), uv_faces, face_chart)
/// \throw InvalidInputError the wedge counts differ
SafeRemapResult safe_remap_layout(const Parameterization& param, const Parameterization& warped,
                                  const SafeRemapOptions& options = {});

/// Every wedge at (1 − t)·from + t·to, clamped to [0,1]². \pre same wedge count \throw InvalidInputError the wedge counts differ
Parameterization blend_layouts(const Parameterization& from, const Parameterization& to, double t);

}  // namespace adaptex
