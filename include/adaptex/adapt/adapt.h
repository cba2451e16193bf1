#pragma once
/// \file adapt.h
/// Signal-adaptive re-parameterization in one call. AdaptMode selects the method that warps the square
/// (method.h): `density-flow` (default; error_density.h, density_flow.h, error_polish.h) or the
/// thesis' `single` / `two-stage` relaxation (§3.7–3.8). Refinement (refine.h) and a flip-, degeneracy-
/// and overlap-free remap (remap.h) follow for every method. The painting loop: session.h.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "adaptex/adapt/atlas_flow.h"
#include "adaptex/adapt/density_flow.h"
#include "adaptex/adapt/error_density.h"
#include "adaptex/adapt/error_polish.h"

#include "adaptex/adapt/grid.h"
#include "adaptex/adapt/importance.h"
#include "adaptex/adapt/ls2.h"
#include "adaptex/adapt/relax.h"
#include "adaptex/adapt/remap.h"
#include "adaptex/adapt/uv_warp.h"
#include "adaptex/core/image.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/core/progress.h"
#include "adaptex/paint/texel_map.h"

namespace adaptex {

/// A method by the name it is registered under (method.h); parse_adapt_mode() finds any of them.
class AdaptMode {
 public:
  /// \p name must outlive the value (a literal, or a name held by the registry).
  constexpr explicit AdaptMode(const char* name) : name_(name) {}
  static const AdaptMode None;         ///< Keep the parameterization (the baseline of every comparison).
  static const AdaptMode Single;       ///< One grid of fine_grid cells (thesis §3.7).
  static const AdaptMode TwoStage;     ///< coarse_grid then fine_grid (thesis §3.8).
  static const AdaptMode DensityFlow;  ///< Error-model density + flow-based density-equalizing map. Default.
  constexpr const char* name() const { return name_; }
  friend bool operator==(const AdaptMode& a, const AdaptMode& b) { return std::string_view(a.name_) == b.name_; }

 private:
  const char* name_;
};
inline constexpr AdaptMode AdaptMode::None{"none"};
inline constexpr AdaptMode AdaptMode::Single{"single"};
inline constexpr AdaptMode AdaptMode::TwoStage{"two-stage"};
inline constexpr AdaptMode AdaptMode::DensityFlow{"density-flow"};

/// Largest grid of the thesis' relaxation, in cells per side (a 4096² grid has 16.8 M points).
inline constexpr int kMaxGridCells = 4096;

/// `single` / `two-stage`: the thesis' grid relaxation (§3.5–3.8; docs/adaptive.md).
struct ThesisOptions {
  int coarse_grid = 16;              ///< Cells per side of the coarse stage (two-stage), in [1, kMaxGridCells]; 16.
  int fine_grid = 256;               ///< Cells per side of the fine (or single) stage, in [1, kMaxGridCells]; 256.
  double alpha = 1.0;                ///< L_s² weight α of the geometry stretch where there is signal (§3.6); 1.
  double geometry_scale = 0.25;      ///< Share of the normalized geometry stretch in L_s² (1: as written); 0.25.
  double beta = 0.95;                ///< L_s² weight β of the signal stretch E_h (§3.6); 0.95.
  double min_weight = 0.02;          ///< Strictly positive lower clamp of L_s²; 0.02.
  bool use_geometry_stretch = true;  ///< false: L2 = 0 everywhere (signal only, Fig. 3.9e); true.
  ImportanceOptions importance;      ///< Normalization of the Sobel importance map (importance.h).
  PoolMode pool = PoolMode::Mean;    ///< Sampling of L_s² at each grid's scale; Mean.
  GridRing ring = GridRing::Eight;   ///< 1-ring of the relaxation; Eight.
  bool slide_boundary = false;       ///< Boundary grid points slide along the square's sides; false.
  double epsilon_texels = 0.05;      ///< Stop a stage when the largest move < this many texels; 0.05.
  int max_iterations = 300;          ///< Sweep cap of the coarse (or single) stage; 300.
  int fine_max_iterations = 40;      ///< Sweep cap of two-stage's fine stage (it only refines locally); 40.
};

/// `density-flow`: error-model density, flow map, polish, re-pack of the charts (docs/error_model.md).
struct DensityFlowMethodOptions {
  ErrorDensityOptions density;       ///< The error model and its target density (error_density.h).
  DensityFlowOptions flow;           ///< The flow map: lattice size, accuracy (density_flow.h).
  ErrorPolishOptions polish;         ///< The polish of the flow lattices (error_polish.h; sweeps = 0: off).
  double chart_gutter_texels = 2.0;  ///< Least gap between re-packed charts, in texels (atlas_flow.h); 2.
};

/// Refinement of triangles too large for the warp (refine.h), for methods that ask for it.
struct WarpRefineOptions {
  bool enabled = true;              ///< false keeps the input's vertices (`--no-refine`); true.
  double tolerance_texels = 0.5;    ///< Largest deviation of the warp from linear along a UV edge, texels; 0.5.
  int max_levels = 4;               ///< Refinement rounds (each can halve an edge); 4.
  double max_face_factor = 4.0;     ///< Face budget, as a multiple of the input's face count; 4.
};

/// Settings of adapt_parameterization(), grouped by method and stage (docs/decisions.md: why).
struct AdaptOptions {
  AdaptMode mode = AdaptMode::DensityFlow;    ///< The method (method.h); density-flow.
  ThesisOptions thesis;                       ///< single / two-stage.
  DensityFlowMethodOptions density_flow;      ///< density-flow.
  WarpRefineOptions refine;                   ///< Refinement under the warp (density-flow).
  SafeRemapOptions remap;                     ///< Flip / degeneracy / overlap guarantees of the remap.
  bool geometry_safeguard = true;             ///< No signal at all: keep the warp only if it lowers L2; true.
  ProgressCallback progress;                  ///< Phases "importance" … "remap" (core/progress.h).
};

/// Timings (seconds) and figures of one re-parameterization (texture-update times: filled by the caller).
struct AdaptReport {
  AdaptMode mode = AdaptMode::TwoStage;
  double time_importance = 0, time_stretch_map = 0, time_ls2 = 0;
  double time_coarse = 0, time_fine = 0, time_remap = 0;
  double time_density = 0, time_flow = 0, time_polish = 0, time_refine = 0;  ///< density-flow phases.
  double time_texel_map = 0, time_texture_update = 0, time_safeguard = 0;
  double time_total = 0;       ///< Everything above.
  double l2_before = 0, l2_after = 0;  ///< Mesh L2 stretch (measure_stretch().l2, 1 = ideal).
  double damping = 1;          ///< Mean blend factor of the applied warp: 1 = full warp, 0 = none.
  double global_damping = 1;   ///< Global blend factor t of safe_remap() (1 unless local damping failed).
  int locally_damped = 0;      ///< Wedges damped locally by safe_remap() (their faces would have flipped).
  int coarse_iterations = 0, fine_iterations = 0;  ///< Relaxation sweeps per stage.
  int remap_checks = 0;        ///< Candidate layouts checked by safe_remap().
  int flipped_after = 0, degenerate_after = 0;  ///< Always 0 (guaranteed by safe_remap()).
  double signal_fraction = 0;  ///< Fraction of chart texels with E_h > 0.
  bool accepted = true;        ///< false: a safeguard kept the previous parameterization.
  double error_before = -1, error_after = -1;  ///< Safeguard error estimates (MSE), -1 if not run.
  double predicted_gain_db = 0;  ///< density-flow: the error model's predicted PSNR gain.
  double gain_over_held_db = 0;  ///< Each-stroke: predicted PSNR gain over the held layout (0: not computed).
  bool skipped = false;          ///< Each-stroke: the gate stopped the cycle (gain < min_gain_db; accepted false).
  int flow_tangled_cells = 0;    ///< density-flow: flow-grid cells untangled (density_flow.h).
  int flow_inverted_cells = 0;   ///< density-flow: cells still not convex after that (0 expected).
  long flow_steps = 0;           ///< density-flow: accepted integration steps over every lattice point.
  long flow_advected_points = 0; ///< density-flow: lattice points integrated (the others interpolated).
  int polish_sweeps = 0;         ///< density-flow: most polish sweeps of a lattice (error_polish.h).
  double polish_error_before = 0, polish_error_after = 0;  ///< density-flow: the polish's model error before / after.
  int polish_warm_lattices = 0;  ///< Always 0 (the polish always starts cold); kept in report.json.
  int faces_before = 0, faces_after = 0;  ///< Mesh faces before / after refinement.
};

/// Result of adapt_parameterization().
struct AdaptResult {
  Parameterization param;  ///< The new parameterization (== input when not accepted / mode None).
  AdaptReport report;
  ImageF importance;       ///< E_h at texture resolution (§3.5).
  ImageF stretch;          ///< Normalized geometry stretch map at texture resolution (Fig. 3.8).
  ImageF ls2;              ///< L_s² at texture resolution (§3.6), before pooling (thesis methods).
  ImageF density;          ///< density-flow: target area density per cell (mean 1; error_density.h).
  std::shared_ptr<const UvWarp> warp;               ///< The method's warp (uv_warp.h); null for None.
  std::shared_ptr<const TriMesh> refined_mesh;      ///< The refined mesh param belongs to; null: the input.
  std::shared_ptr<const Parameterization> refined_layout;  ///< With refined_mesh: its layout before the warp.
  FaceData<int> parent_face;  ///< With refined_mesh: input face id of every refined face (size F').
  std::vector<const GridWarp*> warps() const;  ///< The warp's lattices, in application order.
  Parameterization start_layout(const Parameterization& input) const;  ///< refined_layout or \p input, charts moved.
};

/// Re-parameterizes \p current from \p texture (its texel map \p current_map) and, if given, the exact
/// stroke \p history, with a new solver of options.mode (a session keeps one: adapt_with()).
/// \pre mesh, current and current_map are consistent; texture non-empty
/// \throw InvalidInputError inconsistent sizes, bad options (grid < 1, α/β < 0, ...), unknown mode
/// \throw CancelledError the progress callback returned false
AdaptResult adapt_parameterization(const TriMesh& mesh, const Parameterization& current,
                                   const ImageRGBA8& texture, const TexelMap& current_map,
                                   const AdaptOptions& options = {}, const StrokeFile* history = nullptr);

/// The same with a precomputed error model \p model (a layered material's: error_density.h) instead of
/// one from a history or the texture; \p texture is what the layout holds (the polish's edges read it).
/// Methods without an error model ignore \p model.
/// \throw as above
AdaptResult adapt_parameterization(const TriMesh& mesh, const Parameterization& current,
                                   const ImageRGBA8& texture, const TexelMap& current_map,
                                   const ErrorDensity& model, const AdaptOptions& options);

/// Name of a mode as used on the command line: "none", "single", "two-stage", "density-flow", ...
const char* to_string(AdaptMode mode);
/// The registered mode named \p name. \throw InvalidInputError otherwise (listing the names)
AdaptMode parse_adapt_mode(const std::string& name);
/// Every registered mode, in the order a UI lists them (None first).
std::vector<AdaptMode> adapt_modes();

}  // namespace adaptex
