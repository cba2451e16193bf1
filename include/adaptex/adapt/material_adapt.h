#pragma once
/// \file material_adapt.h
/// A layered material (stroke file version 2) painted on an adapted layout: one error model sums the
/// errors of every channel by its effect on the rendered image (base colour; roughness, metallic and
/// alpha; the shading normal derived from the height), then the density-flow warp and the textures on
/// the new layout (docs/error_model.md, "Materials").
#include <functional>
#include <vector>

#include "adaptex/adapt/adapt.h"
#include "adaptex/adapt/error_density.h"
#include "adaptex/paint/material_paint.h"

namespace adaptex {

/// Settings of adapt_material().
struct MaterialAdaptOptions {
  MaterialPaintOptions paint;  ///< Texture size and seam padding.
  /// The adaptation: mode density-flow (default) or none; refinement, remap and progress as for paint.
  AdaptOptions adapt;
  double data_weight = 0.25;  ///< Weight of the roughness / metallic / alpha errors (default 0.25).
  long long check_samples = 200000;  ///< Surface samples of the never-worse check (default 200k).
};

/// Result of adapt_material().
struct MaterialAdaptResult {
  TriMesh mesh;                 ///< The input, or its refinement (same surface) when the warp refined it.
  /// With a refinement: the input face of every face of mesh (size F'), as AdaptResult::parent_face;
  /// empty otherwise.
  FaceData<int> parent_face;
  Parameterization param;       ///< The layout the textures are on.
  MaterialTextures textures;
  AdaptReport report;           ///< The adaptation's report (mode none: the fixed layout's).
  bool adapted = false;         ///< The adapted layout was kept (false: the input layout).
  /// Weighted MSE of every channel (MaterialError::weighted, the normal included) over the check's samples.
  double error_fixed = 0, error_adapted = 0;
};

/// The error planes of \p file on \p param with its painted \p textures (\p map: the texel map of
/// \p param at their size): base colour (weight 1), roughness / metallic / alpha (\p data_weight), and
/// the shading normal from the height (weight 4 · the mean square of the base colour over the chart
/// texels: Lambert shading changes by the albedo times |Δn|).
/// The planes refer to \p mesh, \p param and \p file: they must outlive the planes.
/// \throw InvalidInputError map and textures of different sizes
std::vector<ErrorPlane> material_error_planes(const TriMesh& mesh, const Parameterization& param, const TexelMap& map,
                                              const MaterialStrokeFile& file, const MaterialTextures& textures,
                                              double data_weight);

/// The exact material at the chart texels of a texel map, shape [map.inside.size()] (as
/// evaluate_material() at texel_points(map)), owned by the source and valid until its next call.
using MaterialTexelSource = std::function<const std::vector<MaterialValue>&(const TexelMap&)>;

/// The unit normals of the exact height at every texel of a texel map, W*H (height_normals() of
/// (exact[6] − 0.5) · height scale at the chart texels), owned by the source and valid until its next call.
using MaterialNormalSource = std::function<const std::vector<Vec3f>&(const TexelMap&)>;

/// material_error_planes() with the exact material from \p exact (e.g. a session's point caches)
/// instead of evaluating the file, and the exact height's normals from \p normals when given (else
/// derived from \p exact). The sources must outlive the planes.
/// \throw InvalidInputError map and textures of different sizes, no source
std::vector<ErrorPlane> material_error_planes(const TriMesh& mesh, const Parameterization& param, const TexelMap& map,
                                              const MaterialTextures& textures, MaterialTexelSource exact,
                                              double data_weight, MaterialNormalSource normals = {});

/// Paints \p file on \p layout, adapts the layout to the material's summed error model, paints again
/// on the adapted layout, and keeps whichever layout reconstructs every channel better on surface
/// samples (evaluate_material_textures(): the height through its shading normal, the model's weights).
/// \pre layout matches mesh
/// \throw InvalidInputError bad options (a mode other than density-flow or none), inconsistent input
/// \throw CancelledError the progress callback returned false
MaterialAdaptResult adapt_material(const TriMesh& mesh, const Parameterization& layout, const MaterialStrokeFile& file,
                                   const MaterialAdaptOptions& options = {});

}  // namespace adaptex
