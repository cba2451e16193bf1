// Distances between UV triangles for the packing and unwrap tests.
#pragma once

#include <algorithm>
#include <array>
#include <limits>

#include "adaptex/core/types.h"

namespace adaptex::test {

using Tri = std::array<Vec2, 3>;

inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Separating-axis test over the six edge normals: true if the closed triangles share a point.
inline bool triangles_meet(const Tri& a, const Tri& b) {
  for (const Tri* t : {&a, &b})
    for (int i = 0; i < 3; ++i) {
      const Vec2 e = (*t)[(i + 1) % 3] - (*t)[i];
      const Vec2 nrm(-e.y(), e.x());
      double a0 = 1e300, a1 = -1e300, b0 = 1e300, b1 = -1e300;
      for (const Vec2& p : a) a0 = std::min(a0, nrm.dot(p)), a1 = std::max(a1, nrm.dot(p));
      for (const Vec2& p : b) b0 = std::min(b0, nrm.dot(p)), b1 = std::max(b1, nrm.dot(p));
      if (nrm.squaredNorm() > 0 && (a1 < b0 || b1 < a0)) return false;
    }
  return true;
}

/// Distance from \p p to the segment [a, b].
inline double point_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double t = d.squaredNorm() > 0 ? std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
  return (p - (a + t * d)).norm();
}

/// Distance between two disjoint triangles: the least distance between their edges.
inline double triangle_distance(const Tri& a, const Tri& b) {
  double d = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      d = std::min(d, point_segment(a[i], b[j], b[(j + 1) % 3]));
      d = std::min(d, point_segment(b[j], a[i], a[(i + 1) % 3]));
    }
  return d;
}

}  // namespace adaptex::test
