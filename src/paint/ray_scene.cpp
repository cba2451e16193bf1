/// \file ray_scene.cpp
/// Embree 3 scene of a triangle mesh (ray_scene.h).
#include "adaptex/paint/ray_scene.h"

#include <embree3/rtcore.h>

#include <limits>
#include <vector>

#include "adaptex/core/errors.h"

namespace adaptex {

struct RayScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::string who;

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  void check(const char* what) const {
    const RTCError err = rtcGetDeviceError(device);
    if (err != RTC_ERROR_NONE)
      throw Error(who + ": Embree failed in " + what + " (error " + std::to_string(static_cast<int>(err)) + ")");
  }

  /// Copies the mesh into a new triangle geometry of the scene. \pre the mesh has faces
  void add_mesh(const TriMesh& mesh) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* verts = static_cast<float*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.positions.size()));
    auto* tris = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.faces.size()));
    if (!verts || !tris) {
      rtcReleaseGeometry(geom);
      check("rtcSetNewGeometryBuffer");
      throw Error(who + ": Embree could not allocate the mesh buffers");
    }
    for (size_t v = 0; v < mesh.positions.size(); ++v)
      for (int k = 0; k < 3; ++k) verts[3 * v + k] = static_cast<float>(mesh.positions[v][k]);
    for (size_t f = 0; f < mesh.faces.size(); ++f)
      for (int k = 0; k < 3; ++k) tris[3 * f + k] = static_cast<unsigned>(mesh.faces[f][k]);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
  }
};

namespace {

RTCRay to_embree(const RayScene::Ray& r) {
  RTCRay ray;
  ray.org_x = static_cast<float>(r.origin.x());
  ray.org_y = static_cast<float>(r.origin.y());
  ray.org_z = static_cast<float>(r.origin.z());
  ray.dir_x = static_cast<float>(r.dir.x());
  ray.dir_y = static_cast<float>(r.dir.y());
  ray.dir_z = static_cast<float>(r.dir.z());
  ray.tnear = r.tnear;
  ray.tfar = r.tfar;
  ray.time = 0.0f;
  ray.mask = 0xFFFFFFFFu;
  ray.id = 0;
  ray.flags = 0;
  return ray;
}

/// Embree marks an occluded ray by tfar = -inf.
bool blocked(const RTCRay& ray) { return ray.tfar == -std::numeric_limits<float>::infinity(); }

}  // namespace

RayScene::RayScene(const TriMesh& mesh, const Options& options, const std::string& who)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.who = who;
  m.device = rtcNewDevice(options.single_thread ? "threads=1" : nullptr);
  if (!m.device) throw Error(who + ": cannot create the Embree device");
  m.scene = rtcNewScene(m.device);
  rtcSetSceneFlags(m.scene, RTC_SCENE_FLAG_ROBUST);
  if (options.high_quality) rtcSetSceneBuildQuality(m.scene, RTC_BUILD_QUALITY_HIGH);
  if (!mesh.faces.empty()) m.add_mesh(mesh);
  rtcCommitScene(m.scene);
  m.check("rtcCommitScene");
}

RayScene::~RayScene() = default;
RayScene::RayScene(RayScene&&) noexcept = default;
RayScene& RayScene::operator=(RayScene&&) noexcept = default;

std::optional<RayScene::Hit> RayScene::intersect(const Ray& ray) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh{};
  rh.ray = to_embree(ray);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &ctx, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  return Hit{static_cast<int>(rh.hit.primID), rh.hit.u, rh.hit.v};
}

bool RayScene::occluded(const Ray& ray) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay r = to_embree(ray);
  rtcOccluded1(impl_->scene, &ctx, &r);
  return blocked(r);
}

void RayScene::occluded(std::span<const Ray> rays, std::span<char> out) const {
  if (out.size() != rays.size()) throw InvalidInputError(impl_->who + ": occluded: rays and out differ in size");
  if (rays.empty()) return;
  std::vector<RTCRay> stream(rays.size());
  for (size_t k = 0; k < rays.size(); ++k) stream[k] = to_embree(rays[k]);
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  rtcOccluded1M(impl_->scene, &ctx, stream.data(), static_cast<unsigned>(stream.size()), sizeof(RTCRay));
  for (size_t k = 0; k < rays.size(); ++k) out[k] = blocked(stream[k]) ? 1 : 0;
}

}  // namespace adaptex
