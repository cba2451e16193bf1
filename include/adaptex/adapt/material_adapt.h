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

/// The planes' exact values at every texel of a texel map, W*H (read at the chart texels): \p plane 0
/// the base colour, 1 (roughness, metallic, alpha), 2 the exact height's unit normal n stored as
/// (n + 1) / 2 (height_normals() of (exact[6] − 0.5) · height scale); owned by the source and valid
/// until its next call. Their values at one texel: material_plane_value(), normal_plane_value().
using MaterialPlaneSource = std::function<const std::vector<Vec3f>&(int plane, const TexelMap&)>;

/// Plane 0 (base colour) or 1 (roughness, metallic, alpha) of the material \p v.
inline Vec3f material_plane_value(int plane, const MaterialValue& v) {
  return plane == 0 ? Vec3f(float(v[0]), float(v[1]), float(v[2])) : Vec3f(float(v[4]), float(v[5]), float(v[3]));
}

/// Plane 2's value of the unit normal \p n: (n + 1) / 2, as the normal map stores it.
inline Vec3f normal_plane_value(const Vec3f& n) { return 0.5f * (n + Vec3f::Ones()); }

/// material_error_planes() with the planes' exact values from \p exact (e.g. a session's, kept between
/// cycles) instead of evaluating the file. The source must outlive the planes.
/// \throw InvalidInputError map and textures of different sizes, no source
std::vector<ErrorPlane> material_error_planes(const TexelMap& map, const MaterialTextures& textures,
                                              MaterialPlaneSource exact, double data_weight);

/// Paints \p file on \p layout, adapts the layout to the material's summed error model, paints again
/// on the adapted layout, and keeps whichever layout reconstructs every channel better on surface
/// samples (evaluate_material_textures(): the height through its shading normal, the model's weights).
/// \pre layout matches mesh
/// \throw InvalidInputError bad options (a mode other than density-flow or none), inconsistent input
/// \throw CancelledError the progress callback returned false
MaterialAdaptResult adapt_material(const TriMesh& mesh, const Parameterization& layout, const MaterialStrokeFile& file,
                                   const MaterialAdaptOptions& options = {});

}  // namespace adaptex
