// PaintSession: the painting loop with signal-adaptive re-parameterization (thesis Fig. 3.1): strokes,
// the cycle (reparameterize()), the public API. By concern: layouts.cpp, surface_cache.cpp,
// safeguard.cpp (paint/eval.h's reconstruction_mse at samples carried by point_transfer.h),
// gain_gate.cpp. Report JSON and debug pictures: adapt_report.h, debug_maps.h.
#include <chrono>
#include <cmath>
#include <numbers>
#include <string>

#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "adaptex/core/timer.h"
#include "adaptex/param/stretch.h"
#include "session_impl.h"

namespace adaptex {

void PaintSession::Impl::record_stroke(Stroke s) {
  coverage += s.type == Stroke::Type::Decal ? 1.0 : s.dabs.size() * std::numbers::pi * s.radius * s.radius / area;
  history.strokes.push_back(std::move(s));
  if (uses_surface_cache()) surface_cache_now();
  if (fixed_layout()) method->update(history, adapt_options());  // O(stroke) now, not O(history) later
  if (!opt.safeguard || opt.safeguard_samples == 0) return;
  ensure_samples();
  cached_signal(samples);
}

AdaptOptions PaintSession::Impl::adapt_options() const {
  AdaptOptions ao = opt.adapt;
  if (ao.mode == AdaptMode::None) ao.mode = AdaptOptions{}.mode;  // explicit request: the default method
  // Resample mode maps old texels to new ones face by face: it keeps the mesh.
  if (opt.update == TextureUpdate::Resample) ao.refine.enabled = false;
  return ao;
}

std::unique_ptr<AdaptResult> PaintSession::Impl::compute(const AdaptOptions& ao) {
  if (base_painter)
    return std::make_unique<AdaptResult>(adapt_with(
        *method, WarpInput{mesh, *base_param, base_painter->texture(), base_painter->texel_map(), &history, ao}));
  return std::make_unique<AdaptResult>(
      adapt_with(*method, WarpInput{current_mesh(), *param, texture(), painter->texel_map(), &history, ao}));
}

const AdaptReport& PaintSession::Impl::record(std::unique_ptr<AdaptResult> res, std::chrono::steady_clock::time_point t_all) {
  res->report.time_total = seconds_since(t_all);
  pending = false;
  cycle_strokes = history.strokes.size();
  held_l2 = res->report.l2_after;
  reports.push_back(res->report);
  last = std::move(res);
  return reports.back();
}

const AdaptReport& PaintSession::Impl::reparameterize(bool gated) {
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
  std::unique_ptr<AdaptResult> res = compute(ao);
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
  // Each-stroke mode runs the last cycle again if it was skipped or if the held texture was resampled
  // from the surface cache: with exact replay, what end mode computes, so the session ends on end
  // mode's layout and texture.
  if (m.opt.schedule == ReparamSchedule::EachStroke && !m.pending && !m.held_from_cache) return;
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
  return m.cycle_strokes == m.history.strokes.size() && !m.held_from_cache;
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
