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

}  // namespace adaptex
