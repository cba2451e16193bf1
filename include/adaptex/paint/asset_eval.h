#pragma once
/// \file asset_eval.h
/// The measure of a shrunk textured asset: how close a (new mesh, new layout, new texture) renders
/// to the original (mesh, layout, texture), judged by PSNR over points spread uniformly by surface
/// area, under the renderer's bilinear lookup. Also the baseline a user has without adaptex: the
/// artist's layout with the texture box-downsized to the same size, and the texel count that baseline
/// needs to match a result (Sander et al. 2002: "texture size needed for equal error").
#include <cstdint>
#include <vector>

#include "adaptex/core/image.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/paint/signal.h"

namespace adaptex {

/// Area-average resize of \p img to \p width x \p height: every output texel is the mean of the
/// source area it covers (fractional texels weighted by their covered fraction), per channel,
/// alpha included and not premultiplied; rounded to the nearest 8-bit value. An integer factor
/// averages whole blocks (2x2 for 1024 -> 512). What a user does to make a texture smaller.
/// \pre img not empty, width >= 1, height >= 1. \throw InvalidInputError otherwise
ImageRGBA8 box_downsize(const ImageRGBA8& img, int width, int height);

/// Settings of surface_psnr().
struct SurfacePsnrOptions {
  long long samples = 200000;   ///< Number K of surface samples on the reference mesh (>= 1).
  std::uint64_t seed = 1;       ///< Seed of the samples (sample_surface(): same seed, same points).
  bool keep_sample_errors = false;  ///< Also return every sample's error (diagnostics, error maps).
};

/// Result of surface_psnr().
struct SurfacePsnr {
  double mse = 0;   ///< Mean over samples and the 3 channels of the squared RGB difference, in [0,1] units.
  double psnr = 0;  ///< 10 log10(1 / mse) dB; 200 when mse < 1e-20 (identical at every sample).
  double max_error = 0;  ///< Largest per-sample mean squared RGB difference.
  long long samples = 0;
  std::uint64_t seed = 0;
  /// With keep_sample_errors: K values, the mean over RGB of the squared difference at sample k.
  std::vector<float> sample_errors;
  /// With keep_sample_errors: the K sample points on the reference mesh.
  std::vector<SurfacePoint> points;
};

/// PSNR of a textured mesh against a reference textured mesh of the same surface. K points are drawn
/// uniformly by area on \p ref_mesh (sample_surface()); at each, the reference colour is the bilinear
/// lookup of \p ref_texture at the point's \p ref_param UV, the test colour the bilinear lookup of
/// \p texture at the same surface point's \p param UV (sample_bilinear(): texel centres at
/// ((i+0.5)/W, (j+0.5)/H), clamp-to-edge, as the stroke contract and the exporters' clamped samplers).
/// Only RGB counts: alpha is ignored (straight, not premultiplied colours are compared), as an opaque
/// material shows them. UVs outside [0,1] are looked up clamped, as sample_bilinear() does.
/// \param parent_face empty when \p mesh has the faces of \p ref_mesh (same count, face f on face f);
///        else, size mesh.num_faces(): \p mesh is a conforming refinement of \p ref_mesh (every face
///        lies on face parent_face[c] of ref_mesh) and the points are carried by transfer_points().
/// Deterministic for a seed (fixed summation order, whatever the thread count). Parallel (TBB).
/// \pre each param matches its mesh (uv_faces parallel to faces).
/// \throw InvalidInputError an empty texture, a layout that does not match its mesh, a face count that
///        differs from ref_mesh's without parent_face, a bad parent_face, samples < 1, or a reference
///        mesh without area
SurfacePsnr surface_psnr(const TriMesh& ref_mesh, const Parameterization& ref_param, const ImageRGBA8& ref_texture,
                         const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& texture,
                         const FaceData<int>& parent_face = {}, const SurfacePsnrOptions& options = {});

/// Result of texels_to_match().
struct TexelMatch {
  double texels = 0;         ///< Texel count at which the curve reaches the target PSNR.
  bool above_range = false;  ///< Target above the curve's last point: extrapolated with the last slope.
  bool below_range = false;  ///< Target below the curve's first point: extrapolated with the first slope.
};

/// The texel count a baseline needs to reach \p target_psnr, from its PSNR measured at several texel
/// counts (e.g. box_downsize() to 128², 181², 256², 362², 512²): PSNR is taken as piecewise linear in
/// log2(texels) through the points (sorted by texels; made non-decreasing by a running maximum, so a
/// step that lost PSNR counts as flat), extrapolated past the ends with the end segments' slopes (a
/// flat end segment gives +inf or the first point). The texel saving factor of a result with
/// \p target_psnr at T texels is texels / T.
/// \pre at least two points, texels > 0 and finite, all PSNRs finite, sizes equal.
/// \throw InvalidInputError otherwise
TexelMatch texels_to_match(const std::vector<double>& texels, const std::vector<double>& psnr, double target_psnr);

}  // namespace adaptex
