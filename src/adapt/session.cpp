// PaintSession: the painting loop with signal-adaptive re-parameterization (thesis Fig. 3.1).
// Texture update (replay / resample): texture_update.h; the safeguard's error: paint/eval.h
// (reconstruction_mse) at samples carried to refined meshes by point_transfer.h; report JSON and debug
// pictures: adapt_report.h, debug_maps.h; option strings: apps/cli/session_options.h.
#include "adaptex/adapt/session.h"

#include <chrono>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>

#include "adaptex/paint/point_transfer.h"
#include "adaptex/adapt/method.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "adaptex/core/timer.h"
#include "adaptex/paint/eval.h"
#include "adaptex/paint/signal.h"
#include "adaptex/paint/strokes.h"
#include "adaptex/paint/surface_cache.h"
#include "adaptex/param/stretch.h"

namespace adaptex {

namespace {

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
}  // namespace

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
  bool held_warm = false;        // the held layout's polish started from an earlier cycle's (warm_start)
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

  const ImageRGBA8& texture() {
    if (!resampled) return painter->texture();
    if (!segment || segment->empty) return base;
    if (composite_dirty) {
      composite = composite_over_base(base, segment->black.texture(), segment->white.texture(), painter->texel_map(),
                                      opt.padding);
      composite_dirty = false;
    }
    return composite;
  }

  void new_segment() {
    const PainterOptions po = painter_options();
    segment = std::make_unique<Segment>(Segment{Painter(current_mesh(), *param, po, Vec3(0, 0, 0)),
                                                Painter(current_mesh(), *param, po, Vec3(1, 1, 1)), true});
  }

  void paint(const Stroke& s) {
    if (base_painter) base_painter->paint_stroke(s);
    painter->paint_stroke(s);  // keeps the painter's own (replay-exact) texture for the history too
    if (resampled) {
      segment->black.paint_stroke(s);
      segment->white.paint_stroke(s);
      segment->empty = false;
      composite_dirty = true;
    }
  }

  /// The safeguard's samples on the input mesh (and on the current refined mesh), drawn once.
  void ensure_samples() {
    if (samples.empty()) samples = sample_surface(mesh, opt.safeguard_samples, opt.safeguard_seed);
    if (refined && refined_samples.size() != samples.size()) {  // refined without a safeguard run
      refined_samples = sample_surface(*refined, opt.safeguard_samples, opt.safeguard_seed);
      refined_moved = false;
    }
  }

  /// Whether \p pts are the samples' 3-D points: `samples`, or refined_samples moved from them.
  bool are_samples(const std::vector<SurfacePoint>& pts) const {
    return &pts == &samples || (&pts == &refined_samples && refined_moved);
  }

  /// The exact history signal at \p pts (the same 3-D points as `samples`, see are_samples) from the
  /// signal cache, brought up to date; null when the cache does not apply (other points, or decals,
  /// whose value depends on the face a point lies on): then StrokeSignal evaluates the history.
  const std::vector<Vec3>* cached_signal(const std::vector<SurfacePoint>& pts) {
    if (!are_samples(pts) || samples.empty()) return nullptr;
    if (!signal_cache) signal_cache = std::make_unique<PointSignalCache>(mesh, samples, history.background);
    signal_cache->update(history);
    return signal_cache->has_decals() ? nullptr : &signal_cache->values();
  }

  /// Whether textures of layouts of the input mesh come from the surface cache now
  /// (PaintSessionOptions::surface_cache, surface_cache_coverage).
  bool uses_surface_cache() const {
    return surface_fits && base_param && opt.update == TextureUpdate::Replay && !exact_only &&
           coverage >= opt.surface_cache_coverage && !history.strokes.empty();
  }

  /// The surface cache, built on first use (from the whole history) and brought up to date with it.
  SurfaceSignalCache& surface_cache_now() {
    if (!surface)
      surface = std::make_unique<SurfaceSignalCache>(mesh, texel_spacing / opt.surface_cache, history.background,
                                                     kMaxSurfaceCacheSamples);
    surface->update(history);
    return *surface;
  }

  /// \p p's texture from the surface cache (\p p: a fresh painter of a layout of the input mesh, or of
  /// a refinement of it with \p parent_face).
  const ImageRGBA8& texture_from_cache(Painter& p, const TriMesh& m, const std::vector<int>* parent_face) {
    p.fill_colours(surface_cache_now().texel_colours(p.texel_map(), m, parent_face));
    return p.texture();
  }

  /// Records \p s in the history; with the safeguard on, composites it into the signal cache now
  /// (O(stroke)), so a re-parameterization finds the cache up to date.
  void record_stroke(Stroke s) {
    coverage += s.type == Stroke::Type::Decal ? 1.0 : s.dabs.size() * std::numbers::pi * s.radius * s.radius / area;
    history.strokes.push_back(std::move(s));
    if (uses_surface_cache()) surface_cache_now();
    if (fixed_layout()) method->update(history, adapt_options());  // O(stroke) now, not O(history) later
    if (!opt.safeguard || opt.safeguard_samples == 0) return;
    ensure_samples();
    cached_signal(samples);
  }

  /// The exact history signal at \p pts of \p m: cached when possible, else evaluated.
  std::vector<Vec3> exact_signal(const std::vector<SurfacePoint>& src, const TriMesh& m,
                                 const std::vector<SurfacePoint>& pts) {
    if (const std::vector<Vec3>* c = cached_signal(src)) return *c;
    return StrokeSignal(m, history).evaluate(pts);
  }

  /// The settings of a re-parameterization requested now.
  AdaptOptions adapt_options() const {
    AdaptOptions ao = opt.adapt;
    if (ao.mode == AdaptMode::None) ao.mode = AdaptOptions{}.mode;  // explicit request: the default method
    // Resample mode maps old texels to new ones face by face: it keeps the mesh.
    if (opt.update == TextureUpdate::Resample) ao.refine = false;
    return ao;
  }

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

  /// \p warm: the cycle may start from the method's previous one (each-stroke mode).
  std::unique_ptr<AdaptResult> compute(const AdaptOptions& ao, bool warm) {
    if (base_painter)
      return std::make_unique<AdaptResult>(adapt_with(
          *method, WarpInput{mesh, *base_param, base_painter->texture(), base_painter->texel_map(), &history, ao, warm}));
    return std::make_unique<AdaptResult>(
        adapt_with(*method, WarpInput{current_mesh(), *param, texture(), painter->texel_map(), &history, ao}));
  }

  /// Moves the samples to the candidate's mesh, evaluates the exact signal there and the reference
  /// layout's error (rep.error_before): the initial layout's if path_independent(), else the current's.
  SafeguardPoints prepare_safeguard(const AdaptResult& res, const TriMesh& cand_mesh, AdaptReport& rep) {
    SafeguardPoints sg;
    const std::vector<SurfacePoint>& src_pts = base_param ? samples : current_samples();
    if (res.refined_mesh && !src_pts.empty())
      sg.moved = transfer_points(src_pts, source_mesh(), cand_mesh, res.parent_face);
    if (!res.refined_mesh) sg.kept = &src_pts;
    sg.from_samples = are_samples(src_pts);
    sg.exact = exact_signal(src_pts, cand_mesh, sg.points());
    const bool initial = path_independent();
    const std::vector<SurfacePoint>& ref_pts = initial ? samples : current_samples();
    // Without refinement the candidate's points are the reference's: evaluate the signal once.
    const std::vector<Vec3> ref_exact = sg.kept == &ref_pts ? std::vector<Vec3>{}
                                                            : exact_signal(ref_pts, initial ? mesh : current_mesh(), ref_pts);
    rep.error_before = reconstruction_mse(initial ? *base_param : *param, initial ? base_painter->texture() : texture(),
                                          ref_pts, sg.kept == &ref_pts ? sg.exact : ref_exact);
    return sg;
  }

  /// The candidate layout of \p res damped to \p t (1: as computed), its painter and texture.
  Candidate make_candidate(AdaptResult& res, double t, const AdaptOptions& ao, const TriMesh& cand_mesh) {
    AdaptReport& rep = res.report;
    Candidate c;
    if (t == 1.0) {
      c.param = std::make_unique<Parameterization>(res.param);
    } else {
      const Parameterization start = res.start_layout(source_param());
      c.param = std::make_unique<Parameterization>(
          safe_remap_layout(start, res.warp->warp_layout(start, t * rep.damping), ao.remap).param);
    }
    auto tm = std::chrono::steady_clock::now();
    c.painter = std::make_unique<Painter>(cand_mesh, *c.param, painter_options(), history.background);
    rep.time_texel_map += seconds_since(tm);
    tm = std::chrono::steady_clock::now();
    // Resample: the visible texture is the resampled one; the new painter only provides the texel map
    // (and the segment painters paint the strokes that follow).
    c.from_cache = uses_surface_cache() && &source_mesh() == &mesh;
    if (c.from_cache)
      c.texture = texture_from_cache(*c.painter, cand_mesh, res.refined_mesh ? &res.parent_face : nullptr);
    else
      c.texture = update_texture(opt.update, *c.painter, history, *param, texture(), opt.padding, ao.progress);
    rep.time_texture_update += seconds_since(tm);
    return c;
  }

  /// The safeguard: the candidate, else the candidate damped by half, if its error is below the
  /// limit. \return whether \p c holds an accepted candidate.
  bool judge(Candidate& c, AdaptResult& res, const SafeguardPoints& sg, const AdaptOptions& ao,
             const TriMesh& cand_mesh) {
    AdaptReport& rep = res.report;
    auto t0 = std::chrono::steady_clock::now();
    rep.error_after = reconstruction_mse(*c.param, c.texture, sg.points(), sg.exact);
    // The margin guards the fixed layout against an adapted one that only the estimate finds better.
    // End mode asked again (or resample mode) once the current layout is adapted: any better candidate
    // replaces it.
    const bool against_fixed = path_independent() || !adapted;
    const double limit = rep.error_before * (1.0 - (against_fixed ? opt.safeguard_margin : 0.0));
    rep.time_safeguard += seconds_since(t0);
    if (rep.error_after < limit) return true;
    Candidate half = make_candidate(res, 0.5, ao, cand_mesh);
    t0 = std::chrono::steady_clock::now();
    const double eh = reconstruction_mse(*half.param, half.texture, sg.points(), sg.exact);
    rep.time_safeguard += seconds_since(t0);
    if (!(eh < limit)) return false;
    c = std::move(half);
    rep.error_after = eh;
    rep.damping *= 0.5;
    return true;
  }

  /// The candidate becomes the current layout.
  void adopt(Candidate&& c, AdaptResult& res, SafeguardPoints&& sg) {
    adapted = true;
    held_from_cache = c.from_cache;
    held_warm = res.report.polish_warm_lattices > 0;
    if (path_independent()) method->hold(&res);
    res.param = *c.param;
    painter = std::move(c.painter);  // references *c.param and the candidate's mesh: keep both alive
    param = std::move(c.param);
    if (res.refined_mesh) {
      refined_moved = sg.from_samples && !sg.moved.empty();
      refined_samples = std::move(sg.moved);
      refined = res.refined_mesh;
    } else if (base_param) {
      refined.reset();  // each-stroke: an unrefined candidate lives on the input mesh
      refined_samples.clear();
      refined_moved = false;
    }
    if (opt.update == TextureUpdate::Resample) {
      resampled = true;
      base = std::move(c.texture);
      new_segment();
      composite_dirty = true;
    }
  }

  /// Path-independent mode without an accepted candidate: the initial layout, the history replayed.
  void return_to_initial() {
    method->hold(nullptr);
    held_error = held_best = -1;
    held_warm = false;
    if (!adapted) return;
    param = std::make_unique<Parameterization>(*base_param);
    held_from_cache = uses_surface_cache();
    if (held_from_cache) {
      painter = std::make_unique<Painter>(mesh, *param, painter_options(), history.background);
      texture_from_cache(*painter, mesh, nullptr);
    } else {
      painter = std::make_unique<Painter>(replay_texture(mesh, *param, history, painter_options()));
    }
    refined.reset();
    refined_samples.clear();
    refined_moved = false;
    adapted = false;
  }

  /// The candidate is rejected: the session keeps its layout (path_independent(): returns to the
  /// initial layout, what end mode keeps), the report says so.
  void keep(AdaptResult& res) {
    if (path_independent()) return_to_initial();
    AdaptReport& rep = res.report;
    rep.accepted = false;
    rep.damping = 0;
    rep.l2_after = rep.l2_before;
    rep.faces_after = current_mesh().num_faces();
    res.param = *param;
    res.refined_mesh = refined;
    res.refined_layout.reset();
    res.parent_face.clear();
  }

  const AdaptReport& record(std::unique_ptr<AdaptResult> res, std::chrono::steady_clock::time_point t_all) {
    res->report.time_total = seconds_since(t_all);
    pending = false;
    cycle_strokes = history.strokes.size();
    held_l2 = res->report.l2_after;
    reports.push_back(res->report);
    last = std::move(res);
    return reports.back();
  }

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
  std::optional<Model> model_now(const AdaptOptions& ao, bool measure) {
    if (!fixed_layout() || history.strokes.empty()) return std::nullopt;
    const auto t0 = std::chrono::steady_clock::now();
    const std::optional<GainModel> g =
        method->predict_gain(WarpInput{mesh, *base_param, base_painter->texture(), base_painter->texel_map(), &history, ao});
    if (!g) return std::nullopt;
    Model m{*g};
    const double best = g->least_error;
    const double now = measure && held_error > 0 && held_best > 0 && best > 0 ? current_error() : -1;
    const double held = now > 0 ? now : g->held_error;
    const double reachable = now > 0 ? held_error * best / held_best : best;
    m.gain_over_held_db = held > 0 && reachable > 0 ? 10 * std::log10(held / reachable) : 0.0;
    m.seconds = seconds_since(t0);
    return m;
  }

  /// The current texture's MSE against the exact history on the safeguard's samples (0 without
  /// strokes, -1 without samples).
  double current_error() {
    if (history.strokes.empty()) return 0;
    if (opt.safeguard_samples == 0) return -1;
    ensure_samples();
    const std::vector<SurfacePoint>& pts = current_samples();
    return reconstruction_mse(*param, texture(), pts, exact_signal(pts, current_mesh(), pts));
  }

  /// The report of a cycle that stopped after the error model (gain below opt.min_gain_db).
  const AdaptReport& skip(const AdaptOptions& ao, const Model& m, std::chrono::steady_clock::time_point t_all) {
    AdaptReport rep;
    rep.mode = ao.mode;
    rep.skipped = true;
    rep.accepted = false;
    rep.damping = 0;
    rep.signal_fraction = m.gain.signal_fraction;
    rep.predicted_gain_db = m.gain.predicted_gain_db;
    rep.gain_over_held_db = m.gain_over_held_db;
    rep.faces_before = rep.faces_after = current_mesh().num_faces();
    if (held_l2 < 0) held_l2 = measure_stretch(current_mesh(), *param).l2;
    rep.l2_before = rep.l2_after = held_l2;
    rep.time_density = m.seconds;
    rep.time_total = seconds_since(t_all);
    pending = true;
    reports.push_back(rep);
    return reports.back();
  }

  /// \p gated: each-stroke mode's cycle after a stroke, which may stop after the error model
  /// (opt.min_gain_db); false: re-parameterize whatever the model predicts.
  const AdaptReport& reparameterize(bool gated) {
    const auto t_all = std::chrono::steady_clock::now();
    const AdaptOptions ao = adapt_options();
    const bool decide = gated && opt.min_gain_db > 0;
    const std::optional<Model> model = model_now(ao, decide);
    if (decide && model && model->gain_over_held_db < opt.min_gain_db)
      return skip(ao, *model, t_all);
    // A cycle that throws (cancelled through the progress callback: in compute(), or replaying the
    // candidate's texture) leaves the layout as it was, and a cycle still owed: finish() runs it.
    // record() clears it.
    pending = true;
    // A cycle after a stroke starts its polish from the last cycle's (opt.warm_start); finish() and
    // reparameterize() start cold, so the session still ends on end mode's layout.
    std::unique_ptr<AdaptResult> res = compute(ao, gated && opt.warm_start && base_param);
    const TriMesh& cand_mesh = res->refined_mesh ? *res->refined_mesh : source_mesh();
    AdaptReport& rep = res->report;
    if (model) {
      rep.time_density += model->seconds;
      rep.gain_over_held_db = model->gain_over_held_db;
    }
    if (!opt.debug_dir.empty()) write_debug_maps(opt.debug_dir, "reparam" + std::to_string(reparam_count), *res);
    ++reparam_count;
    if (!rep.accepted || (rep.damping == 0 && !res->warp->moves_charts())) {
      if (path_independent()) return_to_initial();
      return record(std::move(res), t_all);
    }
    // safeguard_samples 0: no estimate, so no safeguard (with no points every error is 0, and no
    // candidate could be below the limit).
    const bool use_safeguard = opt.safeguard && opt.safeguard_samples > 0 && !history.strokes.empty();
    SafeguardPoints sg;
    if (use_safeguard) {
      const auto t0 = std::chrono::steady_clock::now();
      ensure_samples();
      sg = prepare_safeguard(*res, cand_mesh, rep);
      rep.time_safeguard += seconds_since(t0);
    }
    Candidate c = make_candidate(*res, 1.0, ao, cand_mesh);
    const bool accept = !use_safeguard || judge(c, *res, sg, ao, cand_mesh);
    if (accept)
      adopt(std::move(c), *res, std::move(sg));
    else
      keep(*res);
    // What the gate of the next cycles compares with (model_now()).
    held_error = !use_safeguard ? -1.0 : accept ? rep.error_after : rep.error_before;
    held_best = model && held_error > 0 ? model->gain.least_error : -1.0;
    return record(std::move(res), t_all);
  }
};

PaintSession::PaintSession(TriMesh mesh, Parameterization initial, const PaintSessionOptions& options,
                           const Vec3& background)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  if (initial.uv_faces.size() != mesh.faces.size())
    throw InvalidInputError("paint session: parameterization has " + std::to_string(initial.uv_faces.size()) +
                            " faces, mesh has " + std::to_string(mesh.faces.size()));
  if (options.texture_size < 1 || options.texture_size > kMaxTextureSize)
    throw InvalidInputError("paint session: texture size must be in [1, " + std::to_string(kMaxTextureSize) + "], got " +
                            std::to_string(options.texture_size));
  if (options.padding < 0) throw InvalidInputError("paint session: padding must be >= 0");
  if (options.safeguard_samples < 0 || options.safeguard_samples > kMaxSafeguardSamples)
    throw InvalidInputError("paint session: safeguard_samples must be in [0, " + std::to_string(kMaxSafeguardSamples) +
                            "], got " + std::to_string(options.safeguard_samples));
  if (!(options.surface_cache >= 0) || !std::isfinite(options.surface_cache))
    throw InvalidInputError("paint session: surface_cache must be a finite number >= 0");
  if (!(options.surface_cache_coverage >= 0) || !std::isfinite(options.surface_cache_coverage))
    throw InvalidInputError("paint session: surface_cache_coverage must be a finite number >= 0");
  if (!(options.min_gain_db >= 0) || !std::isfinite(options.min_gain_db))
    throw InvalidInputError("paint session: min_gain_db must be a finite number >= 0");
  m.mesh = std::move(mesh);
  m.opt = options;
  m.history.background = background;
  m.param = std::make_unique<Parameterization>(std::move(initial));
  m.painter = std::make_unique<Painter>(m.mesh, *m.param, m.painter_options(), background);
  m.texel_spacing = std::sqrt(surface_area(m.mesh) / std::max<size_t>(1, m.painter->texel_map().inside.size()));
  if (options.schedule == ReparamSchedule::EachStroke && options.adapt.mode != AdaptMode::None) {
    m.base_param = std::make_unique<Parameterization>(*m.param);
    m.base_painter = std::make_unique<Painter>(m.mesh, *m.base_param, m.painter_options(), background);
  }
  m.area = std::max(surface_area(m.mesh), 1e-300);
  m.method = make_adapt_method(m.adapt_options().mode);
  if (m.fixed_layout()) m.method->fix_layout(m.mesh, *m.base_param, options.texture_size, background);
  // The surface cache's size now (it is built when the history is long enough): too large, exact replay.
  m.surface_fits = m.base_param && options.update == TextureUpdate::Replay && options.surface_cache > 0 &&
                   SurfaceSignalCache::count_samples(m.mesh, m.texel_spacing / options.surface_cache) <=
                       kMaxSurfaceCacheSamples;
}

PaintSession::~PaintSession() = default;

void PaintSession::add_stroke(const Stroke& stroke) {
  Impl& m = *impl_;
  if (m.open) throw Error("paint session: add_stroke() while an interactive stroke is open");
  m.paint(stroke);
  m.record_stroke(stroke);
  if (m.opt.schedule == ReparamSchedule::EachStroke && m.opt.adapt.mode != AdaptMode::None) m.reparameterize(true);
}

void PaintSession::add_strokes(const std::vector<Stroke>& strokes) {
  Impl& m = *impl_;
  if (m.open) throw Error("paint session: add_strokes() while an interactive stroke is open");
  if (strokes.empty()) return;
  // All checked first: a bad stroke changes nothing.
  for (size_t k = 0; k < strokes.size(); ++k)
    validate_stroke(strokes[k], "paint session: add_strokes(): stroke " + std::to_string(k));
  for (const Stroke& s : strokes) {
    m.paint(s);
    m.record_stroke(s);
  }
  if (m.opt.schedule == ReparamSchedule::EachStroke && m.opt.adapt.mode != AdaptMode::None) m.reparameterize(true);
}

void PaintSession::begin_stroke(const Stroke& style) {
  Impl& m = *impl_;
  if (m.resampled) throw Error("paint session: interactive strokes are not supported in resample mode");
  m.painter->begin_stroke(style);
  if (m.base_painter) m.base_painter->begin_stroke(style);
  m.open_style = style;
  m.open_style.dabs.clear();
  m.open = true;
}

std::array<int, 4> PaintSession::add_dab(const Vec3& centre) {
  Impl& m = *impl_;
  const auto r = m.painter->add_dab(centre);
  if (m.base_painter) m.base_painter->add_dab(centre);
  m.open_dabs.push_back(centre);
  return r;
}

void PaintSession::end_stroke() {
  Impl& m = *impl_;
  m.painter->end_stroke();
  if (m.base_painter) m.base_painter->end_stroke();
  m.open = false;
  Stroke s = m.open_style;
  s.dabs = std::move(m.open_dabs);
  m.open_dabs.clear();
  if (s.dabs.empty()) return;
  m.record_stroke(std::move(s));
  if (m.opt.schedule == ReparamSchedule::EachStroke && m.opt.adapt.mode != AdaptMode::None) m.reparameterize(true);
}

void PaintSession::finish() {
  Impl& m = *impl_;
  if (m.opt.adapt.mode == AdaptMode::None) return;
  // Each-stroke mode runs the last cycle again if it was skipped, if the held texture was resampled
  // from the surface cache, or if the held layout was warm-started: cold and with exact replay, what
  // end mode computes, so the session ends on end mode's layout and texture.
  if (m.opt.schedule == ReparamSchedule::EachStroke && !m.pending && !m.held_from_cache && !m.held_warm) return;
  m.exact_only = m.opt.schedule == ReparamSchedule::EachStroke;
  struct Reset {
    bool& flag;
    ~Reset() { flag = false; }
  } reset{m.exact_only};  // also when the cycle throws (cancelled)
  m.reparameterize(false);
}

const AdaptReport& PaintSession::reparameterize() { return impl_->reparameterize(false); }
bool PaintSession::settled() const {
  const Impl& m = *impl_;
  if (m.opt.adapt.mode == AdaptMode::None || m.history.strokes.empty()) return true;
  return m.cycle_strokes == m.history.strokes.size() && !m.held_from_cache && !m.held_warm;
}
const TriMesh& PaintSession::mesh() const { return impl_->current_mesh(); }
const Parameterization& PaintSession::param() const { return *impl_->param; }
const ImageRGBA8& PaintSession::texture() { return impl_->texture(); }
const TexelMap& PaintSession::texel_map() const { return impl_->painter->texel_map(); }
const StrokeFile& PaintSession::history() const { return impl_->history; }
const std::vector<AdaptReport>& PaintSession::reports() const { return impl_->reports; }
const AdaptResult* PaintSession::last_result() const { return impl_->last.get(); }
const PaintSessionOptions& PaintSession::options() const { return impl_->opt; }
long long PaintSession::surface_cache_samples() const { return impl_->surface ? impl_->surface->num_samples() : 0; }
Painter& PaintSession::painter() { return *impl_->painter; }

double PaintSession::estimate_error() { return std::max(0.0, impl_->current_error()); }

template <>
std::span<const EnumName<ReparamSchedule>> enum_names<ReparamSchedule>() {
  static constexpr EnumName<ReparamSchedule> names[] = {{ReparamSchedule::End, "end"},
                                                        {ReparamSchedule::EachStroke, "each-stroke"},
                                                        {ReparamSchedule::EachStroke, "each_stroke", true}};
  return names;
}

}  // namespace adaptex
