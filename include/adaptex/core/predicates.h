#pragma once
/// \file predicates.h
/// Filtered geometric predicates in the plane. A static error bound (Shewchuk 1997, "Adaptive
/// precision floating-point arithmetic and fast robust geometric predicates", the first stage of
/// orient2d) certifies the sign of a determinant; where it cannot, the predicate answers 0, so a
/// caller that treats 0 as "maybe" is conservative but never wrong.
#include <cmath>

#include "adaptex/core/types.h"

namespace adaptex {

/// Sign of the orientation of \p c relative to the directed line \p a -> \p b: +1 left
/// (counter-clockwise), -1 right, 0 when the static filter cannot certify the sign (c is on the
/// line up to rounding).
/// \pre finite coordinates
/// \throw nothing
inline int orient2d_filtered(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double l = (a.x() - c.x()) * (b.y() - c.y());
  const double r = (a.y() - c.y()) * (b.x() - c.x());
  const double det = l - r;
  const double bound = 3.3306690738754716e-16 * (std::abs(l) + std::abs(r));
  return det > bound ? 1 : det < -bound ? -1 : 0;
}

/// The z component of the cross product of \p a and \p b (twice the signed area of 0, a, b).
/// \throw nothing
inline double cross2d(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Signed area of the triangle \p a, \p b, \p c: positive when counter-clockwise. Unfiltered (see
/// orient2d_filtered() for a certified sign).
/// \throw nothing
inline double triangle_signed_area(const Vec2& a, const Vec2& b, const Vec2& c) {
  return 0.5 * ((b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x()));
}

}  // namespace adaptex
