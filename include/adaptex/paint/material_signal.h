#pragma once
/// \file material_signal.h
/// The exact painted material of a version 2 stroke file at surface points: every channel after the
/// layers' strokes, masks and blend modes (docs/strokes.md, "Version 2: layered materials"). The
/// ground truth of the channel quality measures, as StrokeSignal is for version 1.
#include <array>
#include <vector>

#include "adaptex/core/mesh.h"
#include "adaptex/paint/material_strokes.h"
#include "adaptex/paint/signal.h"

namespace adaptex {

/// Coverage alpha(x) of a brush or erase stroke at the 3-D point \p p: the maximum over its dabs of
/// opacity_i * falloff(|p - c_i| / radius_i), with the pressure curves applied per dab.
/// \pre stroke.type is Brush or Erase
double material_stroke_coverage(const MaterialStroke& stroke, const Vec3& p);

/// Evaluates every channel of \p file at \p points of \p mesh (parallel over points; decal strokes
/// use the mesh for visibility). Result k belongs to points[k].
/// \pre 0 <= points[k].face < mesh.num_faces()
/// \throw InvalidInputError a face index out of range, or a decal stroke breaking the contract
std::vector<MaterialValue> evaluate_material(const TriMesh& mesh, const MaterialStrokeFile& file,
                                             const std::vector<SurfacePoint>& points);

/// One layer's own state at surface points, before it is blended (docs/strokes.md, "Layer state"
/// and "Mask"). Shapes: P points.
struct MaterialLayerSamples {
  std::vector<MaterialValue> value;                     ///< L: the layer's value per component (0 where a_c = 0).
  std::vector<std::array<double, kNumChannels>> cover;  ///< a_c per channel, in [0,1].
  std::vector<double> mask;                             ///< M, in [0,1] (1 for a layer without a mask).
};

/// Evaluates layer \p layer of \p file alone at \p points (its visibility, opacity and blend mode
/// are not applied: compositing the layers' samples over the background with them gives
/// evaluate_material()).
/// \pre 0 <= points[k].face < mesh.num_faces()
/// \throw InvalidInputError layer out of range, or as evaluate_material()
MaterialLayerSamples evaluate_layer(const TriMesh& mesh, const MaterialStrokeFile& file, int layer,
                                    const std::vector<SurfacePoint>& points);

/// Brute force at one 3-D point, straight from the contract (every dab of every stroke; decals
/// throw InvalidInputError). For tests of evaluate_material().
MaterialValue evaluate_material_reference(const MaterialStrokeFile& file, const Vec3& p);

}  // namespace adaptex
