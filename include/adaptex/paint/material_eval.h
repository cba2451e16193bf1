#pragma once
/// \file material_eval.h
/// How well a material's textures on a layout reconstruct the exact material (docs/quality.md,
/// "Channel cases"): every channel judged over area-uniform surface samples, the height through the
/// shading normal it derives, combined with the error model's weights (docs/error_model.md §13).
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/paint/eval.h"  // psnr_from_mse()
#include "adaptex/paint/material_paint.h"

namespace adaptex {

/// Settings of evaluate_material_textures().
struct MaterialEvalOptions {
  long long samples = 200000;  ///< Surface samples K, area-uniform (default 200k).
  std::uint64_t seed = 1;      ///< Seed of the samples (sample_surface(); default 1).
  double data_weight = 0.25;   ///< Weight of roughness, metallic and alpha (default 0.25, as the error model).
  /// Step of the exact height's forward differences, as a fraction of the bounding-box diagonal
  /// (default 2e-5: far below a texel at 4096², above double rounding). Not used when no stroke
  /// paints height (the exact normal is then the surface's).
  double gradient_step = 2e-5;
};

/// Per-channel MSEs of a material's textures (values in [0,1]; mean over samples and components).
struct MaterialError {
  double base_color = 0;  ///< Bilinear base colour map vs the exact RGB (mean of 3 components).
  double alpha = 0, roughness = 0, metallic = 0;  ///< Bilinear channel maps vs the exact values.
  /// Shading normal: the bilinear normal map's (n + 1) / 2 vs that of the exact normal
  /// normalize(n − ∇H) (∇H the surface gradient of the exact height times the height scale), both
  /// in the layout's tangent frame (mean of 3 components).
  double normal = 0;
  double normal_weight = 0;  ///< 4 · mean square of the exact base colour (Lambert: albedo · |Δn|).
  /// base_color + data_weight · (alpha + roughness + metallic) / 3 + normal_weight · normal: the
  /// error model's sum of planes (data plane (roughness, metallic, alpha) is one 3-vector there).
  double weighted = 0;
};

/// Judges every channel of \p textures on \p param of \p mesh against the exact material of \p file
/// (evaluate_material()) at options.samples area-uniform surface points: uv interpolated from the
/// face's corner UVs, then sample_bilinear (as evaluate_texture() for version 1).
/// The height scale is textures.height_scale (the one the normal map was derived with).
/// \pre param matches mesh, textures of one size
/// \throw InvalidInputError param not matching the mesh, samples < 1, empty textures, bad options
MaterialError evaluate_material_textures(const TriMesh& mesh, const Parameterization& param,
                                         const MaterialTextures& textures, const MaterialStrokeFile& file,
                                         const MaterialEvalOptions& options = {});

/// The points at which evaluate_material_textures() reads the exact material.
struct MaterialEvalPoints {
  std::vector<SurfacePoint> samples;  ///< K area-uniform samples.
  /// P·K points: sample k at P·k, then (P = 3) its two probes a gradient step away along directions[k].
  std::vector<SurfacePoint> probes;
  std::vector<std::array<Vec3, 2>> directions;  ///< K unit directions in the sample's face (zero: P = 1).
  int per_sample = 1;                           ///< P: 3 where some stroke paints height, else 1.
  double step = 0;                              ///< The probes' distance (world units).
};

/// The samples and probes of \p options on \p mesh (\p with_height: with the probes of the height's
/// gradient). \throw InvalidInputError samples < 1, gradient_step <= 0
MaterialEvalPoints material_eval_points(const TriMesh& mesh, bool with_height, const MaterialEvalOptions& options = {});

/// evaluate_material_textures() with the exact material at \p points.probes given (\p exact, shape
/// [P·K]; e.g. from a MaterialPointCache). \p points.samples lie on \p mesh: a session moves them to
/// a refined mesh (the same 3-D points, so the same exact values). options.samples and seed are not used.
/// \p terms: the layout's height_normal_terms() when the caller has them (their vertex normals and
/// wedge tangents are the frames read; the same result), else computed here.
/// \throw InvalidInputError as above, or exact of another size, or terms of another mesh or layout
MaterialError evaluate_material_textures(const TriMesh& mesh, const Parameterization& param,
                                         const MaterialTextures& textures, const MaterialEvalPoints& points,
                                         const std::vector<MaterialValue>& exact, const MaterialEvalOptions& options = {},
                                         const HeightNormalTerms* terms = nullptr);

/// evaluate_material_textures() on one layout judged again and again as its textures and exact values
/// change (a session's initial layout): the per-sample terms are kept, and a call recomputes only
/// those of the samples whose probes' exact values or whose four bilinear texels changed since the
/// last call; the sum is then the full one's, in sample order. The result equals
/// evaluate_material_textures() with the same arguments, bit for bit, when the flags cover every change.
class MaterialErrorTracker {
 public:
  MaterialErrorTracker();
  ~MaterialErrorTracker();
  MaterialErrorTracker(MaterialErrorTracker&&) noexcept;
  MaterialErrorTracker& operator=(MaterialErrorTracker&&) noexcept;

  /// The next call computes every sample (as the first call does).
  void reset();
  /// \p mesh, \p param and \p points: the same at every call (until reset()). \p changed_probes: P·K
  /// flags, the probes whose exact value changed since the last call; \p changed_texels: W·H flags,
  /// the texels whose bytes changed since the last call in any of the maps judged (base colour,
  /// roughness, metallic, normal). Both are not read by a call that computes every sample.
  /// \throw InvalidInputError as evaluate_material_textures(), or flags of other sizes
  MaterialError evaluate(const TriMesh& mesh, const Parameterization& param, const MaterialTextures& textures,
                         const MaterialEvalPoints& points, const std::vector<MaterialValue>& exact,
                         const std::vector<char>& changed_probes, const std::vector<char>& changed_texels,
                         const MaterialEvalOptions& options = {});

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace adaptex
