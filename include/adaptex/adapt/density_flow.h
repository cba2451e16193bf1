#pragma once
/// \file density_flow.h
/// Flow-based density-equalizing map of the unit square (Gastner, Seguy & More, "Fast flow-based
/// algorithm for creating density-equalizing map projections", PNAS 115(10), 2018).
///
/// Given a density ρ₀ > 0 on an L x L cell raster of [0,1]² (mean ρ̄), the map X: [0,1]² → [0,1]²
/// has Jacobian determinant det ∇X(x) = ρ₀(x) / ρ̄: a cell of density 4ρ̄ becomes 4 times larger.
/// Construction: ρ_t = (1 − t)ρ₀ + tρ̄ for t ∈ [0,1]; the flux J = −∇φ with ∇²φ = ρ̄ − ρ₀ and zero
/// normal flux on the sides (one DCT Poisson solve, FFTW REDFT10/REDFT01) satisfies ∂ρ_t/∂t + ∇·J = 0,
/// so advecting points with v(x, t) = J(x) / ρ_t(x) from t = 0 to 1 pushes ρ₀ forward to ρ̄.
/// The flow of a smooth velocity field is a diffeomorphism: the map cannot fold, and because the
/// normal velocity vanishes on the sides, boundary points slide along their side and corners stay.
///
/// The result is a GridWarp (grid.h): the advected (n+1)² lattice points; GridWarp::apply then
/// interpolates the map bilinearly between them, which is how remap.h consumes every warp. Where the
/// flow bends a cell so much that the quad of its advected corners is not convex (sharp density
/// contrast at the scale of one cell), the lattice is untangled locally by Laplacian smoothing, so
/// that every cell is convex and the bilinear warp is one-to-one.
#include <functional>
#include <memory>
#include <vector>

#include "adaptex/adapt/grid.h"
#include "adaptex/core/image.h"

namespace adaptex {

/// Settings of density_equalizing_warp(). Why each default: docs/decisions.md ("A 256-cell flow
/// lattice and a 3-cell density blur", "The flow is sampled on a lattice").
struct DensityFlowOptions {
  int cells = 256;             ///< Cells per side n of the output GridWarp (lattice of (n+1)² points).
  double tolerance = 2e-2;     ///< Local error bound of the adaptive integration, in output cells.
  int max_steps = 4000;        ///< Cap on integration steps per point (never reached on sane input).
  /// Longest move of a point in one integration step, in cells of the output lattice (the step-size
  /// control adds its own limit).
  double max_step_cells = 4.0;
  bool parallel = true;        ///< Advect points and measure the lattice with TBB (identical results either way).
  /// Coarse-to-fine advection, in output cells (0: advect every point). On an even lattice (cells >=
  /// 16) the lattice of the even points is built first (recursively, down to 8 cells); in each of its
  /// cells where the fourth differences of the advected points bound the error of cubic interpolation
  /// (5/64 |Δ⁴X|) below this tolerance, the other points are interpolated instead of advected.
  double interpolation_tolerance = 1.0;
  /// Advect the mesh's wedges (and refinement's test points) through the flow itself (DensityFlow /
  /// FlowWarp below) instead of through the bilinear lattice, which then only draws pictures. Not
  /// adopted (docs/decisions.md): kept for the study of bench/adapt/quality.cpp (--direct-flow).
  bool direct = false;
  /// direct: local error bound of the integration, in cells of the density raster the flow was
  /// solved on (the velocity varies at that scale, not at the lattice's).
  double direct_tolerance = 2e-3;
  double direct_max_step_cells = 1.0;  ///< direct: longest move in one step, in density-raster cells.
};

/// What density_equalizing_warp() did.
struct DensityFlowStats {
  long total_steps = 0;        ///< Accepted integration steps over all points.
  int max_steps = 0;           ///< Most steps any point took.
  long advected_points = 0;    ///< Lattice points integrated (the rest were interpolated).
  double max_displacement = 0; ///< Largest point displacement (uv units).
  /// Cells of the advected lattice whose corner quad was not convex (the flow bends or shears faster
  /// than one cell); they and their neighbours were Laplacian-smoothed until every cell was convex.
  int tangled_cells = 0;
  int inverted_cells = 0;      ///< Cells still not convex after that (0: the bilinear warp is one-to-one).
  /// Relative L1 error of the achieved cell areas against ρ₀/ρ̄, sampled on the output lattice
  /// (Σ |area·n² − ρ₀/ρ̄| / n²): how exactly the map reached the density.
  double density_error = 0;
};

/// The flow of a density-equalizing map, solved once (one DCT Poisson solve), that advects any point
/// of [0,1]² from t = 0 to t = 1 through v(x, t) = J(x) / ((1 − t)ρ₀(x) + tρ̄) (J and ρ₀ bilinear on
/// the density raster's corner lattice) with the adaptive Bogacki–Shampine RK3(2) of the lattice
/// warp. Cheap to copy (shared, immutable state); advect() is thread-safe.
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

/// Exact flow maps on disjoint axis-aligned rectangles of the square (one per chart rectangle,
/// atlas_flow.h, or one over the whole square): the maps that GridWarps of density_equalizing_warp()
/// sample on a lattice. Each acts in its rectangle's local coordinates (uv − lo) / (hi − lo) and maps
/// the rectangle onto itself; apply() is the identity outside every rectangle.
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
  /// Relative L1 error of the mapped cell areas against ρ/ρ̄ (as DensityFlowStats::density_error).
  double density_error = 0;
  double dense_target = 0;   ///< Share of the square's area that the dense cells (ρ > threshold·ρ̄) should get.
  double dense_area = 0;     ///< Share they get.
  /// Area-weighted mean of σmax/σmin of the mapped dense cells (1: the map magnifies them
  /// isotropically; capped at 50 per cell). The error model assumes 1 (texel spacing h·ρ^(−1/2)).
  double dense_anisotropy = 0;
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
