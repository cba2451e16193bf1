#pragma once
/// \file ls2.h
/// L_s² of thesis §3.6: 1 − L2 where E_h = 0, else 1 − (α·L2 + β·E_h), clamped to [min_weight, 1].
#include "adaptex/core/image.h"

namespace adaptex {

/// Settings of compute_ls2().
struct Ls2Options {
  double alpha = 1.0;        ///< Weight of the geometry stretch where there is signal.
  /// Scale s of the normalized geometry stretch (L2 ← s·L2n); 1 = the thesis as written.
  double geometry_scale = 1.0;
  double beta = 0.95;        ///< Weight of the signal stretch E_h.
  double min_weight = 0.02;  ///< Lower clamp of L_s² (strictly positive).
  double zero_signal = 1.0 / 512.0;  ///< E_h at or below this counts as "E_h = 0" (8-bit noise).
};

/// L_s² per texel (\p stretch empty: L2 = 0, Fig. 3.9e). \pre stretch empty or importance's size
/// \throw InvalidInputError size mismatch, α/β negative or NaN, min_weight not in (0, 1]
ImageF compute_ls2(const ImageF& importance, const ImageF& stretch, const Ls2Options& options = {});

/// How pool_for_grid() reduces a block of texels.
enum class PoolMode {
  None,  ///< No pooling: the grid samples the full-resolution map.
  Mean,  ///< Box average (default).
  Min,   ///< Minimum weight (= maximum signal) of the block.
};

/// \p map reduced to min(size, 2·cells) per side by mean / min, so a grid point sees its cell's footprint.
/// \pre cells >= 1
ImageF pool_for_grid(const ImageF& map, int cells, PoolMode mode = PoolMode::Mean);

}  // namespace adaptex
