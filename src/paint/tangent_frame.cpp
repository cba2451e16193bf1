/// \file tangent_frame.cpp
/// Vertex normals, MikkTSpace wedge tangents and the interpolated frame a renderer builds from them.
#include "adaptex/paint/tangent_frame.h"

#include <algorithm>
#include <cmath>

#include "adaptex/core/errors.h"

namespace adaptex {

namespace {

Vec3 unit_or(const Vec3& v, const Vec3& fallback) {
  const double len = v.norm();
  return len > 0 && std::isfinite(len) ? Vec3(v / len) : fallback;
}

/// unit_or() with the fallback computed only when used (\p fallback() is called then).
template <class F>
Vec3 unit_or_else(const Vec3& v, F&& fallback) {
  const double len = v.norm();
  return len > 0 && std::isfinite(len) ? Vec3(v / len) : fallback();
}

/// A unit vector orthogonal to unit \p n.
Vec3 any_orthogonal(const Vec3& n) {
  const Vec3 axis = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  return (axis - n * n.dot(axis)).normalized();
}

/// Signed doubled area of face \p f's UV triangle.
double uv_det(const Parameterization& param, int f) {
  const Face& T = param.uv_faces[f];
  const Vec2 d1 = param.uv[T[1]] - param.uv[T[0]], d2 = param.uv[T[2]] - param.uv[T[0]];
  return d1.x() * d2.y() - d1.y() * d2.x();
}

}  // namespace

std::vector<Vec3> vertex_normals(const TriMesh& mesh) {
  std::vector<Vec3> n(mesh.positions.size(), Vec3::Zero());
  for (const Face& f : mesh.faces) {
    const Vec3 a = (mesh.positions[f[1]] - mesh.positions[f[0]]).cross(mesh.positions[f[2]] - mesh.positions[f[0]]);
    for (int v : f) n[v] += a;
  }
  for (Vec3& v : n) v = unit_or(v, Vec3(0, 0, 1));
  return n;
}

void face_uv_gradients(const TriMesh& mesh, const Parameterization& param, int f, Vec3& pu, Vec3& pv) {
  const Face& F = mesh.faces[f];
  const Face& T = param.uv_faces[f];
  const Vec3 e1 = mesh.positions[F[1]] - mesh.positions[F[0]], e2 = mesh.positions[F[2]] - mesh.positions[F[0]];
  const Vec2 d1 = param.uv[T[1]] - param.uv[T[0]], d2 = param.uv[T[2]] - param.uv[T[0]];
  const double det = d1.x() * d2.y() - d1.y() * d2.x();
  if (!(std::abs(det) > 0) || !std::isfinite(det)) {
    pu = pv = Vec3::Zero();
    return;
  }
  pu = (e1 * d2.y() - e2 * d1.y()) / det;
  pv = (e2 * d1.x() - e1 * d2.x()) / det;
}

std::vector<Eigen::Vector4d> wedge_tangents(const TriMesh& mesh, const Parameterization& param,
                                            const std::vector<Vec3>& normals) {
  if (param.uv_faces.size() != mesh.faces.size() || normals.size() != mesh.positions.size())
    throw InvalidInputError("wedge_tangents: the layout, the mesh and the normals disagree in size");
  const int nw = param.num_wedges();
  // Per wedge, the angle-weighted sums of projected face tangents for each orientation (+, −).
  std::vector<Vec3> sum[2] = {std::vector<Vec3>(nw, Vec3::Zero()), std::vector<Vec3>(nw, Vec3::Zero())};
  std::vector<double> weight[2] = {std::vector<double>(nw, 0.0), std::vector<double>(nw, 0.0)};
  std::vector<int> vertex(nw, -1);
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const int fi = static_cast<int>(f);
    Vec3 pu, pv;
    face_uv_gradients(mesh, param, fi, pu, pv);
    const double det = uv_det(param, fi);
    if (!(pu.norm() > 0)) continue;  // degenerate UV triangle: no tangent
    const int side = det > 0 ? 0 : 1;
    const Vec3 tf = pu.normalized();
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.faces[f][k], w = param.uv_faces[f][k];
      vertex[w] = v;
      const Vec3& n = normals[v];
      const Vec3 t = tf - n * n.dot(tf);
      if (!(t.norm() > 0)) continue;
      // Corner angle between the two edges, both projected onto the vertex's tangent plane.
      Vec3 a = mesh.positions[mesh.faces[f][(k + 1) % 3]] - mesh.positions[v];
      Vec3 b = mesh.positions[mesh.faces[f][(k + 2) % 3]] - mesh.positions[v];
      a = unit_or(a - n * n.dot(a), Vec3::Zero());
      b = unit_or(b - n * n.dot(b), Vec3::Zero());
      const double angle = std::acos(std::clamp(a.dot(b), -1.0, 1.0));
      sum[side][w] += angle * t.normalized();
      weight[side][w] += angle;
    }
  }
  for (int w = 0; w < nw; ++w)  // a wedge no face uses: its vertex from the layout when known
    if (vertex[w] < 0 && w < static_cast<int>(param.wedge_vertex.size()) && param.wedge_vertex[w] >= 0 &&
        param.wedge_vertex[w] < static_cast<int>(normals.size()))
      vertex[w] = param.wedge_vertex[w];
  std::vector<Eigen::Vector4d> out(nw);
  for (int w = 0; w < nw; ++w) {
    const Vec3 n = vertex[w] >= 0 ? normals[vertex[w]] : Vec3(0, 0, 1);
    const int side = weight[1][w] > weight[0][w] ? 1 : 0;
    const Vec3 t = unit_or_else(sum[side][w], [&n] { return any_orthogonal(n); });
    const double handed = weight[side][w] > 0 && side == 1 ? -1.0 : 1.0;
    out[w] = Eigen::Vector4d(t.x(), t.y(), t.z(), handed);
  }
  return out;
}

namespace {

/// interpolated_frame() with the face normal given and ∂P/∂u from \p pu_of() (needed only where the
/// interpolated tangent vanishes).
template <class PU>
TangentFrame frame_at(const TriMesh& mesh, const Parameterization& param, const std::vector<Vec3>& normals,
                      const std::vector<Eigen::Vector4d>& tangents, int f, double b0, double b1, const Vec3& fn,
                      PU pu_of) {
  const double bc[3] = {b0, b1, 1 - b0 - b1};
  const Face& F = mesh.faces[f];
  const Face& T = param.uv_faces[f];
  Vec3 n = Vec3::Zero(), t = Vec3::Zero();
  for (int k = 0; k < 3; ++k) {
    n += bc[k] * normals[F[k]];
    t += bc[k] * tangents[T[k]].head<3>();
  }
  n = unit_or(n, fn);
  t -= n * n.dot(t);
  if (!(t.norm() > 1e-6)) {  // tangents cancelling inside the face: its own frame
    const Vec3 pu = pu_of();
    t = pu - n * n.dot(pu);
  }
  t = unit_or_else(t, [&n] { return any_orthogonal(n); });
  double w = 0;  // the renderer's handedness: the interpolated w of the wedges
  for (int k = 0; k < 3; ++k) w += bc[k] * tangents[T[k]].w();
  const double handed = w < 0 ? -1.0 : 1.0;
  return {t, handed * n.cross(t), n};
}

}  // namespace

TangentFrame interpolated_frame(const TriMesh& mesh, const Parameterization& param, const std::vector<Vec3>& normals,
                                const std::vector<Eigen::Vector4d>& tangents, int f, double b0, double b1) {
  return frame_at(mesh, param, normals, tangents, f, b0, b1, face_normal(mesh, f), [&] {
    Vec3 pu, pv;
    face_uv_gradients(mesh, param, f, pu, pv);
    return pu;
  });
}

TangentFrame interpolated_frame(const TriMesh& mesh, const Parameterization& param, const std::vector<Vec3>& normals,
                                const std::vector<Eigen::Vector4d>& tangents, int f, double b0, double b1,
                                const Vec3& face_n, const Vec3& pu) {
  return frame_at(mesh, param, normals, tangents, f, b0, b1, face_n, [&pu] { return pu; });
}

}  // namespace adaptex
