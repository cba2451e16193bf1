#pragma once
/// \file density_flow.h
/// Flow-based density-equalizing map of the unit square (Gastner, Seguy & More, PNAS 115(10), 2018):
/// for a density ρ₀ > 0 on an L x L raster (mean ρ̄), X: [0,1]² → [0,1]² with det ∇X = ρ₀ / ρ̄, by
/// advecting points through v = J / ρ_t, J = −∇φ, ∇²φ = ρ̄ − ρ₀ (one DCT Poisson solve, FFTW). The
/// flow cannot fold; side points slide along their side. The result is a GridWarp (grid.h) whose
/// non-convex cells are untangled by Laplacian smoothing. docs/error_model.md.
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
  bool direct = false;                   ///< Wedges through the exact flow, not the lattice (not adopted); false.
  double direct_tolerance = 2e-3;        ///< direct: integration error bound, density-raster cells; 2e-3.
  double direct_max_step_cells = 1.0;    ///< direct: longest move in one step, density-raster cells; 1.
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
  /// \pre density.width == density.height >= 2, every value finite and > 0
  /// \throw InvalidInputError a precondition fails
  explicit DensityFlow(const ImageF& density);
  /// Cells per side L of the density raster.
  int cells() const;
  /// \p x (clamped to [0,1]²) advected to t = 1. \p tolerance and \p max_move in uv units of the
  /// square; at most \p max_steps accepted steps. Side points stay on their side, corners stay.
  /// \param steps if given: the accepted steps
  Vec2 advect(const Vec2& x, double tolerance, double max_move, int max_steps, int* steps = nullptr) const;
  /// advect() with options.direct_tolerance / direct_max_step_cells (in density cells) and max_steps.
  Vec2 advect(const Vec2& x, const DensityFlowOptions& options, int* steps = nullptr) const;

 private:
  struct Field;
  std::shared_ptr<const Field> field_;
};

/// Exact flow maps on disjoint rectangles of the square, each in its local coordinates; identity outside.
struct FlowWarp {
  /// One flow and its rectangle.
  struct Part {
    Vec2 lo = Vec2(0, 0), hi = Vec2(1, 1);  ///< The rectangle (lo < hi componentwise).
    std::shared_ptr<const DensityFlow> flow;  ///< Its flow (nullptr: the identity).
  };
  std::vector<Part> parts;      ///< Pairwise disjoint rectangles.
  DensityFlowOptions options;   ///< Integration settings (direct_tolerance, direct_max_step_cells, max_steps).
  /// \p uv advected by the flow of the first rectangle containing it, else \p uv itself.
  /// \param steps if given: the integration's accepted steps (0 outside every rectangle)
  Vec2 apply(const Vec2& uv, int* steps = nullptr) const;
  /// Every point of \p uv through apply(), in parallel (TBB). \return the accepted steps, summed
  long apply_all(std::vector<Vec2>& uv) const;
};

/// How a map of the square realizes \p density: what flow_shape() measures.
struct FlowShape {
  double density_error = 0;     ///< As DensityFlowStats::density_error.
  double dense_target = 0;      ///< Share of the square's area that the dense cells (ρ > threshold·ρ̄) should get.
  double dense_area = 0;        ///< Share they get.
  double dense_anisotropy = 0;  ///< Area-weighted mean σmax/σmin of the mapped dense cells (≤ 50 per cell).
  int folded_cells = 0;      ///< Mapped cells with signed area <= 0.
};

/// Maps an n x n lattice of the square through \p map and compares its cells with \p density
/// (docs/error_model.md §9). \p map must be thread-safe.
/// \pre density square with values > 0, n >= 1, threshold > 0 \throw InvalidInputError otherwise
FlowShape flow_shape(const ImageF& density, const std::function<Vec2(const Vec2&)>& map, int n,
                     double threshold = 1.5);

/// The density-equalizing map of \p density (L x L, any L >= 2; rows are v, as images are).
/// \pre density.width == density.height >= 2, every value finite and > 0; options.cells >= 1
/// \throw InvalidInputError a precondition fails
GridWarp density_equalizing_warp(const ImageF& density, const DensityFlowOptions& options = {},
                                 DensityFlowStats* stats = nullptr);

}  // namespace adaptex
