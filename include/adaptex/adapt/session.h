#pragma once
/// \file session.h
/// A painting session with signal-adaptive re-parameterization (the thesis' interactive loop,
/// Fig. 3.1): the mesh, its current parameterization, the exact stroke history, a Painter for the
/// current texture, and the re-parameterization policy. Used by `adaptex paint` and by the studio.
///
///   PaintSession s(mesh, unwrap(mesh).param, opts, history.background);
///   for (auto& st : history.strokes) s.add_stroke(st);   // each-stroke mode re-parameterizes here
///   s.finish();                                          // end mode re-parameterizes once here
///   write(s.param(), s.texture());  json["adapt"] = adapt_reports_json(s.reports());
///
/// Each-stroke mode re-parameterizes from the *initial* layout every time (the history is also painted
/// on it): warps never compose over many strokes, so the layout cannot drift or accumulate distortion,
/// and after the last stroke the layout is the one end mode computes (docs/adaptive.md).
///
/// Never worse (safeguard): with a history, each candidate parameterization is judged by the
/// reconstruction error of its replayed texture against the exact stroke signal on a fixed set of
/// surface samples (uniform by area; paint/eval.h reconstruction_mse); the candidate, else the
/// candidate damped by half, is kept only if its error is lower than the reference layout's
/// (report.error_before); otherwise the session keeps its parameterization (report.accepted = false).
/// The reference is the initial layout in end mode and in each-stroke mode with replay, so each-stroke
/// mode is path independent: after every stroke it holds exactly the layout (and replayed texture)
/// that end mode gives for the history so far; a rejected candidate returns it to the initial layout,
/// as end mode would keep it (an earlier candidate, computed for part of the history, is not kept on
/// the strength of the estimate). In resample mode, and when reparameterize() is called again in end
/// mode, the reference is the current layout.
/// With PaintSessionOptions::min_gain_db > 0, each-stroke mode skips the cycles whose predicted gain
/// is below it (the layout is then end mode's for an earlier part of the history) and finish() catches
/// up, so the last layout is still end mode's.
/// The exact signal at the samples is kept up to date stroke by stroke (paint/signal.h
/// PointSignalCache), so the safeguard does not evaluate the whole history again after every stroke.
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

/// Largest PaintSessionOptions::safeguard_samples: the samples and their cached signal take ~100 bytes
/// each (1 GB here).
inline constexpr int kMaxSafeguardSamples = 10'000'000;
/// Largest surface signal cache of a session (PaintSessionOptions::surface_cache): 50 million samples
/// (400 MB).
inline constexpr long long kMaxSurfaceCacheSamples = 50'000'000;

/// Settings of a PaintSession. (The command line's option strings are parsed in apps/cli,
/// session_options.h.)
struct PaintSessionOptions {
  int texture_size = 1024;  ///< Texture width = height in texels.
  int padding = 4;          ///< Seam padding in texels.
  AdaptOptions adapt;       ///< Re-parameterization settings; adapt.mode = None disables it.
  ReparamSchedule schedule = ReparamSchedule::End;  ///< each-stroke | end.
  TextureUpdate update = TextureUpdate::Replay;     ///< replay | resample.
  bool safeguard = true;       ///< The "never worse" check described above (needs the history).
  /// Surface samples of the safeguard's error estimate, in [0, kMaxSafeguardSamples] (0: no estimate,
  /// so no safeguard: every candidate is taken).
  int safeguard_samples = 60000;
  std::uint64_t safeguard_seed = 0x5eedada;  ///< Seed of those samples (paint/eval.h sample_surface).
  /// Accept a candidate only if its estimated MSE is below (1 - margin) x the reference's, whenever
  /// the reference is the fixed (initial) layout; against an adapted current layout (resample mode,
  /// or end mode re-parameterizing again) a candidate only has to be better (docs/decisions.md, "The
  /// never-worse safeguard and its 0.02 margin").
  double safeguard_margin = 0.02;
  /// Each-stroke mode with replay: once the history's dabs cover the surface surface_cache_coverage
  /// times (Σ π r² / area; a decal counts 1), a candidate's texture is resampled in O(texels) from a
  /// surface signal cache (paint/surface_cache.h) instead of replaying the history. The value is the
  /// samples per texel spacing of the initial layout (8 bytes each; a lattice of more than
  /// kMaxSurfaceCacheSamples is not built). 0: always exact replay. finish() ends on exact replay.
  /// End mode never uses it (docs/decisions.md, "Replay exactly, then resample from a surface cache").
  double surface_cache = 3;
  double surface_cache_coverage = 4;  ///< Covers of the surface from which the surface cache is used (0: at once).
  /// Each-stroke mode with replay: after a stroke, re-parameterize only if the method's model predicts
  /// a gain of at least this PSNR, in dB, over the held layout (AdaptMethod::predict_gain(); where the
  /// safeguard measured the held layout's error, that error scaled by the model's least error from
  /// then to now against the held layout's error now); otherwise the report says `skipped` and the
  /// strokes add up for the next cycle. finish() catches up, so the session ends on end mode's layout.
  /// 0: a cycle after every stroke (docs/decisions.md, "The min-gain gate").
  double min_gain_db = 0.3;
  /// Each-stroke mode: a cycle after a stroke may start from the method's previous cycle (density-flow:
  /// its polish, ErrorPolishOptions::warm_sweeps). The held layouts then depend on which cycles ran;
  /// finish() runs the last cycle again cold. Off (docs/decisions.md, "Warm start of the polish: off").
  bool warm_start = false;
  std::filesystem::path debug_dir;  ///< If set: PNGs of the maps and grids of every re-parameterization.
};

class PaintSession {
 public:
  /// \param mesh the surface (moved into the session)
  /// \param initial its initial parameterization (e.g. unwrap(mesh).param)
  /// \param background colour of unpainted surface (the history's background)
  /// \throw InvalidInputError bad options (texture size outside [1, kMaxTextureSize], negative padding,
  ///        safeguard_samples outside [0, kMaxSafeguardSamples], surface_cache or surface_cache_coverage
  ///        negative or not finite) or param/mesh mismatch
  PaintSession(TriMesh mesh, Parameterization initial, const PaintSessionOptions& options,
               const Vec3& background = Vec3(1, 1, 1));
  ~PaintSession();
  PaintSession(const PaintSession&) = delete;
  PaintSession& operator=(const PaintSession&) = delete;

  /// Paints a whole stroke, records it in the history, and in each-stroke mode re-parameterizes.
  void add_stroke(const Stroke& stroke);
  /// Paints several whole strokes and records them; in each-stroke mode then runs one cycle (gated by
  /// min_gain_db) as if they were one stroke. A background session that receives strokes faster than
  /// it adapts (the studio) catches up with one cycle instead of one per stroke. Nothing for an empty
  /// list. \throw InvalidInputError a stroke breaks the contract (checked first: nothing is painted);
  /// CancelledError the cycle was cancelled through AdaptOptions::progress (the strokes stay painted
  /// and recorded, the layout is unchanged, and settled() is false)
  void add_strokes(const std::vector<Stroke>& strokes);
  /// Interactive painting (studio): begin / dabs / end; end_stroke() records the stroke (with all its
  /// dabs) and in each-stroke mode re-parameterizes. add_dab returns the touched texel rectangle.
  void begin_stroke(const Stroke& style);
  std::array<int, 4> add_dab(const Vec3& centre);
  void end_stroke();
  /// End mode: re-parameterizes once. Each-stroke mode: re-parameterizes, cold and with exact replay,
  /// if the last cycle was skipped (min_gain_db), the held texture came from the surface cache
  /// (surface_cache) or the held layout was warm-started (warm_start), so that the session ends on end
  /// mode's layout and texture. No-op with mode None.
  void finish();
  /// Re-parameterizes now, whatever the schedule and min_gain_db. \return the report (also appended
  /// to reports()).
  const AdaptReport& reparameterize();
  /// finish() would change nothing: no strokes, mode None, or the last completed re-parameterization
  /// saw the whole history, its texture was replayed exactly (not resampled from the surface cache)
  /// and the held layout was not warm-started.
  /// Each-stroke mode is then on end mode's layout and texture for the history so far.
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
  /// Samples of the surface signal cache (PaintSessionOptions::surface_cache); 0 while it is not built
  /// (short history, end mode, surface_cache 0, or a lattice too large).
  long long surface_cache_samples() const;
  Painter& painter();                      ///< The painter of the current parameterization.
  /// Estimated reconstruction MSE of the current texture against the exact history signal on the
  /// safeguard's surface samples (0 without strokes).
  double estimate_error();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace adaptex
