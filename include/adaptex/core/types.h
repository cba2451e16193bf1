#pragma once
/// \file types.h
/// Basic geometric types shared by every area of adaptex.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <limits>

namespace adaptex {

using Vec2 = Eigen::Vector2d;  ///< A point or vector in the (u,v) domain.
using Vec3 = Eigen::Vector3d;  ///< A point or vector in world space (the mesh's own units).
using Vec3f = Eigen::Vector3f;

/// Positive infinity (an unreached distance, an unbounded stretch).
inline constexpr double kInf = std::numeric_limits<double>::infinity();

/// A triangle: three vertex indices, counter-clockwise seen from the front.
using Face = std::array<int, 3>;

/// Axis-aligned bounding box in world space.
struct BoundingBox {
  Vec3 min = Vec3::Constant(0.0);  ///< Smallest x, y, z over the vertices.
  Vec3 max = Vec3::Constant(0.0);  ///< Largest x, y, z over the vertices.
  /// Length of the diagonal (0 for an empty box).
  double diagonal() const { return (max - min).norm(); }
};

}  // namespace adaptex
