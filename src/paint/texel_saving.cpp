/// \file texel_saving.cpp
/// Texel saving factor: inverse of the fixed layout's PSNR curve, piecewise linear in log2(size).
#include "adaptex/paint/texel_saving.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "adaptex/core/errors.h"

namespace adaptex {

TexelSaving texel_saving_factor(double psnr, const std::array<double, 3>& psnr_none,
                                const TexelSavingOptions& options) {
  const auto [p0, p1, p2] = psnr_none;
  if (!std::isfinite(psnr) || !std::isfinite(p0) || !std::isfinite(p1) || !std::isfinite(p2))
    throw InvalidInputError("texel_saving_factor: PSNR values must be finite");
  if (!(options.min_factor > 0 && options.min_factor <= 1))
    throw InvalidInputError("texel_saving_factor: min_factor must be in (0, 1], got " +
                            std::to_string(options.min_factor));
  TexelSaving r;
  const double lossless = options.lossless_db;
  if (psnr >= lossless && p0 >= lossless) {
    r.lossless = true;
    return r;
  }
  const double target = std::min(psnr, lossless);
  const double x_min = std::log(options.min_factor) / std::log(4.0);
  // Running maximum: a size step that lost PSNR (noise at lossless levels) counts as flat.
  const double q0 = p0, q1 = std::max(q0, p1), q2 = std::max(q1, p2);
  double x;
  if (target < q0) {  // worse than none@N: extrapolate down with the N -> 2N slope
    x = q1 > q0 ? (target - q0) / (q1 - q0) : x_min;
  } else if (target <= q1) {
    x = q1 > q0 ? (target - q0) / (q1 - q0) : 0;
  } else if (target <= q2) {
    x = 1 + (target - q1) / (q2 - q1);
  } else {  // above none@4N: extrapolate with the 2N -> 4N slope, a lower bound
    r.above_range = true;
    x = q2 > q1 ? 2 + (target - q2) / (q2 - q1) : 2;
  }
  if (target < q0 && x <= x_min) {
    x = x_min;
    r.clamped = true;
  }
  r.factor = std::pow(4.0, x);
  return r;
}

bool worse_than_none(double psnr, double psnr_none_n, double tolerance_db, double lossless_db) {
  if (psnr >= lossless_db && psnr_none_n >= lossless_db) return false;
  return psnr < psnr_none_n - tolerance_db;
}

}  // namespace adaptex
