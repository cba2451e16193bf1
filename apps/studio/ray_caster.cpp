/// \file ray_caster.cpp
/// Picking on the library's ray scene (see ray_caster.h).
#include "ray_caster.h"

#include <limits>

namespace adaptex::studio {

namespace {
/// +1 if the faces are wound CCW seen from outside (positive signed volume), -1 otherwise.
int mesh_orientation(const TriMesh& mesh) {
  double volume6 = 0;
  for (const Face& fc : mesh.faces) {
    const Vec3& a = mesh.positions[fc[0]];
    const Vec3& b = mesh.positions[fc[1]];
    const Vec3& c = mesh.positions[fc[2]];
    volume6 += a.dot(b.cross(c));
  }
  return volume6 < 0 ? -1 : 1;
}
}  // namespace

RayCaster::RayCaster(const TriMesh& mesh)
    : scene_(mesh, {.single_thread = true, .high_quality = false}, "studio"),
      mesh_(mesh),
      orientation_(mesh_orientation(mesh)) {}

std::optional<Hit> RayCaster::intersect(const Ray& ray) const {
  const std::optional<RayScene::Hit> hit =
      scene_.intersect({ray.origin, ray.dir, 0.0f, std::numeric_limits<float>::infinity()});
  if (!hit) return std::nullopt;
  Hit h;
  h.face = hit->face;
  // Embree: p = (1-u-v) p0 + u p1 + v p2.
  const double u = hit->u, w = hit->v;
  h.b0 = 1.0 - u - w;
  h.b1 = u;
  h.point = point_on_face(mesh_, h.face, h.b0, h.b1);
  h.t = (h.point - ray.origin).norm();
  h.normal = face_normal(mesh_, h.face) * double(orientation_);
  h.front_facing = h.normal.dot(ray.dir) < 0.0;
  return h;
}

}  // namespace adaptex::studio
