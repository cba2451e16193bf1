#pragma once
/// \file texel_grid.h
/// Internal: spatial index of the 3-D points of the texels of a TexelMap, so that a dab visits only
/// the texels near it. Texels are sorted by the Morton code of a fine uniform grid; a coarse cell of
/// level L (2^L fine cells per side) is then a contiguous range, found through a per-level hash.
/// A ball query of radius r uses the level whose cell size is in (r/2, r].
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "adaptex/core/types.h"
#include "cell_hash.h"

namespace adaptex::detail {

class TexelGrid {
 public:
  struct P3 {
    float x, y, z;
  };
  static constexpr int kMaxLevel = 21;

  /// \p points: the 3-D points (any order); \p spacing: typical distance between neighbouring points.
  TexelGrid(const std::vector<Vec3f>& points, double spacing);

  /// Number of points.
  int size() const { return static_cast<int>(order_.size()); }
  /// Slot s (sorted order) holds input point order()[s].
  const std::vector<int>& order() const { return order_; }
  const std::vector<P3>& sorted_points() const { return pos_; }

  /// Level used for radius r: cell size in (r/2, r] (or the finest level).
  int level_for(double r) const {
    int L = 0;
    while (L < kMaxLevel && cell_ * std::ldexp(1.0, L + 1) <= r) ++L;
    return L;
  }

  /// Calls fn(slot, squared distance) for every point with |p - c| < r.
  template <class Fn>
  void for_each_in_ball(const Vec3& c, double r, Fn&& fn) const {
    if (pos_.empty()) return;
    const int L = level_for(r);
    const CellHash& table = levels_[L];
    const double cs = cell_ * std::ldexp(1.0, L);
    const double r2 = r * r;
    std::int64_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      const double top = std::ldexp(1.0, 21 - L) - 1;
      lo[a] = static_cast<std::int64_t>(std::clamp(std::floor((c[a] - r - origin_[a]) / cs), 0.0, top));
      hi[a] = static_cast<std::int64_t>(std::clamp(std::floor((c[a] + r - origin_[a]) / cs), 0.0, top));
    }
    const float cx = static_cast<float>(c.x()), cy = static_cast<float>(c.y()), cz = static_cast<float>(c.z());
    const float fr2 = static_cast<float>(r2);
    for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
      const double dz = axis_gap(c.z() - origin_[2], z, cs);
      for (std::int64_t y = lo[1]; y <= hi[1]; ++y) {
        const double dy = axis_gap(c.y() - origin_[1], y, cs);
        if (dz * dz + dy * dy >= r2) continue;
        for (std::int64_t x = lo[0]; x <= hi[0]; ++x) {
          const double dx = axis_gap(c.x() - origin_[0], x, cs);
          if (dz * dz + dy * dy + dx * dx >= r2) continue;
          std::uint32_t b, e;
          table.find(morton3(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y),
                             static_cast<std::uint32_t>(z)),
                     b, e);
          for (std::uint32_t s = b; s < e; ++s) {
            const P3& p = pos_[s];
            const float ex = p.x - cx, ey = p.y - cy, ez = p.z - cz;
            const float d2 = ex * ex + ey * ey + ez * ez;
            if (d2 < fr2) fn(static_cast<int>(s), d2);
          }
        }
      }
    }
  }

 private:
  /// Distance along one axis from coordinate v to the cell [k cs, (k+1) cs].
  static double axis_gap(double v, std::int64_t k, double cs) {
    const double a = k * cs, b = a + cs;
    return v < a ? a - v : (v > b ? v - b : 0.0);
  }
  Vec3 origin_ = Vec3::Zero();
  double cell_ = 1;  // fine cell size
  std::vector<int> order_;
  std::vector<P3> pos_;
  std::array<CellHash, kMaxLevel + 1> levels_;  // all built by the constructor
};

}  // namespace adaptex::detail
