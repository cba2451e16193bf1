/// \file surface_jobs.cpp
/// Background loads, rebuilds and comparisons (see surface_jobs.h).
#include "surface_jobs.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "settings.h"

namespace adaptex::studio {

namespace {
using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

/// The live worker's newest surface (none without a worker); its error is rethrown after \p drop().
template <class W, class F>
std::optional<RebuildResult> take_update_or_drop(std::unique_ptr<W>& worker, F drop) {
  if (!worker) return std::nullopt;
  try {
    return worker->take_update();
  } catch (...) {
    drop();
    throw;
  }
}

template <class R>
std::unique_ptr<Job<R>> take_if_ready(std::unique_ptr<Job<R>>& job) {
  if (job && job->ready()) return std::move(job);
  return nullptr;
}

/// The model's mesh and initial layout: its own atlas and texture when it has them and \p request
/// does not ask for an unwrap, else a fresh unwrap for the options' texture size.
void read_layout(Model& model, const PaintSessionOptions& options, LoadRequest request, int& size, Job<LoadResult>& job) {
  std::string why = "asked for";
  model.unwrap_asked = request.unwrap;
  std::optional<ArtistAtlas> atlas;
  if (!request.unwrap && model.path.rfind("builtin:", 0) != 0) atlas = read_artist_atlas(model.path, why);
  if (atlas) {
    if (request.size_from_texture)
      size = std::clamp(std::max(atlas->texture.width, atlas->texture.height), 16, kMaxTextureSize);
    model.mesh = std::make_shared<const TriMesh>(std::move(atlas->mesh));
    model.initial = std::make_shared<const Parameterization>(std::move(atlas->param));
    model.base = std::make_shared<const ImageRGBA8>(std::move(atlas->texture));
    model.shared_fraction = atlas->shared_fraction;
    model.layout = "artist's UV atlas";
    return;
  }
  model.mesh = std::make_shared<const TriMesh>(load_mesh(model.path));
  if (!job.progress("unwrap", 0.0)) throw CancelledError();
  model.initial = std::make_shared<const Parameterization>(
      unwrap_mesh(*model.mesh, size, options.padding,
                  [&job](std::string_view phase, double f) { return job.progress(phase, f); }));
  model.layout = model.path.rfind("builtin:", 0) == 0 ? "fresh unwrap" : "fresh unwrap (" + why + ")";
}

LoadResult load_model(const std::string& path, const PaintSessionOptions& options, const Vec3& background,
                      LoadRequest request, Job<LoadResult>& job) {
  const auto t0 = Clock::now();
  job.progress("read", 0.0);
  auto model = std::make_shared<Model>();
  model->path = path;
  int size = options.texture_size;
  read_layout(*model, options, request, size, job);
  const TriMesh& mesh = *model->mesh;
  model->box = bounding_box(mesh);
  if (!job.progress("index", 0.0)) throw CancelledError();
  model->caster = std::make_shared<RayCaster>(mesh);
  model->unwrap_size = size;
  model->unwrap_padding = options.padding;
  if (!job.progress("texture", 0.0)) throw CancelledError();
  LoadResult r;
  r.surface = std::make_unique<Surface>();
  r.surface->model = model;
  r.surface->mesh = model->mesh;
  r.surface->caster = model->caster;
  r.surface->param = model->initial;
  r.surface->base = model->base;
  r.surface->size = size;
  r.surface->canvas =
      std::make_unique<Canvas>(mesh, *model->initial, size, size, background, options.padding, model->base.get());
  r.model = std::move(model);
  r.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return r;
}

/// paint_history() from the model's initial layout, as a surface with its maps.
RebuildResult adapt_surface(const std::shared_ptr<const Model>& model, const StrokeFile& history,
                            const PaintSessionOptions& options, Job<RebuildResult>& job) {
  const auto t0 = Clock::now();
  PaintSessionOptions opt = options;
  if (history.strokes.empty()) opt.adapt.mode = AdaptMode::None;  // nothing to adapt to
  RebuildResult r = surface_from_session(
      model, paint_history(model->mesh, *model->initial, history, opt,
                           [&job](std::string_view ph, double f) { return job.progress(ph, f); }));
  r.phase_ms.emplace_back("total", ms_since(t0));
  return r;
}

/// What adapt_artist_atlas() did, in one line.
std::string atlas_note(const AtlasAdaptation& a) {
  char buf[320];
  if (!a.param) {
    std::snprintf(buf, sizeof buf,
                  "kept the artist's atlas: no new layout reconstructs the painting better (%.2f dB against "
                  "the painting at %d^2)",
                  a.psnr, a.reference_size);
  } else {
    std::snprintf(buf, sizeof buf,
                  "adapted the artist's atlas (%s): %.2f dB -> %.2f dB against the painting at %d^2; %d flipped "
                  "faces; texels shared on %.0f %% of the surface (%.0f %% before)",
                  a.chosen.c_str(), a.psnr_before, a.psnr, a.reference_size, a.flipped, 100 * a.shared_after,
                  100 * a.shared_before);
  }
  return buf;
}

/// The artist's atlas adapted to \p history (adapt_artist_atlas(), from the model's own atlas: the
/// layout is a function of the history), with the history replayed on it; the atlas itself when the
/// library keeps it or there is nothing painted.
RebuildResult adapt_atlas_surface(const std::shared_ptr<const Model>& model, const StrokeFile& history,
                                  const PaintSessionOptions& options, Job<RebuildResult>& job) {
  const auto t0 = Clock::now();
  RebuildResult r;
  r.surface = std::make_unique<Surface>();
  Surface& s = *r.surface;
  s.model = model;
  s.mesh = model->mesh;
  s.caster = model->caster;
  s.param = model->initial;
  s.base = model->base;
  const int n = options.texture_size;
  if (!history.strokes.empty()) {
    const AtlasAdaptation a =
        adapt_artist_atlas(*model->mesh, *model->initial, *model->base, history, n, options.padding,
                           [&job](std::string_view ph, double f) { return job.progress(ph, f); });
    if (a.param) {
      s.param = a.param;
      s.base = a.base;
    }
    char took[32];
    std::snprintf(took, sizeof took, " (%.1f s)", ms_since(t0) / 1000);
    r.note = atlas_note(a) + took;
    auto maps = std::make_shared<AdaptMaps>();
    maps->accepted = a.param != nullptr;
    r.maps = std::move(maps);
    r.phase_ms.emplace_back("atlas", ms_since(t0));
  }
  const auto t1 = Clock::now();
  s.canvas = std::make_unique<Canvas>(*s.mesh, *s.param, n, n, history.background, options.padding, s.base.get());
  for (size_t i = 0; i < history.strokes.size(); ++i) {
    if (!job.progress("replay", double(i) / double(history.strokes.size()))) throw CancelledError();
    s.canvas->paint_stroke(history.strokes[i]);
  }
  r.phase_ms.emplace_back("replay", ms_since(t1));
  return r;
}
/// A new surface on \p mesh (the model's or a refinement) with its shading normals (empty: the
/// renderer's) and picking (\p caster if already built, else built here for a refinement).
RebuildResult surface_on(const std::shared_ptr<const Model>& model, const std::shared_ptr<const TriMesh>& mesh,
                         std::vector<Vec3> normals, std::shared_ptr<const RayCaster> caster) {
  RebuildResult r;
  r.surface = std::make_unique<Surface>();
  Surface& s = *r.surface;
  s.model = model;
  s.mesh = mesh;
  if (!normals.empty()) s.normals = std::make_shared<const std::vector<Vec3>>(std::move(normals));
  s.caster = mesh == model->mesh ? model->caster : caster ? std::move(caster) : std::make_shared<const RayCaster>(*mesh);
  return r;
}
}  // namespace

RebuildResult surface_from_session(const std::shared_ptr<const Model>& model, SessionOutcome o,
                                   std::shared_ptr<const RayCaster> caster) {
  RebuildResult r = surface_on(model, o.mesh, std::move(o.normals), std::move(caster));
  Surface& s = *r.surface;
  // Not re-parameterized, or back on it: the model's own initial layout (the canvas painted an equal copy).
  const bool initial = !o.adapted || (o.mesh == model->mesh && o.param->uv == model->initial->uv &&
                                      o.param->uv_faces == model->initial->uv_faces);
  s.param = initial ? model->initial : o.param;
  if (initial) s.base = model->base;
  s.canvas = std::move(o.canvas);
  r.phase_ms = std::move(o.phase_ms);
  if (o.adapted) {
    auto maps = std::make_shared<AdaptMaps>();
    maps->importance = std::move(o.importance);
    maps->stretch = std::move(o.stretch);
    maps->ls2 = std::move(o.ls2);
    maps->density = std::move(o.density);
    maps->coarse = std::move(o.coarse);
    maps->fine = std::move(o.fine);
    maps->accepted = o.accepted;
    maps->damping = o.damping;
    r.maps = std::move(maps);
  }
  return r;
}

RebuildResult surface_from_material(const std::shared_ptr<const Model>& model, MaterialOutcome o,
                                    const MaterialValue& bg, int size, int padding,
                                    std::shared_ptr<const RayCaster> caster) {
  RebuildResult r = surface_on(model, o.mesh, std::move(o.normals), std::move(caster));
  Surface& s = *r.surface;
  s.param = o.adapted ? o.param : model->initial;
  s.material = o.textures;
  s.canvas = std::make_unique<Canvas>(*s.mesh, *s.param, size, size, Vec3(bg[0], bg[1], bg[2]), padding,
                                      &o.textures->base_color);
  s.size = size;
  r.phase_ms = std::move(o.phase_ms);
  return r;
}

SurfaceJobs::~SurfaceJobs() {
  compare_.reset();
  if (load_) load_->cancel();
  if (rebuild_) rebuild_->cancel();
  if (live_) live_->cancel();
  if (material_) material_->cancel();
}

void SurfaceJobs::retire(std::unique_ptr<JobBase> job) {
  job->cancel();
  retired_.push_back(std::move(job));  // never wait for it on the UI thread
}

void SurfaceJobs::reap() {
  retired_.erase(std::remove_if(retired_.begin(), retired_.end(), [](const auto& j) { return j->ready(); }),
                 retired_.end());
}

void SurfaceJobs::start_load(const std::string& path, const PaintSessionOptions& options, const Vec3& background,
                             LoadRequest request) {
  if (load_) retire(std::move(load_));
  loading_path_ = path;
  load_ = std::make_unique<Job<LoadResult>>([path, options, background, request](Job<LoadResult>& job) {
    return load_model(path, options, background, request, job);
  });
}

void SurfaceJobs::cancel_load() {
  if (load_) load_->cancel();
}

std::unique_ptr<Job<LoadResult>> SurfaceJobs::finished_load() { return take_if_ready(load_); }

void SurfaceJobs::start_rebuild(const Surface& current, std::uint64_t generation, StrokeFile history,
                                const PaintSessionOptions& options, bool adapt) {
  if (rebuild_) retire(std::move(rebuild_));
  rebuild_adapting_ = adapt;
  rebuild_generation_ = generation;
  auto model = current.model;
  auto mesh = current.mesh;
  auto caster = current.caster;
  auto normals = current.normals;
  auto param = current.param;
  auto base = current.base;
  rebuild_ = std::make_unique<Job<RebuildResult>>(
      [model, mesh, caster, normals, param, base, generation, history = std::move(history), options,
       adapt](Job<RebuildResult>& job) {
        RebuildResult r;
        if (adapt && model->base) {  // the artist's atlas: its charts and shared texels are kept
          r = adapt_atlas_surface(model, history, options, job);
        } else if (adapt) {
          r = adapt_surface(model, history, options, job);
        } else {
          r.surface = std::make_unique<Surface>();
          Surface* s = r.surface.get();
          s->model = model;
          const auto t0 = Clock::now();
          s->mesh = mesh;
          s->normals = normals;
          s->caster = caster;
          s->param = param;
          s->base = base;
          s->canvas = std::make_unique<Canvas>(*mesh, *param, options.texture_size, options.texture_size,
                                               history.background, options.padding, base.get());
          for (size_t i = 0; i < history.strokes.size(); ++i) {
            if (!job.progress("replay", double(i) / history.strokes.size())) throw CancelledError();
            s->canvas->paint_stroke(history.strokes[i]);
          }
          r.phase_ms.emplace_back("replay", ms_since(t0));
        }
        r.surface->generation = generation;
        r.surface->size = options.texture_size;
        r.surface->painted = history.strokes.size();
        return r;
      });
}

std::unique_ptr<Job<RebuildResult>> SurfaceJobs::finished_rebuild() { return take_if_ready(rebuild_); }

void SurfaceJobs::feed_live(const std::shared_ptr<const Model>& model, std::uint64_t generation,
                            const std::vector<Stroke>& strokes, const Vec3& background,
                            const PaintSessionOptions& options) {
  if (live_ && live_->serves(model.get(), generation, session_options_key(options)) && live_->fed() <= strokes.size()) {
    live_->feed({strokes.begin() + std::ptrdiff_t(live_->fed()), strokes.end()});
    return;
  }
  stop_live();
  StrokeFile history;
  history.background = background;
  history.strokes = strokes;
  live_ = std::make_unique<LiveAdaptation>(model, generation, options, std::move(history));
}

void SurfaceJobs::stop_live() {
  if (live_) retire(std::move(live_));
}

std::optional<RebuildResult> SurfaceJobs::finished_live() {
  return take_update_or_drop(live_, [this] { stop_live(); });
}

void SurfaceJobs::settle_live_now() {
  if (live_) live_->settle_now();
  if (material_) material_->settle_now();
}

void SurfaceJobs::start_material(const std::shared_ptr<const Model>& model, std::uint64_t generation,
                                 MaterialStrokeFile file, const PaintSessionOptions& options) {
  stop_material();
  material_ = std::make_unique<LiveMaterial>(model, generation, options, std::move(file));
  ++material_starts_;
}

bool SurfaceJobs::material_serves(const Model* model, const PaintSessionOptions& options,
                                  std::uint64_t generation) const {
  return material_ && material_->serves(model, session_options_key(options)) && material_->generation() == generation;
}

bool SurfaceJobs::feed_material(const Model* model, const PaintSessionOptions& options, MaterialFeed stroke) {
  if (!material_serves(model, options, stroke.generation - 1)) return false;
  material_->feed(std::move(stroke));
  return true;
}

void SurfaceJobs::stop_material() {
  if (material_) retire(std::move(material_));
}

std::optional<RebuildResult> SurfaceJobs::finished_material() {
  return take_update_or_drop(material_, [this] { stop_material(); });
}

void SurfaceJobs::start_compare(const Surface& current, StrokeFile history) {
  if (compare_) return;
  auto model = current.model;
  auto mesh = current.mesh;
  auto adaptive = current.param;
  auto tex = std::make_shared<ImageRGBA8>(current.canvas->texture());
  const int size = current.size;
  compare_ = std::make_unique<Job<Comparison>>(
      [model, mesh, adaptive, tex, history = std::move(history), size](Job<Comparison>&) {
        Comparison c;
        c.fixed_param = model->initial;
        c.adaptive_param = adaptive;
        // The initial layout's own seam padding (the adaptive canvas uses the session's, the same
        // once the layout is unwrapped for the current options).
        Canvas fixed(*model->mesh, *model->initial, size, size, history.background, model->unwrap_padding,
                     model->base.get());
        for (const Stroke& s : history.strokes) fixed.paint_stroke(s);
        c.fixed_texture = fixed.texture();
        c.adaptive_texture = *tex;
        c.psnr_fixed = texture_psnr(*model->mesh, *model->initial, c.fixed_texture, history);
        c.psnr_adaptive = texture_psnr(*mesh, *adaptive, c.adaptive_texture, history);
        c.strokes = history.strokes.size();
        return c;
      });
}

std::unique_ptr<Job<Comparison>> SurfaceJobs::finished_compare() { return take_if_ready(compare_); }

std::optional<std::pair<std::string, double>> SurfaceJobs::progress() const {
  if (load_) return std::make_pair("Loading " + loading_path_ + ": " + load_->phase(), load_->fraction());
  if (rebuild_)
    return std::make_pair((rebuild_adapting_ ? "Adapting: " : "Updating texture: ") + rebuild_->phase(),
                          rebuild_->fraction());
  if (live_)
    if (auto p = live_->progress()) return std::make_pair("Adapting: " + p->first, p->second);
  if (material_)
    if (auto p = material_->progress()) return std::make_pair("Material: " + p->first, p->second);
  return std::nullopt;
}

}  // namespace adaptex::studio
