#include "adaptex/core/mesh.h"

#include <Eigen/Geometry>

#include "adaptex/core/parameterization.h"

namespace adaptex {

double face_area(const TriMesh& mesh, int f) {
  const Face& t = mesh.faces[f];
  const Vec3& a = mesh.positions[t[0]];
  return 0.5 * (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a).norm();
}

Vec3 face_normal(const TriMesh& mesh, int f) {
  const Face& t = mesh.faces[f];
  const Vec3& a = mesh.positions[t[0]];
  Vec3 n = (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a);
  const double len = n.norm();
  return len > 0 ? Vec3(n / len) : Vec3::Zero();
}

double surface_area(const TriMesh& mesh) {
  double sum = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) sum += face_area(mesh, f);
  return sum;
}

BoundingBox bounding_box(const TriMesh& mesh) {
  BoundingBox box;
  if (mesh.positions.empty()) return box;
  box.min = box.max = mesh.positions.front();
  for (const Vec3& p : mesh.positions) {
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
  }
  return box;
}

Vec3 point_on_face(const TriMesh& mesh, int f, double b0, double b1) {
  const Face& t = mesh.faces[f];
  return b0 * mesh.positions[t[0]] + b1 * mesh.positions[t[1]] +
         (1.0 - b0 - b1) * mesh.positions[t[2]];
}

double uv_signed_area(const Parameterization& param, int f) {
  const Face& t = param.uv_faces[f];
  const Vec2 a = param.uv[t[1]] - param.uv[t[0]];
  const Vec2 b = param.uv[t[2]] - param.uv[t[0]];
  return 0.5 * (a.x() * b.y() - a.y() * b.x());
}

}  // namespace adaptex
