#pragma once
/// \file tangent_frame.h
/// The per-vertex tangent frame of a textured mesh, as MikkTSpace builds it (Mikkelsen 2008,
/// "Simulation of Wrinkled Surfaces Revisited"): the frame that the exported .glb carries (TANGENT)
/// and that the normal map derived from height is baked in, so renderers decode exactly what was baked.
#include <vector>

#include <Eigen/Core>

#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"

namespace adaptex {

/// Area-weighted vertex normals, one per mesh vertex (smooth across UV seams), unit length;
/// (0, 0, 1) for a vertex with no non-degenerate face. Shape: V.
std::vector<Vec3> vertex_normals(const TriMesh& mesh);

/// MikkTSpace tangents, one per wedge (= one glTF vertex), shape W: xyz the unit tangent along
/// ∂P/∂u made orthogonal to the wedge's vertex normal, averaged over the wedge's faces with their
/// corner angles as weights; w = ±1 the handedness, +1 where the UV triangle (u, v with v up in the
/// picture) turns the same way as the face, so the bitangent w · (n × t) points along +v. Faces of
/// the minority orientation around a wedge (a flipped UV triangle) do not count. A wedge with no
/// usable face gets a unit vector orthogonal to its normal and w = +1.
/// \pre param.uv_faces.size() == mesh.faces.size(), normals.size() == mesh.positions.size()
/// \throw InvalidInputError the sizes disagree
std::vector<Eigen::Vector4d> wedge_tangents(const TriMesh& mesh, const Parameterization& param,
                                            const std::vector<Vec3>& normals);

/// An orthonormal tangent frame at a surface point (t along u, b along v, n the shading normal).
struct TangentFrame {
  Vec3 t, b, n;
};

/// The frame a renderer builds at barycentric (b0, b1) of face \p f from the vertex normals and the
/// wedge tangents: n the normalized interpolated normal, t the interpolated tangent made orthogonal
/// to n, b = w · (n × t) with the face's handedness w. Falls back to the face's own frame
/// (∂P/∂u made orthogonal to the face normal) where the interpolated tangent vanishes.
/// \pre f is a face of mesh, normals and tangents as above
TangentFrame interpolated_frame(const TriMesh& mesh, const Parameterization& param, const std::vector<Vec3>& normals,
                                const std::vector<Eigen::Vector4d>& tangents, int f, double b0, double b1);

/// interpolated_frame() with face \p f's normal \p face_n (face_normal()) and its ∂P/∂u \p pu
/// (face_uv_gradients()) given: the same frame, for callers that evaluate many points of one face.
/// \pre as interpolated_frame()
TangentFrame interpolated_frame(const TriMesh& mesh, const Parameterization& param, const std::vector<Vec3>& normals,
                                const std::vector<Eigen::Vector4d>& tangents, int f, double b0, double b1,
                                const Vec3& face_n, const Vec3& pu);

/// ∂P/∂u and ∂P/∂v of face \p f (both zero when its UV triangle is degenerate).
/// \pre f is a face of mesh and of param
void face_uv_gradients(const TriMesh& mesh, const Parameterization& param, int f, Vec3& pu, Vec3& pv);

}  // namespace adaptex
