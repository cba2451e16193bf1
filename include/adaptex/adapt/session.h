#pragma once
/// \file session.h
/// A painting session with signal-adaptive re-parameterization (thesis Fig. 3.1). Each-stroke mode
/// adapts from the *initial* layout every time (it holds end mode's layout for the history so far);
/// the "never worse" safeguard keeps a candidate only if its estimated MSE is lower. docs/adaptive.md.
///
///   PaintSession s(mesh, unwrap(mesh).param, opts, history.background);
///   for (auto& st : history.strokes) s.add_stroke(st);   // each-stroke mode re-parameterizes here
///   s.finish();                                          // end mode re-parameterizes once here
#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

#include "adaptex/adapt/adapt.h"
#include "adaptex/adapt/adapt_report.h"
#include "adaptex/adapt/debug_maps.h"
#include "adaptex/adapt/texture_update.h"
#include "adaptex/core/image.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/paint/painter.h"
#include "adaptex/paint/strokes.h"

namespace adaptex {

/// When a session re-parameterizes.
enum class ReparamSchedule {
  EachStroke,  ///< After every stroke (as the interactive app does).
  End,         ///< Once, in finish().
};
/// "end", "each-stroke" (alias "each_stroke").
template <>
std::span<const EnumName<ReparamSchedule>> enum_names<ReparamSchedule>();

inline constexpr int kMaxSafeguardSamples = 10'000'000;          ///< ~100 bytes each (1 GB).
inline constexpr long long kMaxSurfaceCacheSamples = 50'000'000;  ///< Surface cache samples (400 MB).

/// Settings of a PaintSession (docs/decisions.md: why each default).
struct PaintSessionOptions {
  int texture_size = 1024;  ///< Texture width = height in texels.
  int padding = 4;          ///< Seam padding in texels.
  AdaptOptions adapt;       ///< Re-parameterization settings; adapt.mode = None disables it.
  ReparamSchedule schedule = ReparamSchedule::End;  ///< each-stroke | end.
  TextureUpdate update = TextureUpdate::Replay;     ///< replay | resample.
  bool safeguard = true;                     ///< The "never worse" check (needs the history); true.
  int safeguard_samples = 60000;             ///< Its surface samples, [0, kMaxSafeguardSamples] (0: off); 60000.
  std::uint64_t safeguard_seed = 0x5eedada;  ///< Seed of those samples (paint/eval.h sample_surface).
  double safeguard_margin = 0.02;            ///< Against the initial layout: MSE must be < (1 − margin)×; 0.02.
  double surface_cache = 3;                  ///< Each-stroke replay: surface cache samples per texel (0: off); 3.
  double surface_cache_coverage = 4;         ///< Covers of the surface from which the cache is used; 4.
  double min_gain_db = 0.3;                  ///< Each-stroke: skip cycles predicted to gain less, dB (0: none); 0.3.
  std::filesystem::path debug_dir;  ///< If set: PNGs of the maps and grids of every re-parameterization.
};

class PaintSession {
 public:
  /// \param background colour of unpainted surface \throw InvalidInputError bad options, param/mesh mismatch
  PaintSession(TriMesh mesh, Parameterization initial, const PaintSessionOptions& options,
               const Vec3& background = Vec3(1, 1, 1));
  ~PaintSession();
  PaintSession(const PaintSession&) = delete;
  PaintSession& operator=(const PaintSession&) = delete;

  /// Paints a whole stroke, records it in the history, and in each-stroke mode re-parameterizes.
  void add_stroke(const Stroke& stroke);
  /// Paints and records several strokes, then (each-stroke mode) one gated cycle for them all.
  /// \throw InvalidInputError a stroke breaks the contract (checked first: nothing is painted)
  /// \throw CancelledError the cycle was cancelled (strokes stay recorded, layout unchanged)
  void add_strokes(const std::vector<Stroke>& strokes);
  /// Interactive painting: begin / dabs (touched texel rectangle) / end (records, may re-parameterize).
  void begin_stroke(const Stroke& style);
  std::array<int, 4> add_dab(const Vec3& centre);
  void end_stroke();
  /// Ends on end mode's layout and texture: end mode adapts once, each-stroke once more unless settled().
  void finish();
  /// Re-parameterizes now, whatever the schedule and min_gain_db. \return the report (in reports())
  const AdaptReport& reparameterize();
  /// finish() would change nothing (the last cycle saw the whole history, replayed exactly, cold).
  bool settled() const;

  const TriMesh& mesh() const;
  const Parameterization& param() const;   ///< Current parameterization.
  const ImageRGBA8& texture();             ///< Current texture (padded).
  const TexelMap& texel_map() const;       ///< Texel map of the current parameterization.
  const StrokeFile& history() const;       ///< Every stroke painted so far.
  /// One per cycle: per re-parameterization, and per skipped cycle (AdaptReport::skipped).
  const std::vector<AdaptReport>& reports() const;
  /// Maps / grids of the last re-parameterization that was not skipped (or null).
  const AdaptResult* last_result() const;
  const PaintSessionOptions& options() const;
  /// Samples of the surface signal cache; 0 while it is not built.
  long long surface_cache_samples() const;
  Painter& painter();                      ///< The painter of the current parameterization.
  /// Estimated MSE of the texture against the exact history on the safeguard's samples (0: no strokes).
  double estimate_error();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace adaptex
