/// \file texel_grid.cpp
/// Internal spatial index of texel points (see texel_grid.h).
#include "texel_grid.h"

#include <tbb/parallel_sort.h>

#include <algorithm>
#include <numeric>

namespace adaptex::detail {

TexelGrid::TexelGrid(const std::vector<Vec3f>& points, double spacing) {
  const size_t n = points.size();
  if (n == 0) return;
  Vec3 lo = points[0].cast<double>(), hi = lo;
  for (const Vec3f& p : points) {
    lo = lo.cwiseMin(p.cast<double>());
    hi = hi.cwiseMax(p.cast<double>());
  }
  origin_ = lo;
  const double extent = (hi - lo).maxCoeff();
  cell_ = std::max({2.0 * spacing, extent / ((1 << 21) - 2), 1e-300});
  std::vector<std::pair<std::uint64_t, int>> keyed(n);
  auto coord = [&](double v, double o) {
    return static_cast<std::uint32_t>(std::clamp(std::floor((v - o) / cell_), 0.0, double((1 << 21) - 1)));
  };
  for (size_t k = 0; k < n; ++k) {
    const Vec3 p = points[k].cast<double>();
    keyed[k] = {morton3(coord(p.x(), lo.x()), coord(p.y(), lo.y()), coord(p.z(), lo.z())), static_cast<int>(k)};
  }
  tbb::parallel_sort(keyed.begin(), keyed.end());
  order_.resize(n);
  pos_.resize(n);
  codes_.resize(n);
  for (size_t s = 0; s < n; ++s) {
    codes_[s] = keyed[s].first;
    order_[s] = keyed[s].second;
    const Vec3f& p = points[order_[s]];
    pos_[s] = P3{p.x(), p.y(), p.z()};
  }
}

void TexelGrid::ensure_level(int L) const {
  std::call_once(once_[L], [&] { levels_[L] = std::make_unique<CellHash>(codes_, 3 * L); });
}

}  // namespace adaptex::detail
