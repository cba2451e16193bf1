#pragma once
/// \file parameterization.h
/// A UV layout of a mesh: the mesh cut into disks ("charts"), each disk mapped into [0,1]^2.
/// Cut vertices are duplicated as separate *wedges* (one UV each), exactly like OBJ's `f v/vt`.
#include <vector>

#include "adaptex/core/mesh.h"

namespace adaptex {

/// UV coordinates of a TriMesh. The face list is parallel to TriMesh::faces: face f of the mesh has
/// corners mesh.faces[f][k] (3-D vertex) and uv_faces[f][k] (wedge); wedge_vertex[uv_faces[f][k]]
/// == mesh.faces[f][k] always holds.
struct Parameterization {
  std::vector<Vec2> uv;          ///< U wedge coordinates, in [0,1]^2.
  std::vector<Face> uv_faces;    ///< F triangles, indices into uv, parallel to TriMesh::faces.
  std::vector<int> wedge_vertex; ///< U: the original mesh vertex of every wedge.
  std::vector<int> face_chart;   ///< F: chart (disk) id of every face, in [0, num_charts).
  int num_charts = 0;            ///< Number of charts packed in the unit square.

  int num_wedges() const { return static_cast<int>(uv.size()); }
};

/// Signed area of face \p f in the UV domain (positive = same orientation as in 3-D).
double uv_signed_area(const Parameterization& param, int f);

}  // namespace adaptex
