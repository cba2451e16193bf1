#pragma once
/// \file slim.h
/// Free-boundary, locally injective layout of a disk that minimizes the symmetric Dirichlet energy
/// Σ_f A_f (σ₁² + σ₁⁻² + σ₂² + σ₂⁻²) by scalable locally injective maps (SLIM: Rabinovich, Poranne,
/// Panozzo, Sorkine-Hornung, ACM TOG 2017), started from a layout without flipped triangles: each
/// step is taken only as far as no triangle flips (the step bound of Smith & Schaefer, "Bijective
/// parameterization with free boundaries", SIGGRAPH 2015), and the energy is infinite at a flip, so
/// no triangle degenerates either. The square disk parameterization of a scan chart stretches it
/// (L2 about 1.5), LSCM is conformal, not isometric, and folds on noisy pieces, and ARAP (which
/// has no barrier) collapses triangles to slivers on them; SLIM from the flip-free square layout lets
/// the boundary find its own shape at near-unit stretch. docs/charts.md, "Scans".
#include <optional>
#include <vector>

#include "adaptex/core/mesh.h"
#include "adaptex/core/types.h"
#include "adaptex/param/unfold.h"  // PolygonLayout

namespace adaptex {

/// Options of slim_relax().
struct SlimOptions {
  int max_iterations = 12;  ///< Local/global iterations at most.
  double tolerance = 1e-3;  ///< Stop when an iteration lowers the energy by less than this fraction.
};

/// Per-vertex layout (size V) of \p disk of lower symmetric Dirichlet energy than \p start, with
/// the boundary free. \p start may have any scale and rotation (it is scaled to the 3-D area first).
/// Each iteration solves SLIM's weighted proxy, cuts the step at 0.9 of the first time a face would
/// flip, and halves it (up to 8 times) until the energy falls. Zero-area faces have no energy but
/// are kept from flipping as well.
/// \pre \p disk is connected and consistently wound; \p start has no flipped or degenerate triangle
///      (a chart's disk parameterization); otherwise \p start comes back unchanged
/// \return the layout (its energy never above that of the scaled \p start)
/// \throw InvalidInputError \p start does not have V entries, a face index is outside [0, V), or a
///        position or start coordinate is not finite
std::vector<Vec2> slim_relax(const TriMesh& disk, const std::vector<Vec2>& start,
                             const SlimOptions& options = {});

/// slim_relax() of \p start, turned into its smallest bounding rectangle and scaled into [0,1]²
/// (fit_to_rectangle()).
/// \pre as slim_relax()
/// \return the layout, or std::nullopt when it has a flipped, degenerate or overlapping UV triangle
///         (the free boundary may run into itself)
/// \throw InvalidInputError as slim_relax()
std::optional<PolygonLayout> slim_layout(const TriMesh& disk, const std::vector<Vec2>& start,
                                         const SlimOptions& options = {});

/// The first valid slim_layout() of \p start with options.max_iterations, then half as many, and
/// so on down to one (a free boundary may run into itself only after many iterations); all from
/// one run of the iterations, the same layouts as separate calls.
/// \pre as slim_relax()
/// \return the layout, or std::nullopt when none is valid or options.max_iterations < 1
/// \throw InvalidInputError as slim_relax()
std::optional<PolygonLayout> slim_layout_halving(const TriMesh& disk, const std::vector<Vec2>& start,
                                                 const SlimOptions& options = {});

}  // namespace adaptex
