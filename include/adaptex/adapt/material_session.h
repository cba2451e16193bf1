#pragma once
/// \file material_session.h
/// A painting session of a layered material (stroke file version 2) with each-stroke adaptation: the
/// version 2 analogue of PaintSession (session.h). Every cycle starts from the initial layout and the
/// history so far (path independent, as PaintSession's each-stroke mode with replay), so after any
/// stroke the session holds what adapt_material() computes for that history, except that a cycle may
/// be skipped by the gain gate. What it keeps between strokes, so that a cycle does not re-evaluate
/// the history (docs/adaptive.md, "Material sessions"):
///   - the exact material, per layer and channel, at the initial layout's chart texels, at the error
///     model's reference and N/2 points, and at the never-worse check's samples (MaterialPointCache,
///     updated with each stroke only);
///   - once the history covers the surface surface_cache_coverage times: the surface cache
///     (MaterialSurfaceCache, per layer, channel and mask on a lattice finer than the texels),
///     from which each candidate layout's textures are interpolated, whatever the history's length;
///   - else the candidate's texels (a MaterialPointCache: the history replayed onto the new layout
///     once, then stroke by stroke).
///
///   MaterialPaintSession s(mesh, unwrap(mesh).param, file_with_layers, opts);
///   s.add_stroke(layer, stroke);  // paints, then one gated cycle
#include <cstdint>
#include <memory>
#include <vector>

#include "adaptex/adapt/adapt.h"
#include "adaptex/adapt/material_adapt.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/paint/material_eval.h"
#include "adaptex/paint/material_paint.h"
#include "adaptex/paint/material_strokes.h"

namespace adaptex {

/// Settings of a MaterialPaintSession.
struct MaterialSessionOptions {
  MaterialPaintOptions paint;  ///< Texture size and seam padding (default 1024², 4).
  AdaptOptions adapt;          ///< The adaptation: density-flow (default) or none (paint only).
  double data_weight = 0.25;   ///< Weight of roughness / metallic / alpha in the error model (default 0.25).
  /// Samples of the never-worse check, [1, 10^7] (default 60000, as PaintSessionOptions::safeguard_samples).
  long long check_samples = 60000;
  std::uint64_t check_seed = 17;     ///< Seed of those samples (default 17, as adapt_material()).
  double check_margin = 0.02;  ///< The adapted layout's error must be < (1 − margin) × the initial's; 0.02.
  double min_gain_db = 0.3;    ///< Skip cycles whose model predicts less gain over the held layout, dB; 0.3.
  /// Candidate layouts' textures from the surface cache (MaterialSurfaceCache): its samples per
  /// texel of the initial layout (0: off, every candidate replays the history exactly); 1.5.
  double surface_cache = 1.5;
  double surface_cache_coverage = 4;  ///< Covers of the surface by the history from which it is used; 4.
};

/// Largest surface cache of a material session (samples; ~250 bytes each with three layers).
inline constexpr long long kMaxMaterialSurfaceCacheSamples = 12'000'000;

class MaterialPaintSession {
 public:
  /// \param file the layers (names, blend modes, masks, ...), background and height scale; its strokes
  ///        are the history so far (painted now, adapted at the first cycle)
  /// \throw InvalidInputError bad options (a mode other than density-flow or none), layout/mesh mismatch
  MaterialPaintSession(TriMesh mesh, Parameterization initial, MaterialStrokeFile file,
                       const MaterialSessionOptions& options = {});
  ~MaterialPaintSession();
  MaterialPaintSession(const MaterialPaintSession&) = delete;
  MaterialPaintSession& operator=(const MaterialPaintSession&) = delete;

  /// Appends \p stroke to layer \p layer (its mask when \p to_mask), then runs one gated cycle.
  /// \throw InvalidInputError layer out of range, no mask, a stroke breaking docs/strokes.md's rules
  ///        (validate_material_stroke(): a stroke or decal with no channel too; checked first:
  ///        nothing changes)
  void add_stroke(int layer, const MaterialStroke& stroke, bool to_mask = false);
  /// Appends several strokes to layer \p layer, then one gated cycle. \throw as add_stroke()
  void add_strokes(int layer, const std::vector<MaterialStroke>& strokes);
  /// One cycle now, whatever the gate. \return its report (in reports())
  const AdaptReport& reparameterize();

  const TriMesh& mesh() const;              ///< The held layout's mesh (the input, or its refinement).
  const Parameterization& param() const;    ///< The held layout.
  /// The held layout's refined mesh: the input face of every face (size F'); empty: the input mesh.
  const FaceData<int>& parent_face() const;
  const MaterialTextures& textures();       ///< Every channel on the held layout, the history painted.
  const MaterialStrokeFile& history() const;
  const std::vector<AdaptReport>& reports() const;  ///< One per cycle (skipped ones: AdaptReport::skipped).
  bool adapted() const;                     ///< The held layout is an adapted one (else the initial).
  /// The never-worse check's judgement (every channel, the height through its normal; material_eval.h)
  /// of the held textures, and of the initial layout's with the same history, on the same samples.
  MaterialError held_error();
  MaterialError initial_error();
  /// Samples of the surface cache (0: not built: off, too large, or the history too short yet).
  long long surface_cache_samples() const;
  /// The held layout's textures come from the surface cache (else they are exact).
  bool held_from_cache() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace adaptex
