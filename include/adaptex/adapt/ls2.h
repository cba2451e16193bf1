#pragma once
/// \file ls2.h
/// The L_s² weight of thesis §3.6, combining geometry stretch L2 (stretch_map.h) and signal stretch
/// E_h (importance.h), both in [0,1]:
///     L_s² = 1 − L2                  where E_h = 0,
///     L_s² = 1 − (α·L2 + β·E_h)      elsewhere,
/// clamped to [min_weight, 1] with min_weight > 0: the relaxation divides by sums of weights and a
/// non-positive weight would pull grid points outside their ring (folds). High L_s² = low signal = the
/// grid gathers there = less texture space.
///
/// Sampling at the grid's scale: a grid point of a coarse grid must "see" the thin strokes between
/// it and its neighbours, so before relaxation the L_s² map is pooled over the grid-cell footprint
/// (pool_for_grid): averaged (default: the mean of E_h is the amount of edge per area, i.e. how many
/// texels the cell's content needs) or minimum-pooled. See docs/adaptive.md for the measurements.
#include "adaptex/core/image.h"

namespace adaptex {

/// Settings of compute_ls2().
struct Ls2Options {
  double alpha = 1.0;        ///< Weight of the geometry stretch where there is signal.
  /// Scale s of the normalized geometry stretch in both cases (L2 ← s·L2n): the share of L_s² given
  /// to geometry. 1 = the thesis as written; see AdaptOptions::geometry_scale.
  double geometry_scale = 1.0;
  double beta = 0.95;        ///< Weight of the signal stretch E_h.
  double min_weight = 0.02;  ///< Lower clamp of L_s² (strictly positive).
  double zero_signal = 1.0 / 512.0;  ///< E_h at or below this counts as "E_h = 0" (8-bit noise).
};

/// L_s² per texel. \p stretch may be empty (then L2 = 0 everywhere: signal only, like thesis
/// Fig. 3.9e). \pre importance non-empty; stretch empty or of the same size
/// \throw InvalidInputError size mismatch, α/β negative or NaN, min_weight not in (0, 1]
ImageF compute_ls2(const ImageF& importance, const ImageF& stretch, const Ls2Options& options = {});

/// How pool_for_grid() reduces a block of texels.
enum class PoolMode {
  None,  ///< No pooling: the grid samples the full-resolution map.
  Mean,  ///< Box average (default).
  Min,   ///< Minimum weight (= maximum signal) of the block.
};

/// Reduces \p map to resolution min(map size, 2·cells) per side, each output texel the mean/min of the
/// input texels whose centres fall in it, so that bilinear sampling at a grid point of a \p cells-cell
/// grid covers about one cell footprint. PoolMode::None returns \p map unchanged.
/// \pre cells >= 1
ImageF pool_for_grid(const ImageF& map, int cells, PoolMode mode = PoolMode::Mean);

}  // namespace adaptex
