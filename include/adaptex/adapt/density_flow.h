#pragma once
/// \file density_flow.h
/// Flow-based density-equalizing map of the square (Gastner, Seguy & More, PNAS 115(10), 2018):
/// det ∇X = ρ₀ / ρ̄, points advected through v = −∇φ / ρ_t, ∇²φ = ρ̄ − ρ₀ (one DCT Poisson solve), sampled
/// on a GridWarp whose non-convex cells are untangled. docs/error_model.md.
#include <functional>
#include <memory>
#include <vector>

#include "adaptex/adapt/grid.h"
#include "adaptex/core/image.h"

namespace adaptex {

/// Settings of density_equalizing_warp() (docs/decisions.md: why each default).
struct DensityFlowOptions {
  int cells = 256;                       ///< Cells per side n of the output GridWarp ((n+1)² points); 256.
  double tolerance = 2e-2;               ///< Local error bound of the adaptive integration, output cells; 2e-2.
  int max_steps = 4000;                  ///< Cap on integration steps per point; 4000.
  double max_step_cells = 4.0;           ///< Longest move of a point in one step, output cells; 4.
  bool parallel = true;                  ///< Advect with TBB (identical results either way); true.
  double interpolation_tolerance = 1.0;  ///< Coarse-to-fine: interpolate where 5/64·|Δ⁴X| < this, cells (0: off); 1.
};

/// What density_equalizing_warp() did.
struct DensityFlowStats {
  long total_steps = 0;        ///< Accepted integration steps over all points.
  int max_steps = 0;           ///< Most steps any point took.
  long advected_points = 0;    ///< Lattice points integrated (the rest were interpolated).
  double max_displacement = 0; ///< Largest point displacement (uv units).
  int tangled_cells = 0;       ///< Cells whose advected quad was not convex (then untangled).
  int inverted_cells = 0;      ///< Cells still not convex after that (0: the bilinear warp is one-to-one).
  double density_error = 0;    ///< Σ |area·n² − ρ₀/ρ̄| / n² on the output lattice.
};

/// The flow of a density-equalizing map, solved once; advect() (Bogacki–Shampine RK3(2)) is thread-safe.
class DensityFlow {
 public:
  /// \pre density square, >= 2, values finite and > 0 \throw InvalidInputError otherwise
  explicit DensityFlow(const ImageF& density);
  int cells() const;  ///< Cells per side L of the density raster.
  /// \p x advected to t = 1 (tolerances in uv units, at most \p max_steps steps, counted in \p steps).
  Vec2 advect(const Vec2& x, double tolerance, double max_move, int max_steps, int* steps = nullptr) const;

 private:
  struct Field;
  std::shared_ptr<const Field> field_;
};

/// How a map of the square realizes \p density: what flow_shape() measures.
struct FlowShape {
  double density_error = 0;     ///< As DensityFlowStats::density_error.
  double dense_target = 0;      ///< Share of the square's area that the dense cells (ρ > threshold·ρ̄) should get.
  double dense_area = 0;        ///< Share they get.
  double dense_anisotropy = 0;  ///< Area-weighted mean σmax/σmin of the mapped dense cells (≤ 50 per cell).
  int folded_cells = 0;      ///< Mapped cells with signed area <= 0.
};

/// Compares the cells of an n x n lattice mapped by \p map (thread-safe) with \p density.
/// \pre density square with values > 0, n >= 1, threshold > 0 \throw InvalidInputError otherwise
FlowShape flow_shape(const ImageF& density, const std::function<Vec2(const Vec2&)>& map, int n,
                     double threshold = 1.5);

/// The density-equalizing map of \p density (L x L, any L >= 2; rows are v, as images are).
/// \pre density square, >= 2, values finite and > 0 \throw InvalidInputError otherwise or bad options
GridWarp density_equalizing_warp(const ImageF& density, const DensityFlowOptions& options = {},
                                 DensityFlowStats* stats = nullptr);

}  // namespace adaptex
