#pragma once
/// \file remap.h
/// Re-parameterization by the optimized grid (thesis §3.7.2): every wedge's new UV is the bilinear
/// interpolation, in its uniform-grid cell, of the cell's four optimized corners; two-stage warps are
/// applied in order (fine ∘ coarse). The warp is continuous and keeps [0,1]^2, but the mesh is
/// piecewise linear, so a strong warp could still flip a UV triangle or make two triangles overlap.
/// safe_remap() guarantees neither happens: it checks the result and, if needed, damps the
/// displacement of the wedges of the offending faces (local damping, halved round after round), and
/// only if that is not enough damps the whole warp toward the identity (bisection on the blend factor
/// t: new uv = old + t·(warped − old); t = 1 full warp, t = 0 the input itself).
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
  /// Check for overlapping triangles as well; only pairs that were not already overlapping in the
  /// input count. A flip-free candidate is first tested by OverlapCertificate (O(F),
  /// overlap_certificate.h); only if that proof fails are the pairs counted
  /// (count_overlapping_triangles, O(F log F)). Skipped (provably unnecessary) for a single chart
  /// whose boundary lies on the square's sides (single_chart_on_square()).
  bool check_overlaps = true;
  /// With check_overlaps, when the input has no overlapping triangles: the faces of every overlapping
  /// pair are damped locally like failing faces (after flips and crossing chart borders are gone), instead of
  /// leaving the pair to the global blend. Found on triceratops' 12-chart layout at 128²: a 3-D sliver
  /// (6.8e-8 of the mean face area), refined, overlapped its neighbours at every global blend down to
  /// 0.005, so the global bisection kept 0.5 % of the warp (texel saving 1.7× against 6.5× at 512²).
  bool damp_overlaps = true;
  /// Local damping rounds: the wedges of every face that flips or degenerates are pulled halfway back
  /// to their input UV, this many times at most, before the whole warp is damped.
  int max_local_rounds = 24;
  /// From this local round on, the wedges of a face that still fails go back to their input UV
  /// instead of halving their displacement (< 0: never). Not with smooth_local_damping, whose
  /// averaging does not halve. See safe_remap_layout().
  int snap_round = 12;
  /// When local damping alone fails and the global blend is used, local damping is also tried with
  /// this many rounds; the result that keeps more of the warp (mean blend factor) wins.
  int extended_local_rounds = 100;
  /// Local damping replaces a failing wedge's displacement by half the mean of its 1-ring's (smooths
  /// as it damps) instead of halving it. Measured on spot lines at 256² (32 charts): smoothing 27.43 /
  /// 27.00 dB (without / with refinement) against halving's 27.72 / 27.67: off by default.
  bool smooth_local_damping = false;
  /// Multi-chart layouts: after local damping, each chart that still has a failing face has its whole
  /// displacement halved, up to this many times, before the global blend damps every chart. Off by
  /// default: measured with density-flow at 256² (spot 32 charts, triceratops 65), 8 halvings lost
  /// 0.3–0.9 dB against the global blend (the failing faces sit in many charts at once).
  int chart_halvings = 0;
  int bisection_steps = 10;  ///< Bisection steps on the global t if local damping is not enough.
  /// Untangling rounds before any damping: interior wedges of failing faces and their 1-rings move to
  /// the mean of their 1-ring's warped positions (0 = off: damp only). Stops as soon as no face
  /// fails; 30 rounds left camelhead lines 256² with 1918 failing faces (texel saving 1.56×), 300
  /// rounds with none (5.65×), in 1 s.
  int untangle_rounds = 500;
  /// Past untangle_rounds, untangling goes on while it still makes progress: as long as fewer faces
  /// fail than untangle_patience rounds before, up to untangle_max_rounds in all (untangle_patience 0,
  /// or untangle_rounds < untangle_patience: stop at untangle_rounds). On the face mask with
  /// dots at 256² and 1024² the full warp needed 1,000–1,100 rounds (the count rises first, then falls,
  /// not monotonically): stopping at 500 failed it and bisected the global blend (12 candidates,
  /// 3,900 rounds, 0.2 dB less).
  int untangle_patience = 200;
  int untangle_max_rounds = 2000;  ///< Hard cap of the rounds (see untangle_patience).
  /// Untangling rounds update the wedges in place (Gauss–Seidel: a wedge reads its ring as already
  /// moved this round) instead of all from the previous round's positions (Jacobi): same fixed point,
  /// fewer rounds (docs/decisions.md, "Untangling in place, without over-relaxation").
  bool untangle_in_place = true;
  /// Over-relaxation ω of the in-place untangling: a wedge moves to p + ω (ring mean − p); in (0, 2).
  double untangle_over_relaxation = 1.0;
  /// Untangling also moves the 1-rings of the failing faces' wedges (off: only the failing faces' own
  /// wedges move, which disturbs fewer good faces).
  bool untangle_rings = false;
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

/// safe_remap() with the full warp given as its result: \p warped is \p param with every wedge
/// already moved (e.g. advected through a FlowWarp, density_flow.h). Damping blends toward it.
/// \pre warped has param's faces and wedges (same uv.size(), uv_faces, face_chart)
/// \throw InvalidInputError the wedge counts differ
SafeRemapResult safe_remap_layout(const Parameterization& param, const Parameterization& warped,
                                  const SafeRemapOptions& options = {});

/// \p from with every wedge moved to (1 − t)·from + t·to (clamped to [0,1]²): a warped layout damped
/// toward its start. \pre same wedge count \throw InvalidInputError the wedge counts differ
Parameterization blend_layouts(const Parameterization& from, const Parameterization& to, double t);

}  // namespace adaptex
