#pragma once
// Internal to the paint area: one layer's stroke arithmetic (docs/strokes.md, "Version 2"), shared by
// the exact evaluation (material_signal.cpp) and the incremental point cache (material_point_cache.cpp).
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "adaptex/paint/material_strokes.h"

namespace adaptex::material_detail {

/// Radius and opacity of dab \p i after the pressure curves.
inline void dab_shape(const MaterialStroke& s, size_t i, double& radius, double& opacity) {
  const double p = s.pressure.empty() ? 1.0 : s.pressure[i];
  radius = s.radius * s.radius_curve(p);
  opacity = s.opacity * s.opacity_curve(p);
}

/// Dabs of one stroke in a uniform grid of cell size = the largest dab radius: a point meets only the
/// dabs of its 27 neighbouring cells.
class DabGrid {
 public:
  explicit DabGrid(const MaterialStroke& s) : stroke_(s) {
    const size_t n = s.dabs.size();
    radius_.resize(n);
    opacity_.resize(n);
    lo_ = Vec3::Constant(INFINITY);
    hi_ = Vec3::Constant(-INFINITY);
    for (size_t i = 0; i < n; ++i) {
      dab_shape(s, i, radius_[i], opacity_[i]);
      cell_ = std::max(cell_, radius_[i]);
      lo_ = lo_.cwiseMin(s.dabs[i]);
      hi_ = hi_.cwiseMax(s.dabs[i]);
    }
    lo_.array() -= cell_;
    hi_.array() += cell_;
    if (!(cell_ > 0)) return;  // every dab has radius 0: nothing painted
    for (size_t i = 0; i < n; ++i)
      if (radius_[i] > 0 && opacity_[i] > 0) cells_[key(cell_of(s.dabs[i]))].push_back(static_cast<int>(i));
  }
  /// Coverage at \p p: max over dabs of opacity * falloff.
  double coverage(const Vec3& p) const {
    if (cells_.empty() || (p.array() < lo_.array()).any() || (p.array() > hi_.array()).any()) return 0;
    const Eigen::Vector3i c = cell_of(p);
    double alpha = 0;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          auto it = cells_.find(key(c + Eigen::Vector3i(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (int i : it->second) {
            const double t = (p - stroke_.dabs[i]).norm() / radius_[i];
            if (t < 1) alpha = std::max(alpha, opacity_[i] * brush_falloff(t, stroke_.hardness));
          }
        }
    return alpha;
  }

 private:
  Eigen::Vector3i cell_of(const Vec3& p) const {
    return ((p - lo_) / cell_).array().floor().cast<int>().matrix();
  }
  static std::uint64_t key(const Eigen::Vector3i& c) {
    const auto u = [](int v) { return static_cast<std::uint64_t>(static_cast<std::uint32_t>(v) & 0x1fffff); };
    return u(c.x()) | u(c.y()) << 21 | u(c.z()) << 42;
  }
  const MaterialStroke& stroke_;
  std::vector<double> radius_, opacity_;
  double cell_ = 0;
  Vec3 lo_, hi_;
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
};

/// Applies a paint (the stroke's values with coverage \p alpha; \p rgb: a decal's image colour, painted
/// as base colour when MaterialStroke::image_color, else null) or an erase to one point's layer state (L, a).
void apply_stroke(const MaterialStroke& s, double alpha, const double* rgb, MaterialValue& L,
                  std::array<double, kNumChannels>& a);
/// Blends one layer's point state (L, a, mask) over the result \p R.
void blend_layer(const MaterialLayer& layer, const MaterialValue& L, const std::array<double, kNumChannels>& a,
                 double mask, MaterialValue& R);
/// A fill's opacity, or the dabs' coverage at \p p (\p grid: the stroke's).
double fill_or_dab_coverage(const MaterialStroke& s, const DabGrid* grid, const Vec3& p);
/// The value a mask stroke paints: its own, or the mask's start value for an eraser.
double mask_stroke_value(const LayerMask& mask, const MaterialStroke& s);

}  // namespace adaptex::material_detail
