#pragma once
/// \file warp_method.h
/// The one seam between adapt_parameterization() and the methods that compute a warp of the square:
/// a method reads the current layout, texture and (if any) exact stroke history, and produces one or
/// more GridWarps (applied in order) plus the maps it used. Remap, refinement, safeguards, texture
/// update, the CLI and the studio are the same for every method. One file per method:
///   - src/adapt/warp_single.cpp       thesis §3.7: one relaxed grid (`single`)
///   - src/adapt/warp_two_stage.cpp    thesis §3.8: coarse then fine relaxed grid (`two-stage`)
///   - src/adapt/warp_density_flow.cpp error-model density + flow-based map (`density-flow`, default)
#include <memory>

#include "adaptex/adapt/adapt.h"
#include "adaptex/paint/strokes.h"

namespace adaptex {

/// Everything a warp method may read.
struct WarpInput {
  const TriMesh& mesh;
  const Parameterization& param;  ///< Current layout (the warp maps its UV square).
  const ImageRGBA8& texture;      ///< Current texture, drawn with param.
  const TexelMap& map;            ///< Texel map of param at the texture's size.
  const StrokeFile* history;      ///< Exact stroke history, or nullptr (texture only).
  const AdaptOptions& options;
  /// Optional cache of the history's signal for this layout (error_density.h); used by density-flow
  /// when it matches the layout, so the error model's cost does not grow with the history.
  ErrorDensityReference* density_reference = nullptr;
  /// Optional: the error model's density for exactly this input, already computed (a painting session
  /// computes it first to decide whether re-parameterizing is worth it, session.h); density-flow then
  /// uses it instead of computing it again. Other methods ignore it.
  const ErrorDensity* density = nullptr;
  /// Optional: an earlier cycle's result on the same layout; density-flow warm-starts its polish from
  /// it (adapt_parameterization()). Other methods ignore it.
  const AdaptResult* warm_start = nullptr;
};

/// A re-parameterization method: computes the warp of [0,1]² (homeomorphism keeping the square).
class WarpMethod {
 public:
  virtual ~WarpMethod() = default;
  /// Sets result.warp (uv_warp.h), the maps the method used (result.importance,
  /// stretch, ls2, density: whichever apply) and its report fields (times, iterations,
  /// signal_fraction). Must not touch result.param.
  /// \throw InvalidInputError bad options \throw CancelledError progress callback returned false
  virtual void compute(const WarpInput& input, AdaptResult& result) const = 0;
  /// True if the warp varies faster than a typical mesh's triangles (the remap should refine).
  virtual bool wants_refinement() const { return false; }
};

std::unique_ptr<WarpMethod> make_single_warp();        ///< thesis §3.7 (warp_single.cpp)
std::unique_ptr<WarpMethod> make_two_stage_warp();     ///< thesis §3.8 (warp_two_stage.cpp)
std::unique_ptr<WarpMethod> make_density_flow_warp();  ///< error model + flow (warp_density_flow.cpp)

/// The method of \p mode. \pre mode != AdaptMode::None \throw InvalidInputError for None
std::unique_ptr<WarpMethod> make_warp_method(AdaptMode mode);

/// Thesis methods: importance (§3.5), geometry stretch (§3.5) and L_s² (§3.6) into result, with times
/// and signal_fraction in result.report. Shared by `single` and `two-stage`.
void compute_thesis_weights(const WarpInput& input, AdaptResult& result);
/// Relaxation settings of the thesis methods from input.options (ε in texels of the texture).
RelaxOptions thesis_relax_options(const WarpInput& input);

}  // namespace adaptex
