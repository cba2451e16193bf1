/// \file decal.cpp
/// Decal projection (thesis Figs. 4.6, 4.7): pinhole camera, bilinear image sampling, occlusion rays
/// (ray_scene.h) for visibility. Definitions: docs/decals.md.
#include "adaptex/paint/decal.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "adaptex/core/errors.h"
#include "adaptex/paint/ray_scene.h"

namespace adaptex {

namespace {

bool finite(const Vec3& v) { return v.allFinite(); }

}  // namespace

DecalFrame decal_frame(const DecalCamera& camera, const std::string& where) {
  if (!finite(camera.eye) || !finite(camera.target) || !finite(camera.up) ||
      !std::isfinite(camera.fov_y_degrees) || !std::isfinite(camera.aspect))
    throw InvalidInputError(where + ": decal camera has a non-finite value");
  if (!(camera.fov_y_degrees > 0.0 && camera.fov_y_degrees < 180.0))
    throw InvalidInputError(where + ": decal \"fov\" must be in (0, 180) degrees, got " +
                            std::to_string(camera.fov_y_degrees));
  if (!(camera.aspect > 0.0))
    throw InvalidInputError(where + ": decal \"aspect\" must be > 0, got " +
                            std::to_string(camera.aspect));
  DecalFrame f;
  f.eye = camera.eye;
  const Vec3 dir = camera.target - camera.eye;
  const double len = dir.norm();
  const double scale = std::max({camera.eye.norm(), camera.target.norm(), 1e-300});
  if (!(len > 1e-12 * scale))
    throw InvalidInputError(where + ": decal \"eye\" and \"target\" coincide");
  f.forward = dir / len;
  const double up_len = camera.up.norm();
  const Vec3 r = f.forward.cross(camera.up);
  if (!(up_len > 0.0) || !(r.norm() > 1e-9 * up_len))
    throw InvalidInputError(where + ": decal \"up\" is zero or parallel to the viewing direction");
  f.right = r.normalized();
  f.up = f.right.cross(f.forward);
  f.tan_half_y = std::tan(camera.fov_y_degrees * std::numbers::pi / 360.0);
  f.tan_half_x = camera.aspect * f.tan_half_y;
  return f;
}

bool DecalFrame::project(const Vec3& p, Vec2& uv, double& depth) const {
  const Vec3 d = p - eye;
  depth = d.dot(forward);
  if (!(depth > 0.0)) return false;
  const double x = d.dot(right) / (depth * tan_half_x);  // in [-1, 1] inside the frustum
  const double y = d.dot(up) / (depth * tan_half_y);
  uv = Vec2(0.5 * (x + 1.0), 0.5 * (y + 1.0));
  return true;
}

Eigen::Vector4d sample_decal_image(const ImageRGBA8& image, double u, double v) {
  const int w = image.width, h = image.height;
  // Continuous texel coordinates: texel i is centred at (i + 0.5) / W.
  const double x = std::clamp(u * w - 0.5, 0.0, static_cast<double>(w - 1));
  const double y = std::clamp(v * h - 0.5, 0.0, static_cast<double>(h - 1));
  const int i0 = std::min(static_cast<int>(x), w - 1), j0 = std::min(static_cast<int>(y), h - 1);
  const int i1 = std::min(i0 + 1, w - 1), j1 = std::min(j0 + 1, h - 1);
  const double fx = x - i0, fy = y - j0;
  const double wts[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
  const std::uint8_t* px[4] = {image.texel(i0, j0), image.texel(i1, j0), image.texel(i0, j1),
                               image.texel(i1, j1)};
  Eigen::Vector3d premul = Eigen::Vector3d::Zero();
  double alpha = 0.0;
  for (int k = 0; k < 4; ++k) {
    const double a = wts[k] * (px[k][3] / 255.0);
    premul += a * Eigen::Vector3d(px[k][0], px[k][1], px[k][2]) / 255.0;
    alpha += a;
  }
  if (alpha <= 0.0) return Eigen::Vector4d::Zero();
  const Eigen::Vector3d rgb = (premul / alpha).cwiseMin(1.0).cwiseMax(0.0);
  return Eigen::Vector4d(rgb.x(), rgb.y(), rgb.z(), std::min(alpha, 1.0));
}

// ------------------------------------------------------------------------------------------------

namespace {

/// The visibility ray eye -> p: t = 1 at p, stopped a relative epsilon short of it.
RayScene::Ray make_ray(const Vec3& eye, const Vec3& p) {
  return {eye, p - eye, 0.0f, static_cast<float>(1.0 - kDecalRayEpsilon)};
}

}  // namespace

struct DecalProjector::Impl {
  RayScene scene;
};

DecalProjector::DecalProjector(const TriMesh& mesh) {
  if (mesh.faces.empty()) throw InvalidInputError("decal: the mesh has no faces");
  // High build quality: a stroke casts a ray per texel, far more rays than the BVH has triangles.
  impl_ = std::make_unique<Impl>(Impl{RayScene(mesh, {.single_thread = false, .high_quality = true}, "decal")});
}

DecalProjector::~DecalProjector() = default;
DecalProjector::DecalProjector(DecalProjector&&) noexcept = default;
DecalProjector& DecalProjector::operator=(DecalProjector&&) noexcept = default;

bool DecalProjector::visible(const Vec3& eye, const Vec3& p) const { return !impl_->scene.occluded(make_ray(eye, p)); }

namespace {

/// Everything evaluate() needs from a decal stroke, validated once per call / batch.
struct PreparedDecal {
  const Stroke* stroke = nullptr;
  DecalFrame frame;
  bool active = false;  // false: brush stroke or zero opacity: nothing to paint
};

PreparedDecal prepare(const Stroke& decal) {
  PreparedDecal d;
  d.stroke = &decal;
  if (decal.type != Stroke::Type::Decal) return d;
  d.frame = decal_frame(decal.camera);
  if (decal.image.empty()) throw InvalidInputError("decal: the decal image is empty");
  d.active = decal.opacity > 0.0;
  return d;
}

/// Colour and coverage of the decal at p before the visibility test: frustum, image, opacity.
/// \return false where nothing is painted whether p is visible or not.
bool unoccluded_value(const PreparedDecal& d, const Vec3& p, int face, Eigen::Vector4d& c) {
  if (!d.active || face < 0) return false;
  Vec2 uv;
  double depth;
  if (!d.frame.project(p, uv, depth)) return false;
  if (uv.x() < 0.0 || uv.x() > 1.0 || uv.y() < 0.0 || uv.y() > 1.0) return false;
  c = sample_decal_image(d.stroke->image, uv.x(), uv.y());
  c.w() *= d.stroke->opacity;
  return c.w() > 0.0;
}

}  // namespace

Eigen::Vector4d DecalProjector::evaluate(const Stroke& decal, const Vec3& p, int face) const {
  Eigen::Vector4d c;
  if (!unoccluded_value(prepare(decal), p, face, c) || !visible(decal.camera.eye, p))
    return Eigen::Vector4d::Zero();
  return c;
}

namespace {

/// Evaluates points [begin, end) of a batch: frustum + image first, then one ray stream (coherent:
/// neighbouring texels give neighbouring rays) for the candidates.
/// \p point(k) / \p face(k) give the inputs, \p store(k, value) the output (zero is pre-stored).
template <class PointFn, class FaceFn, class StoreFn>
void evaluate_block(const PreparedDecal& d, const RayScene& scene, size_t begin, size_t end, PointFn point,
                    FaceFn face, StoreFn store) {
  std::vector<RayScene::Ray> rays;
  std::vector<size_t> which;
  rays.reserve(end - begin);
  which.reserve(end - begin);
  for (size_t k = begin; k < end; ++k) {
    const Vec3 p = point(k);
    Eigen::Vector4d c;
    if (!unoccluded_value(d, p, face(k), c)) continue;
    store(k, c);
    rays.push_back(make_ray(d.frame.eye, p));
    which.push_back(k);
  }
  if (rays.empty()) return;
  std::vector<char> blocked(rays.size());
  scene.occluded(rays, blocked);
  for (size_t m = 0; m < rays.size(); ++m)
    if (blocked[m]) store(which[m], Eigen::Vector4d::Zero());
}

}  // namespace

void DecalProjector::evaluate(const Stroke& decal, std::span<const Vec3> points,
                              std::span<const int> faces, std::span<Eigen::Vector4d> out) const {
  if (points.size() != faces.size() || points.size() != out.size())
    throw InvalidInputError("decal: evaluate: points, faces and out differ in size");
  const PreparedDecal d = prepare(decal);
  std::fill(out.begin(), out.end(), Eigen::Vector4d::Zero());
  if (!d.active) return;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 1024),
                    [&](const tbb::blocked_range<size_t>& r) {
                      evaluate_block(
                          d, impl_->scene, r.begin(), r.end(), [&](size_t k) { return points[k]; },
                          [&](size_t k) { return faces[k]; },
                          [&](size_t k, const Eigen::Vector4d& v) { out[k] = v; });
                    });
}

void DecalProjector::evaluate_texels(const Stroke& decal, const TexelMap& map,
                                     std::vector<Eigen::Vector4f>& out) const {
  const PreparedDecal d = prepare(decal);
  out.assign(map.inside.size(), Eigen::Vector4f::Zero());
  if (!d.active) return;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, map.inside.size(), 1024),
                    [&](const tbb::blocked_range<size_t>& r) {
                      evaluate_block(
                          d, impl_->scene, r.begin(), r.end(),
                          [&](size_t k) { return Vec3(map.position[map.inside[k]].cast<double>()); },
                          [&](size_t k) { return map.face[map.inside[k]]; },
                          [&](size_t k, const Eigen::Vector4d& v) { out[k] = v.cast<float>(); });
                    });
}

}  // namespace adaptex
