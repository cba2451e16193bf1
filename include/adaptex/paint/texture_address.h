#pragma once
/// \file texture_address.h
/// How a bilinear texture lookup treats coordinates near and beyond the texture's border (the
/// glTF sampler's wrap mode). Shared by the texel fit and the exporters.

namespace adaptex {

/// Addressing of a texture lookup.
enum class TextureAddress {
  ClampToEdge,  ///< Clamp to the edge texels, as sample_bilinear() (the stroke-file contract).
  Repeat,       ///< Wrap around (tiling UVs): the lookup's footprint wraps across the border.
};

}  // namespace adaptex
