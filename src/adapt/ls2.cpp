// L_s² of thesis §3.6 and its pooling to a grid's scale.
#include "adaptex/adapt/ls2.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "adaptex/core/errors.h"

namespace adaptex {

ImageF compute_ls2(const ImageF& importance, const ImageF& stretch, const Ls2Options& o) {
  if (importance.width <= 0 || importance.height <= 0) throw InvalidInputError("compute_ls2: empty importance map");
  const bool has_stretch = !stretch.data.empty();
  if (has_stretch && (stretch.width != importance.width || stretch.height != importance.height))
    throw InvalidInputError("compute_ls2: stretch map " + std::to_string(stretch.width) + "x" +
                            std::to_string(stretch.height) + " differs from importance map " +
                            std::to_string(importance.width) + "x" + std::to_string(importance.height));
  if (!(o.alpha >= 0) || !(o.beta >= 0) || !std::isfinite(o.alpha) || !std::isfinite(o.beta))
    throw InvalidInputError("L_s2: alpha and beta must be finite and >= 0");
  if (!(o.geometry_scale >= 0) || !std::isfinite(o.geometry_scale))
    throw InvalidInputError("L_s2: geometry_scale must be finite and >= 0");
  if (!(o.min_weight > 0 && o.min_weight <= 1))
    throw InvalidInputError("L_s2: min_weight must be in (0, 1]");
  ImageF out(importance.width, importance.height);
  const float lo = static_cast<float>(o.min_weight);
  tbb::parallel_for(size_t(0), out.data.size(), [&](size_t k) {
    const double e = importance.data[k];
    const double l2 = has_stretch ? o.geometry_scale * stretch.data[k] : 0.0;
    const double w = e <= o.zero_signal ? 1.0 - l2 : 1.0 - (o.alpha * l2 + o.beta * e);
    out.data[k] = std::clamp(static_cast<float>(w), lo, 1.0f);
  });
  return out;
}

ImageF pool_for_grid(const ImageF& map, int cells, PoolMode mode) {
  if (cells < 1) throw InvalidInputError("pool_for_grid: cells must be >= 1");
  if (mode == PoolMode::None) return map;
  const int rw = std::min(map.width, 2 * cells), rh = std::min(map.height, 2 * cells);
  if (rw == map.width && rh == map.height) return map;
  ImageF out(rw, rh, mode == PoolMode::Min ? 2.0f : 0.0f);
  std::vector<float> count(static_cast<size_t>(rw) * rh, 0.0f);
  // Output texel of an input texel centre: floor((i + 0.5) * rw / W).
  tbb::parallel_for(0, rh, [&](int oj) {
    const int j0 = static_cast<int>(std::ceil(static_cast<double>(oj) * map.height / rh - 0.5));
    const int j1 = static_cast<int>(std::ceil(static_cast<double>(oj + 1) * map.height / rh - 0.5));
    for (int j = std::max(0, j0); j < std::min(map.height, j1); ++j)
      for (int i = 0; i < map.width; ++i) {
        const int oi = std::min(rw - 1, static_cast<int>((i + 0.5) * rw / map.width));
        const size_t o = static_cast<size_t>(oj) * rw + oi;
        const float v = map.at(i, j);
        if (mode == PoolMode::Min) out.data[o] = std::min(out.data[o], v);
        else out.data[o] += v;
        count[o] += 1;
      }
  });
  for (size_t k = 0; k < out.data.size(); ++k) {
    if (count[k] == 0) out.data[k] = 1.0f;
    else if (mode == PoolMode::Mean) out.data[k] /= count[k];
  }
  return out;
}

}  // namespace adaptex
