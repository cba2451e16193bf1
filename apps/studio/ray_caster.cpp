/// \file ray_caster.cpp
/// Embree 3 picking (see ray_caster.h).
#include "ray_caster.h"

#include <embree3/rtcore.h>

#include <cmath>
#include <limits>

#include "adaptex/core/errors.h"

namespace adaptex::studio {

struct RayCaster::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

RayCaster::RayCaster(const TriMesh& mesh) : impl_(std::make_unique<Impl>()), mesh_(mesh) {
  impl_->device = rtcNewDevice("threads=1");
  if (!impl_->device) throw Error("studio: could not create the Embree device");
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_ROBUST);
  RTCGeometry geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                        3 * sizeof(float), mesh.positions.size()));
  for (size_t i = 0; i < mesh.positions.size(); ++i)
    for (int k = 0; k < 3; ++k) v[3 * i + k] = static_cast<float>(mesh.positions[i][k]);
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                             3 * sizeof(unsigned), mesh.faces.size()));
  double volume6 = 0;
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& fc = mesh.faces[f];
    for (int k = 0; k < 3; ++k) idx[3 * f + k] = static_cast<unsigned>(fc[k]);
    const Vec3& a = mesh.positions[fc[0]];
    const Vec3& b = mesh.positions[fc[1]];
    const Vec3& c = mesh.positions[fc[2]];
    volume6 += a.dot(b.cross(c));
  }
  orientation_ = volume6 < 0 ? -1 : 1;
  rtcCommitGeometry(geom);
  rtcAttachGeometry(impl_->scene, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(impl_->scene);
}

RayCaster::~RayCaster() = default;

std::optional<Hit> RayCaster::intersect(const Ray& ray) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh{};
  rh.ray.org_x = float(ray.origin.x());
  rh.ray.org_y = float(ray.origin.y());
  rh.ray.org_z = float(ray.origin.z());
  rh.ray.dir_x = float(ray.dir.x());
  rh.ray.dir_y = float(ray.dir.y());
  rh.ray.dir_z = float(ray.dir.z());
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = std::numeric_limits<float>::infinity();
  rh.ray.mask = 0xFFFFFFFFu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &ctx, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  Hit h;
  h.face = static_cast<int>(rh.hit.primID);
  // Embree: p = (1-u-v) p0 + u p1 + v p2.
  const double u = rh.hit.u, w = rh.hit.v;
  h.b0 = 1.0 - u - w;
  h.b1 = u;
  h.point = point_on_face(mesh_, h.face, h.b0, h.b1);
  h.t = (h.point - ray.origin).norm();
  h.normal = face_normal(mesh_, h.face) * double(orientation_);
  h.front_facing = h.normal.dot(ray.dir) < 0.0;
  return h;
}

}  // namespace adaptex::studio
