#pragma once
/// \file unfold.h
/// Isometric layout of a triangulated polygon (a disk whose vertices all lie on its boundary, such
/// as the strips and single triangles of small scan fragments). The disk parameterization maps such
/// a chart's boundary, i.e. every vertex, onto the square, so its stretch is whatever that boundary
/// map gives (a 10-face strip: L2 about 1.5, a sliver: 250). Without interior vertices the faces can
/// be unfolded one by one across their shared edges (the dual graph of a triangulated polygon is a
/// tree, so the edge lengths alone fix the layout): L2 = 1, and the chart's rectangle takes the
/// layout's own aspect ratio. docs/charts.md.
#include <optional>
#include <vector>

#include "adaptex/core/mesh.h"
#include "adaptex/core/types.h"

namespace adaptex {

/// An unfolded triangulated polygon in its smallest bounding rectangle.
struct PolygonLayout {
  /// V coordinates (indexed like the mesh's positions) in [0,1]²: the isometric layout turned so
  /// that its bounding rectangle has the smallest area, then scaled to the unit square by
  /// (1 / width, 1 / height). Scaling back by (aspect, 1) gives an isometry up to scale.
  std::vector<Vec2> uv;
  double aspect = 1;  ///< Width / height of the bounding rectangle of the isometric layout.
  double fill = 0;    ///< UV area of the layout / area of its bounding rectangle, in (0, 1].
};

/// Unfolds \p disk isometrically (edge lengths of the 3-D faces) when it is a triangulated polygon:
/// connected, every edge on one or two faces, every vertex on exactly two boundary edges, Euler
/// characteristic 1. The first face goes down with positive orientation, every other one across
/// its edge with its parent face (breadth first), so each UV triangle has the orientation of its
/// face's vertex order when the faces are wound consistently. The result is rejected when a UV
/// triangle is flipped or degenerate (measure_stretch()) or two overlap
/// (count_overlapping_triangles()): an unfolding may wrap around a vertex with more than 2π of
/// angle, and a zero-area face has no layout.
/// \pre \p disk has consistently wound faces (faces wound against their neighbours give a folded
///      layout, hence std::nullopt)
/// \return the layout, or std::nullopt when \p disk is not a triangulated polygon or its unfolding
///         folds, overlaps, degenerates or overflows (a zero-area face, coordinates near 1e308)
/// \throw InvalidInputError a face index outside [0, V) or a position that is not finite
std::optional<PolygonLayout> unfold_polygon(const TriMesh& disk);

/// \p uv (a layout of \p disk, indexed like its positions) turned so that its bounding rectangle
/// has the smallest area (one side along an edge of the convex hull) and scaled into [0,1]² by
/// (1 / width, 1 / height); rejected when a UV triangle is flipped or degenerate or two overlap.
/// Shared by unfold_polygon() and the free-boundary layout (lscm.h).
/// \return the layout, or std::nullopt when \p uv has the wrong size, a coordinate that is not
///         finite, no area, or a flipped, degenerate or overlapping triangle
std::optional<PolygonLayout> fit_to_rectangle(const TriMesh& disk, std::vector<Vec2> uv);

/// Throws InvalidInputError, its message starting with \p who, when a face index of \p disk is
/// outside [0, V) or a position is not finite: the input check of the chart layouts (unfold, LSCM,
/// SLIM).
void check_layout_mesh(const TriMesh& disk, const char* who);

}  // namespace adaptex
