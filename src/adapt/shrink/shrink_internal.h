#pragma once
/// \file shrink_internal.h
/// The stages of shrink_textured_mesh() (adapt/shrink.h), one file each: islands.cpp, error_model.cpp,
/// pack_islands.cpp, texels.cpp; shrink.cpp runs them.
#include <functional>
#include <vector>

#include "adaptex/adapt/shrink.h"
#include "adaptex/paint/signal.h"

namespace adaptex::shrink_detail {

/// Calls \p fn(i, j) for every texel (i, j) of an unbounded grid of \p width x \p height texels per
/// UV unit whose centre ((i+0.5)/W, (j+0.5)/H) lies in the UV triangle (a, b, c) (either orientation;
/// centres on an edge count). Indices may be negative or >= the size (the caller wraps them).
void for_each_texel_centre(const Vec2& a, const Vec2& b, const Vec2& c, int width, int height,
                           const std::function<void(int, int)>& fn);

/// \p param with every wedge moved by its chart's integer shift (islands.chart_shift); unchanged
/// under a wrapping (repeat) lookup.
Parameterization shifted_layout(const Parameterization& param, const UvIslands& islands);

/// The surface samples of the measure (paint/asset_eval.h: sample_surface() with a seed) and every
/// map's original colour at each, drawn once and shared by every PSNR the shrink computes.
class SampleSet {
 public:
  /// \pre param consistent with mesh, maps not empty. \p samples >= 1.
  SampleSet(const TriMesh& mesh, const Parameterization& param, const std::vector<ShrinkMap>& maps,
            long long samples, std::uint64_t seed);
  /// Surface PSNR (dB) of \p image on \p param against map \p m: surface_psnr() with the set's
  /// samples and seed when \p stride is 1; else over every stride-th sample (ranking).
  double psnr(size_t m, const Parameterization& param, const ImageRGBA8& image, int stride = 1) const;
  const std::vector<SurfacePoint>& points() const { return points_; }
  /// Map \p m's original colour (RGB in [0,1]) at every sample.
  const std::vector<Vec3>& reference(size_t m) const { return reference_[m]; }

 private:
  std::vector<SurfacePoint> points_;
  std::vector<std::vector<Vec3>> reference_;  ///< Per map: the original's colour at every sample.
};

/// UV footprint of every island (texel centres covered by any of its faces at resolution², wrapped),
/// in square UV units; overlapping charts count once.
std::vector<double> island_areas(const Parameterization& layout, const std::vector<int>& face_island,
                                 int num_islands, int resolution);

/// Texels (centres at resolution², wrapped) covered by faces of two or more islands.
long shared_island_texels(const Parameterization& layout, const std::vector<int>& face_island, int num_islands,
                          int resolution);

/// Per island: the mean squared reconstruction error of every map (weighted by kind) over surface
/// samples, as a function of the texel spacing h of a box-downsized, bilinearly reconstructed copy.
struct ErrorCurves {
  std::vector<double> spacing;              ///< L texel spacings h_l (UV units of the input layout), increasing.
  std::vector<std::vector<double>> error;   ///< I x L: mean error of island i at spacing l.
  std::vector<double> weight;               ///< I: share of the surface samples in island i.
  size_t stride = 1;                        ///< The samples measured: every stride-th of the set.
  std::vector<float> sample_error;          ///< K x L: weighted error of measured sample k at spacing l.
};
/// Measured on every \p stride-th sample of \p set (the input layout's samples), at the levels whose
/// spacing lies within [h_min / 2, 2 h_max] (the others copy the nearest measured level: the budget
/// reads only [h_min, h_max]). \p face_island: island of every face.
ErrorCurves island_error_curves(const SampleSet& set, size_t stride, const Parameterization& layout,
                                const std::vector<int>& face_island, int num_islands,
                                const std::vector<ShrinkMap>& maps, double h_min, double h_max);

/// Error of island \p i at spacing \p h (log-log interpolation between the curve's levels; constant
/// beyond them, 0 below the finest).
double island_error(const ErrorCurves& curves, int i, double h);

/// Error of measured sample \p k (the set's sample k · curves.stride) at spacing \p h, interpolated
/// as island_error().
double sample_error(const ErrorCurves& curves, size_t k, double h);

/// Warps every island inside itself: the density-equalizing map (density_flow.h) of a square lattice
/// over the island's bounding box in \p layout whose cells get area ∝ (error / covered area)^(2/3) (the
/// error model's samples at the island's output spacing; at most \p max_ratio² between cells), damped
/// towards identity per island until no face flips or keeps under 5 % of its area. A function of the
/// UV position, so shared texels stay shared and mirrors stay mirrors; an island without error stays.
/// \p texels[i]: output texels per UV unit of island i (lattice cells of about 2 texels, 4 ... 64 a side).
/// \p blend receives each island's damping in [0, 1] (1: the full warp).
/// \pre curves measured on \p set; \p layout is the set's layout shifted (shifted_layout()); max_ratio >= 1.
Parameterization warp_islands(const SampleSet& set, const ErrorCurves& curves, const Parameterization& layout,
                              const std::vector<int>& face_island, int num_islands,
                              const std::vector<double>& texels, const std::vector<double>& face_texels,
                              double max_ratio, bool measured, std::vector<double>* blend);

/// Relative island scales (s_i: new UV size / input UV size, up to one common factor) minimising
/// Σ weight_i · e_i(1 / (size · s_i)) under Σ area_i · s_i² = budget (equal marginal gain), with
/// s_i within [1/ratio, ratio] of the uniform scale sqrt(budget / Σ area_i).
std::vector<double> allocate_island_scales(const ErrorCurves& curves, const std::vector<double>& area,
                                           double budget, double size, double max_ratio);

/// Placement of one island: its texel coordinates in the output are rotate_k(sigma · uv) + offset
/// (uv in the shifted input layout), where rotate_k turns by k · 90° counter-clockwise; divided by
/// the size, they are the new UVs.
struct IslandPlacement {
  double sigma = 1;            ///< Output texels per input UV unit (size · s_i · λ).
  int turns = 0;               ///< k in {0, 1, 2, 3}.
  Vec2 offset = Vec2::Zero();  ///< In texels of the output.
};

/// Packs the islands of \p layout (shifted input layout) with relative scales \p scales into a
/// size x size square, every island dilated by \p gutter texels, at the largest common factor found
/// by bisection, starting from the factor at which the islands' texels fill \p fill_hint of the
/// square. \p fill receives the share of the square's texels the packed islands touch.
/// \return I placements; empty if no factor fits.
std::vector<IslandPlacement> pack_islands(const Parameterization& layout, const std::vector<int>& face_island,
                                          int num_islands, const std::vector<double>& scales, int size,
                                          int gutter, bool rotate, double fill_hint, double* fill);

/// A UV face is degenerate when its area is below this many square texels (as the evaluation counts).
constexpr double kDegenerateTexelArea = 1e-6;

/// Gives every degenerate face of \p out (a layout of \p input's faces, texels of 1 / \p size) an
/// area of about 1e-3 square texels in its input orientation (its chart's where the input has none):
/// one corner moves off the line of the other two, a shared wedge only where the other faces keep
/// their orientation and area, else a new wedge of the face's own. \return faces lifted.
int lift_degenerate_faces(Parameterization& out, const Parameterization& input, int size);

/// \p layout with every wedge placed by its island's placement (UVs in [0,1]²).
Parameterization apply_placements(const Parameterization& layout, const std::vector<int>& face_island,
                                  const std::vector<IslandPlacement>& placements, int size);

/// Texels of the first \p count maps on \p dst_param (size x size), least-squares fitted to the
/// originals on \p src_param (clamp-to-edge lookups, as the measure), pull-push outside the charts.
/// \p draft: a quarter of the quadrature's samples per original texel (ranking candidates).
std::vector<ImageRGBA8> fit_maps(const TriMesh& mesh, const Parameterization& src_param,
                                 const std::vector<ShrinkMap>& maps, size_t count, const Parameterization& dst_param,
                                 int size, bool draft, const ProgressCallback& progress = {});


}  // namespace adaptex::shrink_detail
