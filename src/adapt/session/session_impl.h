#pragma once
// PaintSession::Impl, shared by the session's files (src/adapt/session/): layouts.cpp (the current,
// initial and resample layouts), surface_cache.cpp, safeguard.cpp, gain_gate.cpp, session.cpp (the cycle).
#include <chrono>
#include <memory>
#include <optional>
#include <vector>

#include "adaptex/adapt/method.h"
#include "adaptex/adapt/session.h"
#include "adaptex/paint/eval.h"
#include "adaptex/paint/signal.h"
#include "adaptex/paint/strokes.h"
#include "adaptex/paint/surface_cache.h"

namespace adaptex {

// The session's own types: a namespace of their own, so they cannot clash with a type of the same name
// elsewhere in the library.
namespace session_detail {

// Strokes painted since the last re-parameterization, in resample mode: composited over the
// resampled base (composite_over_base) from the segment painted over black and over white.
struct Segment {
  Painter black, white;
  bool empty = true;
};

// A candidate layout with its painter and texture.
struct Candidate {
  std::unique_ptr<Parameterization> param;
  std::unique_ptr<Painter> painter;
  ImageRGBA8 texture;
  bool from_cache = false;  // the texture was resampled from the surface cache
};

// The safeguard's view of one re-parameterization: the candidate's surface points (the session's
// samples, moved onto the refined mesh when the candidate refined it: the same 3-D points) and the
// exact stroke signal there.
struct SafeguardPoints {
  std::vector<SurfacePoint> moved;                 // the samples on the refined candidate mesh
  const std::vector<SurfacePoint>* kept = nullptr;  // else: the session's samples (candidate kept the mesh)
  std::vector<Vec3> exact;
  bool from_samples = false;  // the points are the session's samples (the same 3-D points)
  const std::vector<SurfacePoint>& points() const { return kept ? *kept : moved; }
};

}  // namespace session_detail
using session_detail::Candidate;
using session_detail::SafeguardPoints;
using session_detail::Segment;

struct PaintSession::Impl {
  TriMesh mesh;  // the input mesh
  // The mesh of param when a re-parameterization refined it (same surface, more faces); null: mesh.
  std::shared_ptr<const TriMesh> refined;
  std::vector<SurfacePoint> refined_samples;  // the safeguard samples moved onto *refined
  bool refined_moved = false;  // refined_samples are `samples` moved (same 3-D points), not drawn afresh
  const TriMesh& current_mesh() const { return refined ? *refined : mesh; }
  const std::vector<SurfacePoint>& current_samples() const { return refined ? refined_samples : samples; }
  PaintSessionOptions opt;
  std::unique_ptr<Parameterization> param;
  std::unique_ptr<Painter> painter;
  // Each-stroke mode: every re-parameterization starts from the initial layout (base) and the history
  // painted on it, so warps never compose over many strokes (no drift, no accumulated distortion) and
  // the last one equals what end mode computes.
  std::unique_ptr<Parameterization> base_param;
  std::unique_ptr<Painter> base_painter;
  StrokeFile history;
  std::vector<AdaptReport> reports;
  std::unique_ptr<AdaptResult> last;
  // Resample mode after the first re-parameterization: base texture + segment painters.
  bool resampled = false;
  ImageRGBA8 base;
  std::unique_ptr<Segment> segment;
  ImageRGBA8 composite;
  bool composite_dirty = true;
  Stroke open_style;
  std::vector<Vec3> open_dabs;
  bool open = false;
  std::vector<SurfacePoint> samples;
  // The exact history signal at `samples`, updated stroke by stroke (O(stroke), not O(history)).
  std::unique_ptr<PointSignalCache> signal_cache;
  // Each-stroke mode, opt.surface_cache > 0, once the history covers the surface
  // opt.surface_cache_coverage times: the signal on per-face samples of the input mesh, updated
  // stroke by stroke.
  std::unique_ptr<SurfaceSignalCache> surface;
  bool surface_fits = false;  // the lattice has at most kMaxSurfaceCacheSamples samples
  double coverage = 0;        // Σ over the history's dabs of π r² / surface area (a decal: 1)
  double area = 0;            // surface area of the input mesh
  bool held_from_cache = false;  // the held texture was resampled from the surface cache
  bool exact_only = false;       // finish(): this cycle replays exactly
  // The method's solver, for the session's life (method.h): with a fixed layout it keeps what it
  // derives from that layout and the history (density-flow: the error model's reference).
  std::unique_ptr<AdaptMethod> method;
  double texel_spacing = 0;  // sqrt(surface area / chart texels) of the initial layout
  int reparam_count = 0;
  bool adapted = false;  ///< A re-parameterization has been accepted: the current layout is adapted.
  // Each-stroke gating (opt.min_gain_db): the held layout's measured error (the safeguard's MSE on the samples) and the model's least error
  // (predicted_error at its own density) when it was made; -1: unknown (then only the model predicts).
  double held_error = -1, held_best = -1;
  bool pending = false;
  /// History strokes the last completed (not skipped) re-parameterization saw.
  size_t cycle_strokes = 0;
  double held_l2 = -1;  // the held layout's L2 stretch (reports' l2_after), -1: not measured yet

  PainterOptions painter_options() const {
    PainterOptions p;
    p.width = p.height = opt.texture_size;
    p.padding = opt.padding;
    return p;
  }

  const ImageRGBA8& texture();

  void new_segment();

  void paint(const Stroke& s);

  /// The safeguard's samples on the input mesh (and on the current refined mesh), drawn once.
  void ensure_samples();

  /// Whether \p pts are the samples' 3-D points: `samples`, or refined_samples moved from them.
  bool are_samples(const std::vector<SurfacePoint>& pts) const;

  /// The exact history signal at \p pts (the same 3-D points as `samples`, see are_samples) from the
  /// signal cache, brought up to date; null when the cache does not apply (other points, or decals,
  /// whose value depends on the face a point lies on): then StrokeSignal evaluates the history.
  const std::vector<Vec3>* cached_signal(const std::vector<SurfacePoint>& pts);

  /// Whether textures of layouts of the input mesh come from the surface cache now
  /// (PaintSessionOptions::surface_cache, surface_cache_coverage).
  bool uses_surface_cache() const;

  /// The surface cache, built on first use (from the whole history) and brought up to date with it.
  SurfaceSignalCache& surface_cache_now();

  /// \p p's texture from the surface cache (\p p: a fresh painter of a layout of the input mesh, or of
  /// a refinement of it with \p parent_face).
  const ImageRGBA8& texture_from_cache(Painter& p, const TriMesh& m, const std::vector<int>* parent_face);

  /// Records \p s in the history; with the safeguard on, composites it into the signal cache now
  /// (O(stroke)), so a re-parameterization finds the cache up to date.
  void record_stroke(Stroke s);

  /// The exact history signal at \p pts of \p m: cached when possible, else evaluated.
  std::vector<Vec3> exact_signal(const std::vector<SurfacePoint>& src, const TriMesh& m,
                                 const std::vector<SurfacePoint>& pts);

  /// The settings of a re-parameterization requested now.
  AdaptOptions adapt_options() const;

  /// Each-stroke mode with replay: the layout is a function of the history alone. Every candidate is
  /// computed from the initial layout (as end mode does) and judged against the initial layout (as end
  /// mode does), so after any stroke the session holds exactly what end mode gives for the history so
  /// far; an earlier candidate, computed for part of the history, is never preferred to it on the
  /// strength of the estimate (measured before: spot lines 256², 50 strokes, a kept earlier layout was
  /// 0.11 dB below end mode). Resample mode's texture depends on the path anyway: it is judged against
  /// the current layout.
  bool path_independent() const { return base_param && opt.update == TextureUpdate::Replay; }

  // Each-stroke mode starts from the initial layout on the input mesh, end mode from the current one.
  const TriMesh& source_mesh() const { return base_param ? mesh : current_mesh(); }
  const Parameterization& source_param() const { return base_param ? *base_param : *param; }

  /// Each-stroke mode with replay: every cycle starts from the initial layout on the input mesh, both
  /// fixed for the session's life, so the method may cache what it derives from them
  /// (AdaptMethod::fix_layout()).
  bool fixed_layout() const { return base_param && opt.update == TextureUpdate::Replay; }

  std::unique_ptr<AdaptResult> compute(const AdaptOptions& ao);

  /// Moves the samples to the candidate's mesh, evaluates the exact signal there and the reference
  /// layout's error (rep.error_before): the initial layout's if path_independent(), else the current's.
  SafeguardPoints prepare_safeguard(const AdaptResult& res, const TriMesh& cand_mesh, AdaptReport& rep);

  /// The candidate layout of \p res damped to \p t (1: as computed), its painter and texture.
  Candidate make_candidate(AdaptResult& res, double t, const AdaptOptions& ao, const TriMesh& cand_mesh);

  /// The safeguard: the candidate, else the candidate damped by half, if its error is below the
  /// limit. \return whether \p c holds an accepted candidate.
  bool judge(Candidate& c, AdaptResult& res, const SafeguardPoints& sg, const AdaptOptions& ao,
             const TriMesh& cand_mesh);

  /// The candidate becomes the current layout.
  void adopt(Candidate&& c, AdaptResult& res, SafeguardPoints&& sg);

  /// Path-independent mode without an accepted candidate: the initial layout, the history replayed.
  void return_to_initial();

  /// The candidate is rejected: the session keeps its layout (path_independent(): returns to the
  /// initial layout, what end mode keeps), the report says so.
  void keep(AdaptResult& res);

  const AdaptReport& record(std::unique_ptr<AdaptResult> res, std::chrono::steady_clock::time_point t_all);

  /// Each-stroke mode with replay (fixed_layout()) and a history: the method's model for the history
  /// so far (AdaptMethod::predict_gain()), and its predicted gain in dB over the held layout.
  ///
  /// The gain over the held layout: where the held layout's error was measured when it was made
  /// (held_error, with the model's least error then, held_best), the error a new layout would reach
  /// now is predicted as held_error × best / held_best (the model's least error scaled from then to
  /// now), and compared with the held layout's error measured now on the same samples. This sees what
  /// the isotropic model cannot: a new stroke across the direction the held layout's texels were
  /// stretched along (error_polish.h). Otherwise: the model alone, E(ρ_held) / E(ρ_new).
  struct Model {
    GainModel gain;
    double gain_over_held_db = 0;
    double seconds = 0;
  };
  /// \p measure: measure the held layout's error now (only a gated cycle needs it: it decides).
  std::optional<Model> model_now(const AdaptOptions& ao, bool measure);

  /// The current texture's MSE against the exact history on the safeguard's samples (0 without
  /// strokes, -1 without samples).
  double current_error();

  /// The report of a cycle that stopped after the error model (gain below opt.min_gain_db).
  const AdaptReport& skip(const AdaptOptions& ao, const Model& m, std::chrono::steady_clock::time_point t_all);

  /// \p gated: each-stroke mode's cycle after a stroke, which may stop after the error model
  /// (opt.min_gain_db); false: re-parameterize whatever the model predicts.
  const AdaptReport& reparameterize(bool gated);
};

}  // namespace adaptex
