#pragma once
/// \file lscm.h
/// Free-boundary conformal layout of a disk: least-squares conformal maps (Lévy, Petitjean, Ray,
/// Maillot, "Least squares conformal maps for automatic texture atlas generation", SIGGRAPH 2002).
/// The disk parameterization (disk_param.h) maps a chart's boundary onto the square, which
/// stretches charts whose outline is far from a square (strips, L-shapes, the cut-open handles of a
/// scan's fragments); LSCM lets the boundary find its own shape, so a nearly developable chart gets
/// an L2 stretch near 1 at the price of a rectangle it does not fill. docs/charts.md, "Scans".
#include <optional>

#include "adaptex/core/mesh.h"
#include "adaptex/param/unfold.h"  // PolygonLayout

namespace adaptex {

/// LSCM layout of \p disk (a connected disk: one boundary loop) with two boundary vertices pinned
/// far apart, turned into its smallest bounding rectangle and scaled into [0,1]² (fit_to_rectangle()).
/// Each face's conformal energy is weighted by its 3-D area; zero-area faces have no energy.
/// \pre \p disk has consistently wound faces
/// \return the layout, or std::nullopt when the solve fails or the layout has a flipped, degenerate
///         or overlapping UV triangle (LSCM does not guarantee a bijection)
/// \throw InvalidInputError a face index outside [0, V) or a position that is not finite
std::optional<PolygonLayout> lscm_layout(const TriMesh& disk);

}  // namespace adaptex
