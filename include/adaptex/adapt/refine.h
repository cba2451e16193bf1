#pragma once
/// \file refine.h
/// Conforming refinement for a warp of the UV domain: bent edges split at their 3-D midpoint by
/// longest-edge bisection (Rivara 1984); the surface is unchanged, no T-junctions.
#include <functional>

#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"

namespace adaptex {

/// Settings of refine_for_warp().
struct RefineOptions {
  double tolerance = 0.5 / 1024;  ///< Largest |warp(mid) − mid of warped ends| of a UV edge, uv units; ½ texel at 1024.
  int max_levels = 4;             ///< Rounds at most, each splitting an edge at most once (0: none); 4.
  long max_faces = 0;             ///< Face budget, worst edges first (0: 4× the input's faces); 0.
  double min_area = 1e-12;        ///< Warped signed UV area ≤ this counts as degenerate; 1e-12.
};

/// Result of refine_for_warp(). V', F', U' are the refined vertex, face and wedge counts.
struct RefineResult {
  TriMesh mesh;             ///< Input vertices and faces first (same ids), then midpoints and children.
  Parameterization param;   ///< Its layout in the *old* UV domain (input wedges first); the caller warps it.
  FaceData<int> parent_face;  ///< F': input face id each refined face lies on.
  int added_vertices = 0;     ///< V' − V.
  int added_wedges = 0;       ///< U' − U.
  int added_faces = 0;        ///< F' − F.
  int levels = 0;             ///< Rounds that split at least one edge.
  bool budget_reached = false;  ///< Refinement stopped because of max_faces.
  double max_deviation = 0;   ///< Largest edge-midpoint deviation over the refined UV edges.
  int flipped = 0;            ///< Refined faces the warp still flips (0 unless a limit stopped it).
};

/// Refines \p mesh where \p warp (old UV → new UV, thread-safe) bends \p param's edges by more than
/// options.tolerance or flips a triangle. O(F') per round.
/// \pre mesh manifold; param parallel to mesh
/// \throw InvalidInputError param inconsistent, bad options, empty warp, or a non-finite warped point
/// \throw TopologyError an edge with more than two faces
RefineResult refine_for_warp(const TriMesh& mesh, const Parameterization& param,
                             const std::function<Vec2(const Vec2&)>& warp,
                             const RefineOptions& options = {});

}  // namespace adaptex
