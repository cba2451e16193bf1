#pragma once
/// \file stretch_map.h
/// Geometry-stretch map of thesis §3.5 (Fig. 3.8): the Sander et al. 2001 L2 stretch of every face of
/// the current parameterization, normalized to [0,1], "rendered" over the parametric domain (each texel
/// inside a chart takes its face's value; texels outside every chart take 0).
///
/// Normalization (excess stretch): L2n_f = clamp((L2_f − 1) / (L2_ref − 1), 0, 1) with L2_f from
/// face_l2_stretch (1 = ideal, the mesh-wide average texel density) and L2_ref the area-weighted
/// (3-D area) 99th percentile of L2_f. Faces sampled at or above the average density get 0, the most
/// under-sampled 1% get 1. The thesis maps the range to [0,1]; dividing by the plain maximum gave
/// typical faces L2n ≈ 0.6 and made "1 − L2" in unpainted regions smaller than the weight of painted
/// ones, so paint was shrunk (−10 dB on venus blobs, docs/adaptive.md); a percentile keeps one sliver
/// face from squashing every other value.
#include <vector>

#include "adaptex/core/image.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/paint/texel_map.h"

namespace adaptex {

/// Per-face L2 stretch normalized to [0,1] as described above (F values; flipped or degenerate faces,
/// whose stretch is infinite, get 1). \p reference receives L2_ref when not null.
/// \pre param.uv_faces.size() == mesh.faces.size()
std::vector<float> normalized_face_stretch(const TriMesh& mesh, const Parameterization& param,
                                           double* reference = nullptr);

/// Texel image of per-face values: texel t takes values[map.face[t]], or \p outside where face = -1.
/// \pre values.size() covers every face id in map
ImageF rasterize_face_values(const TexelMap& map, const std::vector<float>& values,
                             float outside = 0.0f);

/// The geometry-stretch map at the texel map's resolution.
/// \throw InvalidInputError map empty or param/mesh face counts differ
ImageF compute_stretch_map(const TriMesh& mesh, const Parameterization& param, const TexelMap& map);

}  // namespace adaptex
