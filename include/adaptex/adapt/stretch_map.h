#pragma once
/// \file stretch_map.h
/// Geometry-stretch map of thesis §3.5 (Fig. 3.8): clamp((L2 − 1) / (L2_ref − 1), 0, 1), L2_ref the 99th percentile.
#include <vector>

#include "adaptex/core/image.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/paint/texel_map.h"

namespace adaptex {

/// Per-face normalized L2 stretch (flipped / degenerate faces: 1); \p reference gets L2_ref if set.
/// \pre param.uv_faces.size() == mesh.faces.size()
std::vector<float> normalized_face_stretch(const TriMesh& mesh, const Parameterization& param,
                                           double* reference = nullptr);

/// Texel t takes values[map.face[t]] (\p outside where face = -1). \pre values covers map's faces
ImageF rasterize_face_values(const TexelMap& map, const std::vector<float>& values,
                             float outside = 0.0f);

/// The geometry-stretch map at the texel map's resolution.
/// \throw InvalidInputError map empty or param/mesh face counts differ
ImageF compute_stretch_map(const TriMesh& mesh, const Parameterization& param, const TexelMap& map);

}  // namespace adaptex
