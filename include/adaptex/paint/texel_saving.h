#pragma once
/// \file texel_saving.h
/// Texel saving factor of an adaptive parameterization (docs/quality.md): the
/// texture area that the fixed layout (`none`) needs to reach the adaptive method's PSNR at N x N,
/// relative to N x N. PSNR of `none` is taken as piecewise linear in log2(size) through its values at
/// N, 2N and 4N (Sander et al. 2002 report such savings as "texture size needed for equal error").
#include <array>

namespace adaptex {

/// Result of texel_saving_factor().
struct TexelSaving {
  /// (N'/N)^2, where N' is the size at which `none` reaches the target PSNR; in [0.25, inf).
  double factor = 1;
  bool above_range = false;  ///< Target above none@4N: extrapolated with the 2N -> 4N slope (a lower bound "> f").
  bool clamped = false;      ///< Target so far below none@N that the factor was clamped to 0.25.
  bool lossless = false;     ///< Both the method and none@N are >= the lossless level: counted as equal (1).
};

/// Settings of texel_saving_factor().
struct TexelSavingOptions {
  double lossless_db = 50;  ///< PSNR at or above which two results count as equal (visually lossless).
  double min_factor = 0.25; ///< Lower clamp of the factor (none at N/2).
};

/// Texel saving factor of a method with PSNR \p psnr at N, given \p psnr_none = PSNR of `none` at
/// N, 2N, 4N (dB). With x = log2(N'/N): none(x) is linear on [0, 1] and [1, 2] (made non-decreasing
/// by a running maximum: a step that lost PSNR counts as flat); below 0 it is extrapolated with the
/// [0, 1] slope, above 2 with the [1, 2] slope; the target is min(psnr, lossless_db); factor = 4^x,
/// clamped to >= min_factor. With no usable slope the factor is min_factor below none@N and 4^2
/// (marked above_range) above none@4N.
/// \pre all inputs finite. \throw InvalidInputError a non-finite input or min_factor outside (0, 1]
TexelSaving texel_saving_factor(double psnr, const std::array<double, 3>& psnr_none,
                                const TexelSavingOptions& options = {});

/// True when a method with PSNR \p psnr is worse than `none` at the same size (\p psnr_none_n) by more
/// than \p tolerance_db, unless both are >= \p lossless_db (counted as equal).
bool worse_than_none(double psnr, double psnr_none_n, double tolerance_db = 0.1, double lossless_db = 50);

}  // namespace adaptex
