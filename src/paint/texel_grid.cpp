/// \file texel_grid.cpp
/// Internal spatial index of texel points (see texel_grid.h).
#include "texel_grid.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>

namespace adaptex::detail {

namespace {

/// LSD radix sort of (key, value) pairs on the low \p bits bits of the key, 11 bits per pass.
void radix_sort(std::vector<std::uint64_t>& keys, std::vector<int>& values, int bits) {
  const size_t n = keys.size();
  std::vector<std::uint64_t> k2(n);
  std::vector<int> v2(n);
  constexpr int kDigit = 11;
  std::vector<std::uint32_t> count(1u << kDigit);
  for (int shift = 0; shift < bits; shift += kDigit) {
    std::fill(count.begin(), count.end(), 0u);
    for (size_t i = 0; i < n; ++i) ++count[(keys[i] >> shift) & ((1u << kDigit) - 1)];
    std::uint32_t sum = 0;
    for (auto& c : count) {
      const std::uint32_t t = c;
      c = sum;
      sum += t;
    }
    for (size_t i = 0; i < n; ++i) {
      const std::uint32_t d = count[(keys[i] >> shift) & ((1u << kDigit) - 1)]++;
      k2[d] = keys[i];
      v2[d] = values[i];
    }
    keys.swap(k2);
    values.swap(v2);
  }
}

}  // namespace

TexelGrid::TexelGrid(const std::vector<Vec3f>& points, double spacing) {
  const size_t n = points.size();
  if (n == 0) return;
  using Box = std::pair<Eigen::Vector3f, Eigen::Vector3f>;
  const Box box = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, n, 1 << 14), Box(points[0], points[0]),
      [&](const tbb::blocked_range<size_t>& r, Box b) {
        for (size_t k = r.begin(); k < r.end(); ++k) {
          b.first = b.first.cwiseMin(points[k]);
          b.second = b.second.cwiseMax(points[k]);
        }
        return b;
      },
      [](const Box& a, const Box& b) { return Box(a.first.cwiseMin(b.first), a.second.cwiseMax(b.second)); });
  const Vec3 lo = box.first.cast<double>(), hi = box.second.cast<double>();
  origin_ = lo;
  const double extent = (hi - lo).maxCoeff();
  cell_ = std::max({2.0 * spacing, extent / ((1 << 21) - 2), 1e-300});
  const double top = std::min<double>((1 << 21) - 1, std::floor(extent / cell_) + 1);
  int axis_bits = 1;
  while (axis_bits < 21 && std::ldexp(1.0, axis_bits) <= top) ++axis_bits;
  std::vector<std::uint64_t> keys(n);
  std::vector<int> idx(n);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1 << 14), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t k = r.begin(); k < r.end(); ++k) {
      const Vec3 p = points[k].cast<double>();
      std::uint32_t q[3];
      for (int a = 0; a < 3; ++a) q[a] = static_cast<std::uint32_t>(std::clamp(std::floor((p[a] - lo[a]) / cell_), 0.0, top));
      keys[k] = morton3(q[0], q[1], q[2]);
      idx[k] = static_cast<int>(k);
    }
  });
  radix_sort(keys, idx, 3 * axis_bits);
  order_ = std::move(idx);
  pos_.resize(n);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1 << 14), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t s = r.begin(); s < r.end(); ++s) {
      const Vec3f& p = points[order_[s]];
      pos_[s] = P3{p.x(), p.y(), p.z()};
    }
  });
  // Runs of level 0, then each coarser level from the runs of the finer one.
  std::vector<CellHash::Run> runs;
  for (size_t k = 0; k < n;) {
    size_t e = k + 1;
    while (e < n && keys[e] == keys[k]) ++e;
    runs.push_back({keys[k], static_cast<std::uint32_t>(k), static_cast<std::uint32_t>(e)});
    k = e;
  }
  for (int L = 0; L <= kMaxLevel; ++L) {
    levels_[L] = CellHash(runs);
    if (L == kMaxLevel) break;
    std::vector<CellHash::Run> coarse;
    for (const CellHash::Run& r : runs) {
      const std::uint64_t key = r.key >> 3;
      if (!coarse.empty() && coarse.back().key == key)
        coarse.back().end = r.end;
      else
        coarse.push_back({key, r.begin, r.end});
    }
    runs.swap(coarse);
  }
}

}  // namespace adaptex::detail
