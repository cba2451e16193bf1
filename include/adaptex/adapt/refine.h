#pragma once
/// \file refine.h
/// Conforming refinement of a mesh for a warp of its UV domain. UVs are linear per
/// triangle: a warped layout only moves the wedges, so a triangle that is large for the warp's
/// variation either flips or smears the detail the warp was meant to magnify. refine_for_warp()
/// splits exactly those triangles, in the *old* UV domain, before the caller warps the wedges:
///  - an edge is marked when the warp bends it, |warp(midpoint) − midpoint of the warped ends| >
///    tolerance, and every edge of a face is marked when the warped face flips or degenerates;
///  - the marking is closed so that every face with a marked edge also has its longest (UV) edge
///    marked, and each face is split by longest-edge bisection into 2, 3 or 4 children (Rivara 1984,
///    "Algorithms for refining triangular grids suitable for adaptive and multigrid techniques",
///    IJNME 20: splitting through the longest edge keeps the triangles' angles bounded away from 0
///    over repeated rounds, unlike repeated green bisection);
///  - a marked edge is split at its 3-D midpoint on every face that uses it, so there are no
///    T-junctions, new vertices lie on the original faces and the surface is unchanged.
/// Rounds repeat on the children until no edge is marked, max_levels is reached or the face budget
/// is spent. docs/adaptive.md, "Refinement under the warp".
#include <functional>

#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"

namespace adaptex {

/// Settings of refine_for_warp().
struct RefineOptions {
  /// Largest allowed |warp(m) − (warp(a) + warp(b)) / 2| over the UV edges (a, b) with midpoint m,
  /// in UV units ([0,1]^2). Half a texel (0.5 / N for an N x N texture) is a good choice.
  double tolerance = 0.5 / 1024;
  /// Refinement rounds at most; each round splits an edge at most once (0 = no refinement).
  int max_levels = 4;
  /// Face budget of the refined mesh: edges are split worst first (flipping faces, then by
  /// deviation) and refinement stops before the mesh would exceed this many faces. 0 = four times
  /// the input's face count.
  long max_faces = 0;
  /// A warped UV triangle whose signed area (with the sign of the unwarped triangle) is <= this
  /// counts as degenerate, as in SafeRemapOptions::min_area. Faces already this small before the
  /// warp are not tested.
  double min_area = 1e-12;
};

/// Result of refine_for_warp(). V', F', U' are the refined vertex, face and wedge counts.
struct RefineResult {
  /// The refined mesh: the V input vertices first (same ids), then the new edge midpoints. A face
  /// that was not split keeps its id and corners; a split face's first child takes its id, the other
  /// children are appended after the F input faces.
  TriMesh mesh;
  /// Its UV layout in the *old* (unwarped) domain: the U input wedges first (same ids and UVs), then
  /// the new wedges at UV edge midpoints (one per side of a seam). face_chart is inherited from the
  /// parent face, wedge_vertex[uv_faces[f][k]] == mesh.faces[f][k], children keep the parent's
  /// winding in 3-D and UV. The caller warps it next.
  Parameterization param;
  FaceData<int> parent_face;  ///< F': input face id each refined face lies on.
  int added_vertices = 0;     ///< V' − V.
  int added_wedges = 0;       ///< U' − U.
  int added_faces = 0;        ///< F' − F.
  int levels = 0;             ///< Rounds that split at least one edge.
  bool budget_reached = false;  ///< Refinement stopped because of max_faces.
  /// Largest edge-midpoint deviation (see RefineOptions::tolerance) over the refined UV edges.
  double max_deviation = 0;
  /// Refined faces the warp still flips or degenerates (0 unless max_levels or the budget stopped
  /// the refinement first).
  int flipped = 0;
};

/// Refines \p mesh conformingly where \p warp, a map of the UV square (old UV -> new UV), bends the
/// linear-per-triangle UVs of \p param by more than options.tolerance or flips a triangle (see the
/// file comment). Cost O(F') per round; warp evaluations run in parallel (TBB), so \p warp must be
/// thread-safe. A GridWarp g is passed as `[&](const Vec2& p) { return g.apply(p); }`.
/// \pre mesh is manifold (every edge has 1 or 2 faces); param is parallel to mesh
///      (uv_faces.size() == face_chart.size() == F, wedge_vertex[uv_faces[f][k]] == faces[f][k])
/// \throw InvalidInputError param inconsistent with mesh, tolerance <= 0 or not finite,
///        max_levels < 0, max_faces < 0, empty warp, or a warp that returns a non-finite point
/// \throw TopologyError an edge with more than two faces
RefineResult refine_for_warp(const TriMesh& mesh, const Parameterization& param,
                             const std::function<Vec2(const Vec2&)>& warp,
                             const RefineOptions& options = {});

}  // namespace adaptex
