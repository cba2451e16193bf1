#pragma once
/// \file ray_scene.h
/// A triangle mesh in an Embree 3 BVH with robust traversal (rays through shared edges or vertices
/// cannot slip between two triangles): closest hits and occlusion tests, one ray or a coherent batch.
/// The one Embree wrapper of adaptex: decal visibility (decal.h) and the studio's picking.
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "adaptex/core/mesh.h"

namespace adaptex {

/// Builds the BVH once per mesh (the mesh is copied into it); queries are thread-safe.
class RayScene {
 public:
  struct Options {
    bool single_thread = false;  ///< Embree device with one thread (false: Embree's default).
    bool high_quality = false;   ///< High BVH build quality: slower build, faster queries.
  };
  /// A ray origin + t · dir for t in [tnear, tfar] (single precision in Embree).
  struct Ray {
    Vec3 origin = Vec3::Zero(), dir = Vec3::Zero();
    float tnear = 0.0f, tfar = 0.0f;
  };
  /// The closest hit: face and Embree's barycentrics (p = (1-u-v) p0 + u p1 + v p2).
  struct Hit {
    int face = -1;
    float u = 0, v = 0;
  };

  /// \p who names the caller in errors. A mesh without faces gives an empty scene (every ray misses).
  /// \pre mesh has valid indices \throw Error if Embree fails
  RayScene(const TriMesh& mesh, const Options& options, const std::string& who);
  ~RayScene();
  RayScene(RayScene&&) noexcept;
  RayScene& operator=(RayScene&&) noexcept;

  /// Closest hit along \p ray (nullopt: it misses).
  std::optional<Hit> intersect(const Ray& ray) const;
  /// True if \p ray hits any triangle.
  bool occluded(const Ray& ray) const;
  /// occluded() of every ray of \p rays, as one coherent stream (neighbouring rays should be close):
  /// out[k] = 1 if rays[k] is occluded, else 0. \pre out.size() == rays.size()
  void occluded(std::span<const Ray> rays, std::span<char> out) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace adaptex
