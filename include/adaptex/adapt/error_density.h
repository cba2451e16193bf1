#pragma once
/// \file error_density.h
/// The texel density that minimizes the reconstruction error for a fixed texel budget (the
/// error model behind `--adapt density-flow`; derivation in docs/error_model.md).
///
/// Model. Where the layout gives texel spacing h, bilinear reconstruction of the paint leaves a local
/// mean squared error e(h) = q·h^p: p = 1 across hard edges (MSE ∝ h per unit edge length), p = 4 in
/// smooth paint (MSE ∝ h⁴|∇²f|²), anything between for soft edges near the texel scale. Both q and p
/// are *measured* per cell, not assumed: the exact signal is rasterized finer than the texture
/// (reference raster, from the stroke history) and reconstructed from point samples at the texture's
/// spacing h_N and at 2·h_N; e(h_N), e(2h_N) give q and p = log2(e(2h_N)/e(h_N)), clamped to
/// [min_exponent, max_exponent]. Errors are weighted by the surface area each UV cell stands for, so
/// the model minimizes the error per *surface* area, as quality is measured.
///
/// Equidistribution. With ρ the new UV area of a cell relative to its current area (h = h_N·ρ^(−1/2)),
/// the total error Σ_c q_c ρ_c^(−p_c/2) under the budget Σ_c ρ_c = n_cells is smallest when
/// (p/2)·q·ρ^(−p/2−1) = μ in every cell (one Lagrange multiplier μ, found by bisection), i.e.
/// ρ ∝ q^(1/(1+p/2)): ρ ∝ q^(2/3) on hard edges (linear density ∝ contrast^(2/3)), ρ ∝ q^(1/3) in smooth
/// paint. Where nothing is painted (q = 0) the surface keeps at least `floor` times the uniform
/// surface texel density: the geometric stretch of the current layout stays in the model, so unpainted
/// regions are never starved and over-stretched ones are not shrunk further.
#include <memory>

#include "adaptex/core/image.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/paint/strokes.h"
#include "adaptex/paint/texel_map.h"

namespace adaptex {

/// Settings of compute_error_density().
struct ErrorDensityOptions {
  int cells = 256;            ///< Cells per side L of the density raster (the flow's raster).
  /// Reference raster = this × the texture size (stroke history only), capped at max_reference. 2 keeps
  /// the cost at 4× the texture's texels; the reference must be finer than the texture to see e(h_N).
  int reference_factor = 2;
  int max_reference = 2048;   ///< Cap on the reference raster's side in texels.
  /// Where the texture has at least 4× the density raster's resolution (N >= 4·cells: 16 reference
  /// points per cell, as many as the 2N raster gives at N = 2·cells), take the reference points on the
  /// texture's own N x N grid shifted by a quarter texel, at ((i + 1/4)/N, (j + 1/4)/N), instead of
  /// the texel centres of the reference_factor·N raster. Along each axis the 2N raster's points lie
  /// 1/4 or 3/4 of a texel past a texture texel centre, and 1/8 or 3/8 of an N/2 texel from the
  /// nearest N/2 centre; the shifted grid has the same distances in the same proportions, so both
  /// levels' errors are sampled alike, with a quarter of the exact evaluations and of the reference
  /// texel map. It also stays finer than the texture at N >= max_reference, where the capped raster
  /// is the texture's own texel centres. A trade-off for the model's 3× speed at N >= 1024, not a free
  /// gain (docs/decisions.md, "A quarter-texel reference"). false: always the reference_factor·N raster.
  bool quarter_texel_reference = true;
  /// Gaussian σ, in cells, of the error fields before the density solve (docs/decisions.md, "A
  /// 256-cell flow lattice and a 3-cell density blur").
  double blur_cells = 3.0;
  /// Least surface texel density, relative to a uniform-density layout of the same budget, of any cell
  /// (unpainted regions). 0.02 = spacing at most ~7× the uniform spacing.
  double floor = 0.15;
  double max_density = 256;   ///< Cap on the relative area density ρ of a cell (16× linear).
  /// Gutters between charts (cells outside every chart) take the cover-weighted mean density of the
  /// charts within about this many cells (Gaussian σ).
  double gutter_blur_cells = 3.0;
  double min_exponent = 1.0;  ///< Lower clamp of the measured error exponent p (hard edges).
  double max_exponent = 4.0;  ///< Upper clamp of p (smooth bilinear regime).
};

/// Result of compute_error_density().
struct ErrorDensity {
  /// L x L, > 0, mean 1 over the square: the UV area each cell of the current layout should get,
  /// relative to its current area (the density given to density_equalizing_warp()).
  ImageF density;
  ImageF error;       ///< L x L: surface-weighted MSE of each cell at the current spacing (display).
  ImageF exponent;    ///< L x L: measured p (0 where nothing is painted).
  double signal_fraction = 0;     ///< Fraction of chart cells with a measurable error.
  double predicted_gain_db = 0;   ///< The model's PSNR gain of the density over the current layout.
  int reference_size = 0;         ///< Side of the reference raster (or shifted grid) used.
};

/// The exact history signal that compute_error_density() reads, for one layout at one texture size:
/// at the reference points (the texel centres of the reference raster, R = reference_factor · N capped at
/// max_reference, or the quarter-texel-shifted N x N grid: quarter_texel_reference) and
/// of the N/2 level, kept up to date stroke by stroke (paint/signal.h, PointSignalCache). A painting
/// session re-parameterizes from its initial layout after every stroke (session.h): with this cache
/// the error model evaluates only the new strokes' dabs, not the whole history. It also
/// keeps the rasters and per-cell error sums of its last compute_error_density() call, so that the
/// next call sums again only the rows of cells whose inputs changed (a stroke touches few of them);
/// the result is the same, bit for bit, as summing every row. Those rasters take 12 bytes per texel of
/// the reference raster, the texture and the N/2 raster (28 MB at N = 1024).
class ErrorDensityReference {
 public:
  /// \param mesh, param the layout (the mesh is kept by reference: it must outlive this object)
  /// \param texture_size N, the side of the texture the layout is painted at
  /// \param background the history's background colour, RGB in [0,1]
  /// \throw InvalidInputError param inconsistent with mesh, texture_size < 1, bad options
  ErrorDensityReference(const TriMesh& mesh, const Parameterization& param, int texture_size,
                        const Vec3& background, const ErrorDensityOptions& options = {});
  ~ErrorDensityReference();
  ErrorDensityReference(ErrorDensityReference&&) noexcept;
  ErrorDensityReference& operator=(ErrorDensityReference&&) noexcept;

  /// True if this reference was built for \p mesh (the same object) and \p param (same UVs and faces)
  /// at \p texture_size with the raster sizes that \p options give.
  bool matches(const TriMesh& mesh, const Parameterization& param, int texture_size,
               const ErrorDensityOptions& options) const;
  /// Composites the strokes of \p history not added yet. \pre the strokes added so far are the first
  /// ones of \p history \throw InvalidInputError a stroke breaks the contract's rules
  void update(const StrokeFile& history);

  struct Impl;

 private:
  friend ErrorDensity compute_error_density(const TriMesh&, const Parameterization&, const ImageRGBA8&,
                                            const TexelMap&, const StrokeFile&, ErrorDensityReference&,
                                            const ErrorDensityOptions&);
  std::unique_ptr<Impl> impl_;
};

/// The model's total error Σ_c q_c · ρ_c^(−p_c/2) (q = model.error, p = model.exponent; cells without
/// paint count 0) of a layout whose UV area density, relative to the layout the model was computed on,
/// is \p density: L x L and mean 1 like ErrorDensity::density, or empty for that layout itself (ρ = 1).
/// 10·log10(predicted_error(m, held) / predicted_error(m, m.density)) is what re-parameterizing for
/// the model would gain over a layout with density `held` (PaintSessionOptions::min_gain_db).
/// \pre model.error and model.exponent are L x L
/// \throw InvalidInputError density is neither empty nor L x L, or holds a value that is not finite and > 0
double predicted_error(const ErrorDensity& model, const ImageF& density);

/// Target density from the exact stroke history: reference raster, error levels and equidistribution as
/// described above. \p texture / \p map are the current texture and its texel map (the h_N level).
/// \pre mesh/param consistent; map is the texel map of param at the texture's size
/// \throw InvalidInputError inconsistent sizes or bad options
ErrorDensity compute_error_density(const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& texture,
                                   const TexelMap& map, const StrokeFile& history,
                                   const ErrorDensityOptions& options = {});

/// The same, with the history's signal from \p reference (brought up to date with \p history first):
/// equal to the overload above, at a cost that does not grow with the history.
/// \pre reference.matches(mesh, param, texture.width, options)
/// \throw InvalidInputError inconsistent sizes, bad options, or a reference for another layout
ErrorDensity compute_error_density(const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& texture,
                                   const TexelMap& map, const StrokeFile& history, ErrorDensityReference& reference,
                                   const ErrorDensityOptions& options = {});

/// The same without a history (`adaptex reparam`): the texture itself is the reference, and the two
/// levels are its reconstructions at 2·h_N and 4·h_N (the exponents and the relative densities are the
/// same model; detail finer than the texture cannot be seen).
/// \throw InvalidInputError inconsistent sizes or bad options
ErrorDensity compute_error_density(const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& texture,
                                   const TexelMap& map, const ErrorDensityOptions& options = {});

}  // namespace adaptex
