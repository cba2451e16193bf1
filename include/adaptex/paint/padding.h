#pragma once
/// \file padding.h
/// Seam padding (dilation of the charts): texels outside every chart but within P texels of one take
/// the colour of the nearest chart texel, so bilinear filtering and mipmapping do not pull the
/// background across chart borders (seams). Rings are 8-connected (chessboard distance <= P); inside
/// a ring the source is the chart texel nearest in Euclidean distance among the sources of the
/// already padded 8-neighbours (a distance-transform-like propagation).
#include <vector>

#include "adaptex/core/image.h"
#include "adaptex/paint/texel_map.h"

namespace adaptex {

/// Which texel copies which. Built once per texel map and padding width.
struct SeamPadding {
  int width = 0, height = 0;
  std::vector<int> padded;  ///< Indices (j*W+i) of the padded texels, ring by ring.
  std::vector<int> source;  ///< W*H: chart texel index copied into each padded texel, -1 elsewhere.
};

/// \param inside W*H flags: true for texels whose centre lies in a chart.
/// \param padding P >= 0 (0 gives an empty padding).
/// \pre inside.size() == width*height
SeamPadding build_seam_padding(const std::vector<bool>& inside, int width, int height, int padding);
/// Same, with chart texels = texels of \p map with face >= 0.
SeamPadding build_seam_padding(const TexelMap& map, int padding);

/// Copies the RGBA of each padded texel's source into it (alpha included, so padded texels are
/// opaque). \pre img is pad.width x pad.height
void apply_seam_padding(ImageRGBA8& img, const SeamPadding& pad);

/// Pull-push fill (Gortler et al. 1996, *The Lumigraph*, §3.3): the texels outside \p coverage take
/// a smooth dilation of the covered colours, all four channels, so bilinear lookup and mip-mapping
/// near a chart border see the chart's own colours, never a flat background. Pull: a pyramid of
/// 2 x 2 coverage-weighted means (weights capped at 1); push: each level's uncovered part takes the
/// bilinear upsampling of the level above. Covered texels are unchanged; with no covered texel the
/// image is left as it is.
/// \pre coverage.size() == img.width * img.height
/// \throw InvalidInputError the sizes differ
void pull_push_fill(ImageRGBA8& img, const std::vector<bool>& coverage);

}  // namespace adaptex
