#pragma once
/// \file yoshizawa.h
/// Yoshizawa, Belyaev, Seidel 2004, "A fast and simple stretch-minimizing mesh parameterization"
/// (thesis §2.2 and §3.3): the convex weights of the Tutte embedding are divided by the per-vertex
/// stretch σ_w^η and the system re-solved; parameterize_disk() runs the loop.
#include <vector>

#include "adaptex/core/mesh.h"
#include "adaptex/param/floater.h"

namespace adaptex {

/// Per-vertex stretch σ_w = √(Σ A(T) σ(T)² / Σ A(T)) over the faces T around w, with A(T) the 3-D
/// area and σ(T) the face L2 stretch of the map \p uv (size V, per vertex), normalized so that the UV
/// and 3-D total areas agree. Returns V values (+inf next to a flipped/degenerate face; 1 for a vertex
/// without faces).
std::vector<double> vertex_stretch(const TriMesh& mesh, const std::vector<Vec2>& uv);

/// vertex_stretch() from given per-face values: \p face_l2 (F, as face_l2_stretch() returns them) and
/// \p face_areas (F, 3-D areas).
/// \pre face_l2.size() == face_areas.size() == mesh.faces.size()
std::vector<double> vertex_stretch(const TriMesh& mesh, const std::vector<double>& face_l2,
                                   const std::vector<double>& face_areas);

/// One Yoshizawa update: λ_vw ← λ_vw / σ_w^η, then each row renormalized to sum 1.
/// \pre sigma has V finite positive entries.
void yoshizawa_reweight(ConvexWeights& weights, const std::vector<double>& sigma, double eta);

}  // namespace adaptex
