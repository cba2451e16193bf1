#pragma once
/// \file texel_fit.h
/// Texels of a new layout fitted to a texture on another layout of the same surface: the W x H texels
/// whose bilinear reconstruction through the new UVs is closest, in the mean over the surface area, to
/// the original texture's bilinear reconstruction through the original UVs. A least-squares projection
/// onto the bilinear space of the new texture (rather than point sampling, thesis §3.7.3's resample):
/// ∫_S |T_new(uv_new(x)) - T_old(uv_old(x))|² dA, by a dense area-weighted quadrature over the faces.
/// The normal equations form a 9-point stencil on the texel grid (a bilinear footprint spans 2 x 2
/// adjacent texels), solved by Jacobi-preconditioned conjugate gradients per channel. Charts that
/// share texels (overlap, mirrors) get their area-weighted compromise; texels used across a chart
/// border by the lookup are fitted like any other. Texels that no surface point's lookup touches are
/// filled by pull-push (paint/padding.h), so filtering and mip-mapping never pull in a flat colour.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "adaptex/core/image.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/core/progress.h"
#include "adaptex/paint/texture_address.h"

namespace adaptex {

/// Largest output the fit accepts (width x height): it keeps about 300 bytes per covered texel.
inline constexpr long long kMaxFitTexels = 4096LL * 4096;

/// Settings of fit_texels() / TexelFitter, by stage.
struct TexelFitOptions {
  // Quadrature (surface samples per face: a regular subdivision into m² triangles, one at each centroid).
  double samples_per_texel = 16;        ///< Minimum samples per texel of the NEW texture a face covers (default 16).
  double samples_per_source_texel = 1;  ///< Minimum samples per texel of the ORIGINAL texture a face covers (default 1).
  long long max_samples = 16'000'000;   ///< Cap on all samples (32 bytes each); the densities shrink to fit (default 16M).
  // Addressing of the two lookups.
  TextureAddress source_address = TextureAddress::ClampToEdge;  ///< Lookup of the original (default clamp).
  TextureAddress address = TextureAddress::ClampToEdge;         ///< Lookup of the fitted texture (default clamp).
  // Solve.
  double smoothness = 1e-5;   ///< Laplacian weight between 4-neighbour texels, relative to the mean data weight (default 1e-5).
  /// Pull of every texel towards the footprint-weighted mean of the original under it, relative to the
  /// mean data weight (default 1e-2): negligible where samples determine a texel, decisive on texels
  /// that only a sliver of a footprint touches (chart borders), which would otherwise take extreme values.
  double anchor = 1e-2;
  int max_iterations = 200;   ///< Conjugate-gradient iterations at most (default 200).
  /// Stop when every channel's RMS Jacobi-scaled residual (about the texel change still to come, in
  /// 8-bit units) is below this (default 0.01).
  double tolerance = 0.01;
  // Output.
  bool fill_outside = true;   ///< Pull-push fill of the texels no lookup touches (default on); off: they keep \ref outside.
  std::array<std::uint8_t, 4> outside = {0, 0, 0, 0};  ///< Colour of untouched texels when fill_outside is off.
  /// Called with ("fit samples" | "fit matrix" | "fit solve", fraction) on the calling thread;
  /// returning false cancels (CancelledError). Empty: no reports.
  ProgressCallback progress;
};

/// What fit_texels() / TexelFitter::fit() return.
struct TexelFitResult {
  ImageRGBA8 texture;          ///< W x H fitted texels (RGBA, each channel clamped to [0,255]).
  std::vector<bool> coverage;  ///< W*H: true for the texels some surface point's lookup touches.
  long long samples = 0;       ///< Surface samples of the quadrature.
  int iterations = 0;          ///< Conjugate-gradient iterations run.
  double residual = 0;         ///< Largest final RMS Jacobi-scaled residual over the channels (8-bit units).
};

/// Reusable fit for one pair of layouts (several maps of one material share the quadrature and the
/// matrix): the constructor samples the surface and assembles the normal equations; fit() solves them
/// for one original texture. Thread-safe const fit(); the fitter owns copies of what it needs.
class TexelFitter {
 public:
  /// \param mesh the surface (3-D areas weight the samples); both layouts are layouts of it
  /// \param source_param layout of the original texture; \p source_width x \p source_height its size
  ///        (sets the sample density; fit() accepts any size)
  /// \param param the new layout, fitted at \p width x \p height
  /// \pre both layouts have mesh.faces.size() faces; sizes in [1, kMaxTextureSize], width x height
  ///      <= kMaxFitTexels
  /// \throw InvalidInputError a layout does not match the mesh, a size is out of range, a UV is not
  ///        finite, an option is negative; CancelledError options.progress returned false
  TexelFitter(const TriMesh& mesh, const Parameterization& source_param, int source_width, int source_height,
              const Parameterization& param, int width, int height, const TexelFitOptions& options = {});
  ~TexelFitter();
  TexelFitter(TexelFitter&&) noexcept;
  TexelFitter& operator=(TexelFitter&&) noexcept;

  /// Fits the new texels to \p source (the original texture, any size, RGBA).
  /// \throw InvalidInputError empty source; CancelledError options.progress returned false
  TexelFitResult fit(const ImageRGBA8& source) const;

  /// W*H: true for the texels some sample's lookup touches (the fitted texels).
  const std::vector<bool>& coverage() const;
  /// Number of surface samples of the quadrature.
  long long samples() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// One-shot fit: TexelFitter(mesh, source_param, source size, param, width, height, options).fit(source).
/// For the artist's own layout at a smaller size, pass param = source_param.
/// \throw as TexelFitter and fit()
TexelFitResult fit_texels(const TriMesh& mesh, const Parameterization& source_param, const ImageRGBA8& source,
                          const Parameterization& param, int width, int height,
                          const TexelFitOptions& options = {});

/// The artist's own layout at another size (what a user compares with box downsizing):
/// fit_texels(mesh, param, texture, param, width, height, options).
/// \throw as fit_texels()
TexelFitResult fit_resize(const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& texture, int width,
                          int height, const TexelFitOptions& options = {});

/// Bilinear lookup of all four channels (RGBA, in [0,255]) at (u, v) with the given addressing;
/// identical to sample_bilinear() for ClampToEdge (RGB / 255).
std::array<double, 4> sample_bilinear_rgba(const ImageRGBA8& img, double u, double v, TextureAddress address);

}  // namespace adaptex
