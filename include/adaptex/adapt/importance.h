#pragma once
/// \file importance.h
/// Importance map of thesis §3.5 (Fig. 3.6): the Sobel gradient magnitude of the painted texture, per
/// texel, combined over RGB — the signal stretch E_h that drives the re-parameterization.
///
///     ∂S/∂u = g22 + g02 − g00 − g20 + 2 (g12 − g10)     (per channel, values in [0,1])
///     ∂S/∂v = g20 + g22 − g00 − g02 + 2 (g21 − g01)
///     E(i,j) = sqrt(Σ_{c∈RGB} (∂S_c/∂u)² + (∂S_c/∂v)²) / E_ref, clamped to [0,1].
///
/// Only texels inside charts count: with a TexelMap mask, neighbours outside every chart (padding,
/// gaps) are replaced by the centre texel, so chart borders create no fake gradient, and texels
/// outside charts get 0. Normalizations: see ImportanceNormalization and docs/adaptive.md.
#include "adaptex/core/image.h"
#include "adaptex/paint/texel_map.h"

namespace adaptex {

/// How the Sobel magnitude is mapped to [0,1].
enum class ImportanceNormalization {
  /// Divide by 4·√3, the magnitude of a full-contrast (black/white) axis-aligned step edge in all three
  /// channels: an absolute, content-independent scale (a faint stroke stays faint). Default.
  EdgeContrast,
  /// Divide by the given percentile of the non-zero magnitudes inside charts (relative scale: the
  /// strongest edges of whatever is painted map to 1).
  Percentile,
};

/// Settings of compute_importance().
struct ImportanceOptions {
  ImportanceNormalization normalization = ImportanceNormalization::EdgeContrast;
  double percentile = 0.95;  ///< For Percentile: the quantile of the non-zero magnitudes mapped to 1.
};

/// Importance map of \p texture (same size). \p mask: the texel map of the texture's parameterization
/// (same size) to restrict the filter to chart texels; nullptr = every texel counts.
/// \pre mask == nullptr or mask->width/height equal the texture's
/// \throw InvalidInputError empty texture or mask of another size
ImageF compute_importance(const ImageRGBA8& texture, const TexelMap* mask,
                          const ImportanceOptions& options = {});

}  // namespace adaptex
