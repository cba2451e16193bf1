#pragma once
/// \file material_generate.h
/// A seeded, reproducible layered material on a mesh (`adaptex strokes generate --kind material`):
/// the version 2 test case of docs/strokes.md. Its stroke paths are generate_strokes()'s surface
/// walks.
#include <cstdint>

#include "adaptex/core/mesh.h"
#include "adaptex/paint/material_strokes.h"

namespace adaptex {

/// Three layers over a background (d = bounding-box diagonal):
/// - "Base" (normal): a fill of a muted colour and roughness 0.55-0.8, then 6 broad soft blobs of
///   base colour and roughness;
/// - "Metal" (normal), masked: the mask starts at 0 and 3 blobs paint it to 1; the layer fills
///   metallic 1, roughness 0.15-0.35 and a light grey;
/// - "Scratches" (normal, opacity 0.85-1): 40 thin hard lines with pen pressure tapering along each
///   (pressure curves on radius and opacity): even lines engrave height 0.2-0.35 and darken the
///   base colour, odd lines paint roughness only (0.05-0.2); then one eraser stroke on height.
/// The same mesh and seed give the same file, bit for bit; height_scale is 0.5 % of d.
/// \pre mesh has faces of positive area
/// \throw InvalidInputError no face of positive area
MaterialStrokeFile generate_material_strokes(const TriMesh& mesh, std::uint64_t seed = 1);

/// The single-channel detail cases of the quality study (docs/quality.md, "Channel cases").
enum class MaterialDetail {
  RoughnessScratches,  ///< Only roughness has detail: thin strokes of roughness 0.05-0.2.
  HeightEngravings,    ///< Only height has detail: thin strokes engraving height 0.2-0.35.
};

/// Two layers over a background, d and height_scale as generate_material_strokes():
/// - "Base" (normal): a fill of a flat muted colour and roughness 0.55-0.8 (no detail);
/// - "Scratches" (normal, opacity 1): the 40 thin hard lines of the material's scratch layer, with
///   its pen pressure, every one painting only the channel of \p detail; engravings have hardness 0
///   (a groove whose slope spans the radius), scratches keep the lines' hardness 0.8-1.
/// The same mesh, detail and seed give the same file, bit for bit.
/// \pre mesh has faces of positive area
/// \throw InvalidInputError no face of positive area
MaterialStrokeFile generate_material_detail(const TriMesh& mesh, MaterialDetail detail, std::uint64_t seed = 1);

}  // namespace adaptex
