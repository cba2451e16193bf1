#pragma once
/// \file ray_caster.h
/// CPU picking for adaptex-studio: ray casting against the mesh (paint/ray_scene.h; closest hit = the
/// visible surface under the cursor), with the hit's face, barycentric coordinates and facing.
#include <memory>
#include <optional>

#include "adaptex/core/mesh.h"
#include "adaptex/paint/ray_scene.h"
#include "camera.h"

namespace adaptex::studio {

/// A ray-surface hit.
struct Hit {
  int face = -1;
  double b0 = 0, b1 = 0;  ///< Barycentrics of corners 0 and 1 (corner 2: 1 - b0 - b1).
  double t = 0;           ///< Distance along the ray.
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::Zero();  ///< Unit face normal, oriented to the mesh's outside.
  bool front_facing = true;    ///< The ray sees the outside of the surface.
};

/// Builds the ray scene once per mesh; intersect() is thread-safe.
class RayCaster {
 public:
  /// \pre mesh stays alive and unchanged while the caster is used.
  explicit RayCaster(const TriMesh& mesh);
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  /// Closest hit along \p ray (nullopt: the ray misses).
  std::optional<Hit> intersect(const Ray& ray) const;
  /// +1 if the faces are wound CCW seen from outside (positive signed volume), -1 otherwise.
  int orientation() const { return orientation_; }

 private:
  RayScene scene_;
  const TriMesh& mesh_;
  int orientation_ = 1;
};

}  // namespace adaptex::studio
