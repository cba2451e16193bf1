#pragma once
/// \file material_signal.h
/// The exact painted material of a version 2 stroke file at surface points: every channel after the
/// layers' strokes, masks and blend modes (docs/strokes.md, "Version 2: layered materials"). The
/// ground truth of the channel quality measures, as StrokeSignal is for version 1.
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

/// Brute force at one 3-D point, straight from the contract (every dab of every stroke; decals
/// throw InvalidInputError). For tests of evaluate_material().
MaterialValue evaluate_material_reference(const MaterialStrokeFile& file, const Vec3& p);

}  // namespace adaptex
