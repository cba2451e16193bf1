#pragma once
/// \file error_density.h
/// The texel density minimizing the reconstruction error for a texel budget: e = q·h^p measured per
/// cell (at h_N and 2h_N), ρ ∝ q^(1/(1+p/2)), a floor where unpainted. docs/error_model.md.
#include <functional>
#include <memory>
#include <vector>

#include "adaptex/core/image.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/paint/strokes.h"
#include "adaptex/paint/texel_map.h"

namespace adaptex {

/// Settings of compute_error_density().
struct ErrorDensityOptions {
  int cells = 256;                      ///< Cells per side L of the density raster (the flow's); 256.
  int reference_factor = 2;             ///< History's reference raster = this × texture size; 2.
  int max_reference = 2048;             ///< Cap on the reference raster's side in texels; 2048.
  bool quarter_texel_reference = true;  ///< N ≥ 4·cells: reference points on the N grid shifted ¼ texel; true.
  double blur_cells = 3.0;              ///< Gaussian σ, cells, of the error fields before the solve; 3.
  double floor = 0.15;                  ///< Least surface texel density of any cell, relative to uniform; 0.15.
  double max_density = 256;             ///< Cap on the relative area density ρ of a cell (16× linear); 256.
  double gutter_blur_cells = 3.0;       ///< Gutters take the charts' density within this σ, cells; 3.
  double min_exponent = 1.0;            ///< Lower clamp of the measured exponent p (hard edges); 1.
  double max_exponent = 4.0;            ///< Upper clamp of p (smooth bilinear regime); 4.
};

/// Result of compute_error_density().
struct ErrorDensity {
  ImageF density;     ///< L x L, > 0, mean 1: each cell's new UV area relative to its current area.
  ImageF error;       ///< L x L: surface-weighted MSE of each cell at the current spacing (display).
  ImageF exponent;    ///< L x L: measured p (0 where nothing is painted).
  double signal_fraction = 0;     ///< Fraction of chart cells with a measurable error.
  double predicted_gain_db = 0;   ///< The model's PSNR gain of the density over the current layout.
  int reference_size = 0;         ///< Side of the reference raster (or shifted grid) used.
};

/// The history's exact signal at the reference points of one layout and texture size, updated stroke by
/// stroke, plus the last call's per-cell sums: compute_error_density() then costs O(new strokes) and
/// gives the same result bit for bit (28 MB at N = 1024).
class ErrorDensityReference {
 public:
  /// \p mesh must outlive this. \throw InvalidInputError param inconsistent, texture_size < 1, bad options
  ErrorDensityReference(const TriMesh& mesh, const Parameterization& param, int texture_size,
                        const Vec3& background, const ErrorDensityOptions& options = {});
  ~ErrorDensityReference();
  ErrorDensityReference(ErrorDensityReference&&) noexcept;
  ErrorDensityReference& operator=(ErrorDensityReference&&) noexcept;

  /// Built for this \p mesh object, \p param, \p texture_size and \p options' raster sizes.
  bool matches(const TriMesh& mesh, const Parameterization& param, int texture_size,
               const ErrorDensityOptions& options) const;
  /// Adds \p history's new strokes. \pre a prefix was added \throw InvalidInputError a bad stroke
  void update(const StrokeFile& history);

  struct Impl;

 private:
  friend ErrorDensity compute_error_density(const TriMesh&, const Parameterization&, const ImageRGBA8&,
                                            const TexelMap&, const StrokeFile&, ErrorDensityReference&,
                                            const ErrorDensityOptions&);
  std::unique_ptr<Impl> impl_;
};

/// The model's total error Σ_c q_c · ρ_c^(−p_c/2) of a layout of UV area density \p density (L x L, mean
/// 1) relative to the model's layout, or of that layout itself when \p density is empty.
/// \throw InvalidInputError density neither empty nor L x L with finite values > 0
double predicted_error(const ErrorDensity& model, const ImageF& density);

/// Target density from the exact stroke history; \p texture / \p map give the h_N level.
/// \throw InvalidInputError inconsistent sizes or bad options
ErrorDensity compute_error_density(const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& texture,
                                   const TexelMap& map, const StrokeFile& history,
                                   const ErrorDensityOptions& options = {});

/// The same from \p reference (updated with \p history first): equal, at a cost independent of the history.
/// \throw InvalidInputError as above, or !reference.matches(...)
ErrorDensity compute_error_density(const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& texture,
                                   const TexelMap& map, const StrokeFile& history, ErrorDensityReference& reference,
                                   const ErrorDensityOptions& options = {});

/// The same without a history (`adaptex reparam`): the texture is the reference, levels 2·h_N and 4·h_N.
/// \throw InvalidInputError inconsistent sizes or bad options
ErrorDensity compute_error_density(const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& texture,
                                   const TexelMap& map, const ErrorDensityOptions& options = {});

/// One RGB signal of a multi-channel error model (a layered material: base colour, data channels,
/// shading normal; docs/error_model.md, "Materials"). Its squared error counts with \p weight.
struct ErrorPlane {
  double weight = 1;   ///< Weight of the plane's mean squared RGB error in the sum (> 0).
  ImageRGBA8 texture;  ///< What the layout holds at h_N (level a), RGB / 255; the size of the texel map.
  /// The plane's exact values at every texel centre of a texel map (W*H; read inside charts only), owned
  /// by the plane's source (a session keeps them between cycles) and valid until its next call.
  std::function<const std::vector<Vec3f>&(const TexelMap&)> exact;
};

/// Target density from several planes: each plane's per-cell errors at h_N and 2·h_N (as the history's
/// model), weighted and summed, then one solve. \p map is the texel map of \p param at the planes'
/// texture size.
/// \throw InvalidInputError no plane, a weight <= 0, textures of different sizes, inconsistent input
ErrorDensity compute_error_density(const TriMesh& mesh, const Parameterization& param, const TexelMap& map,
                                   const std::vector<ErrorPlane>& planes, const ErrorDensityOptions& options = {});

/// The texel maps at which compute_error_density() reads the planes' exact values: the reference
/// raster's (ErrorDensityOptions' reference grid) and the N/2 level's. Built once for a fixed layout,
/// they let a session keep the planes' exact values at their points (MaterialPointCache).
struct ErrorPlaneMaps {
  int texture_size = 0;  ///< N.
  TexelMap reference;    ///< The reference points' texel map.
  TexelMap half;         ///< The texel map at N/2.
};

/// The plane maps of \p param at texture size \p texture_size.
/// \throw InvalidInputError texture_size < 1, bad reference options
ErrorPlaneMaps error_plane_maps(const TriMesh& mesh, const Parameterization& param, int texture_size,
                                const ErrorDensityOptions& options = {});

/// compute_error_density() of the planes with their maps built already (error_plane_maps() of the
/// same layout, texture size and options); the same result.
/// \throw InvalidInputError as above, or maps of another size
ErrorDensity compute_error_density(const TriMesh& mesh, const Parameterization& param, const TexelMap& map,
                                   const std::vector<ErrorPlane>& planes, const ErrorPlaneMaps& maps,
                                   const ErrorDensityOptions& options = {});

/// What compute_error_density() of planes keeps between calls on one layout (as ErrorDensityReference
/// for a history): each plane's rasters and cell sums of the last call, so that the next call (after a
/// stroke) sums again only the cell rows whose rasters changed. The result is the same as without it.
class ErrorPlanesMemory {
 public:
  ErrorPlanesMemory();
  ~ErrorPlanesMemory();
  ErrorPlanesMemory(ErrorPlanesMemory&&) noexcept;
  ErrorPlanesMemory& operator=(ErrorPlanesMemory&&) noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  friend ErrorDensity compute_error_density(const TriMesh&, const Parameterization&, const TexelMap&,
                                            const std::vector<ErrorPlane>&, const ErrorPlaneMaps&, ErrorPlanesMemory&,
                                            const ErrorDensityOptions&);
};

/// compute_error_density() of the planes with their maps, remembering in \p memory (used with the same
/// mesh, layout, maps, texture size, options and number of planes on every call; else it starts afresh).
/// \throw as above
ErrorDensity compute_error_density(const TriMesh& mesh, const Parameterization& param, const TexelMap& map,
                                   const std::vector<ErrorPlane>& planes, const ErrorPlaneMaps& maps,
                                   ErrorPlanesMemory& memory, const ErrorDensityOptions& options = {});

}  // namespace adaptex
