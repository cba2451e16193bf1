#pragma once
/// \file importance.h
/// Importance map of thesis §3.5 (Fig. 3.6): Sobel gradient magnitude over RGB inside charts, in [0,1].
#include "adaptex/core/image.h"
#include "adaptex/paint/texel_map.h"

namespace adaptex {

/// How the Sobel magnitude is mapped to [0,1].
enum class ImportanceNormalization {
  /// Divide by 4·√3, a full-contrast step edge in all channels (absolute scale). Default.
  EdgeContrast,
  /// Divide by a percentile of the non-zero magnitudes inside charts (relative scale).
  Percentile,
};

/// Settings of compute_importance().
struct ImportanceOptions {
  ImportanceNormalization normalization = ImportanceNormalization::EdgeContrast;
  double percentile = 0.95;  ///< For Percentile: the quantile of the non-zero magnitudes mapped to 1.
};

/// Importance map of \p texture; \p mask (its texel map, or null) restricts it to chart texels.
/// \throw InvalidInputError empty texture or mask of another size
ImageF compute_importance(const ImageRGBA8& texture, const TexelMap* mask,
                          const ImportanceOptions& options = {});

}  // namespace adaptex
