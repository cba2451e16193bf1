#pragma once
/// \file mesh.h
/// The triangle mesh: geometry (positions) kept separate from connectivity (faces), plain arrays so
/// that per-element data are ordinary vectors indexed by vertex or face id (after geometry-central).
#include <vector>

#include "adaptex/core/types.h"

namespace adaptex {

/// A triangle mesh. Positions are in the input's own units and are never rescaled by adaptex.
struct TriMesh {
  std::vector<Vec3> positions;  ///< V vertex positions.
  std::vector<Face> faces;      ///< F triangles, indices into positions, CCW from the front.

  int num_vertices() const { return static_cast<int>(positions.size()); }
  int num_faces() const { return static_cast<int>(faces.size()); }
};

/// Per-vertex data of type T, indexed by vertex id (size V).
template <class T>
using VertexData = std::vector<T>;
/// Per-face data of type T, indexed by face id (size F).
template <class T>
using FaceData = std::vector<T>;

/// Area of face \p f. \pre 0 <= f < F.
double face_area(const TriMesh& mesh, int f);
/// Unit normal of face \p f (zero vector for a degenerate face).
Vec3 face_normal(const TriMesh& mesh, int f);
/// Sum of the face areas.
double surface_area(const TriMesh& mesh);
/// Bounding box of all vertices (empty box for a mesh without vertices).
BoundingBox bounding_box(const TriMesh& mesh);
/// Point on face \p f at barycentric coordinates (b0, b1, 1-b0-b1).
Vec3 point_on_face(const TriMesh& mesh, int f, double b0, double b1);

}  // namespace adaptex
