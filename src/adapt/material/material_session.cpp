/// \file material_session.cpp
/// MaterialPaintSession (material_session.h): strokes into per-layer point caches, and the cycle:
/// the summed error model from the caches, the gain gate, the warp, the candidate layout's textures (from
/// the surface cache, or the history replayed), the never-worse check on cached exact values.
#include "adaptex/adapt/material_session.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>

#include "adaptex/adapt/error_density.h"
#include "adaptex/adapt/method.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "adaptex/core/timer.h"
#include "adaptex/paint/material_eval.h"
#include "adaptex/paint/material_point_cache.h"
#include "adaptex/paint/material_surface_cache.h"
#include "adaptex/paint/padding.h"
#include "adaptex/paint/point_transfer.h"

namespace adaptex {

namespace {

/// A layout with its mesh, texel map and the history's material at its chart texels.
struct Layout {
  std::shared_ptr<const TriMesh> mesh;
  Parameterization param;
  FaceData<int> parent_face;  // refined mesh: input face of every face; empty: the input mesh
  TexelMap map;
  std::optional<HeightNormalTerms> terms;      // of mesh and param: the normal map's and the check's frames
  std::unique_ptr<MaterialPointCache> texels;  // exact values at the texels (unused when from_cache)
  bool from_cache = false;    // the textures are interpolated from the session's surface cache
  std::vector<MaterialValue> interpolated;  // from_cache: the chart texels' material (storage reused)
  MaterialTextures textures;
  long long painted = -1;     // texels->strokes() (or the surface cache's) when `textures` were made
  ImageF density;             // the model's density that made it (empty: the initial layout)
  // The initial layout's textures are updated where strokes changed them: the material they show,
  // the heights and normals of the chart texels (W*H), and the padding.
  std::vector<MaterialValue> last;
  std::vector<char> recomputed;  // per chart texel: its value recomputed by the cache since the last update
  std::vector<double> height;
  std::vector<Vec3f> normals;
  std::vector<char> mark;
  SeamPadding pad;
};

/// The error planes' exact values (material_error_planes()) at every texel of a texel map (W*H), with
/// the exact height (world units) and its normals, kept between cycles and updated where the material
/// changed.
struct ExactPlanes {
  std::array<std::vector<Vec3f>, 3> planes;  // base colour; roughness, metallic, alpha; (normal + 1) / 2
  std::vector<double> height;
  std::vector<Vec3f> normals;
  std::vector<char> changed;  // per chart texel (map.inside order)
  std::vector<char> mark;     // W*H
};

}  // namespace

struct MaterialPaintSession::Impl {
  MaterialSessionOptions opt;
  MaterialStrokeFile history;
  double height_scale = 0;
  Layout initial;
  std::unique_ptr<Layout> held;   // the adapted layout held, or null: the initial
  std::unique_ptr<Layout> spare;  // a former candidate, whose storage the next one reuses
  std::optional<ErrorPlaneMaps> plane_maps;
  std::unique_ptr<MaterialPointCache> reference, half;  // the model's exact values, at plane_maps' points
  ErrorPlanesMemory plane_memory;  // the model's rasters and cell sums of the last cycle
  ExactPlanes reference_planes, half_planes;  // the planes' exact values at plane_maps' texels
  MaterialEvalPoints check_points;
  std::unique_ptr<MaterialPointCache> check;            // the exact material at check_points.probes
  // The never-worse check of the initial layout, its samples' terms recomputed only where the exact
  // values (check_changed, per probe) or the initial textures (initial_changed, W*H) changed since.
  MaterialErrorTracker initial_check;
  std::vector<char> check_changed, initial_changed;
  std::vector<AdaptReport> reports;
  // The adaptation's method, kept between cycles as a version 1 session's (its buffers then keep their
  // pages); made at the first cycle.
  std::unique_ptr<AdaptMethod> method;
  // The surface cache (material_surface_cache.h): built once the history covers the surface
  // opt.surface_cache_coverage times, if its lattice has at most kMaxMaterialSurfaceCacheSamples.
  std::unique_ptr<MaterialSurfaceCache> surface;
  bool surface_fits = false;
  double texel_spacing = 0;   // sqrt(surface area / chart texels) of the initial layout
  double area = 1;            // of the input mesh
  double coverage = 0;        // Σ over brush and erase dabs of π r² / area (a fill or decal: 1)

  void add_coverage(const MaterialStroke& s) {
    const bool dabs = s.type == MaterialStroke::Type::Brush || s.type == MaterialStroke::Type::Erase;
    coverage += dabs ? s.dabs.size() * std::numbers::pi * s.radius * s.radius / area : 1.0;
  }
  bool uses_surface_cache() const { return surface_fits && coverage >= opt.surface_cache_coverage; }
  MaterialSurfaceCache& surface_now() {
    if (!surface)
      surface = std::make_unique<MaterialSurfaceCache>(*initial.mesh, texel_spacing / opt.surface_cache, history,
                                                       kMaxMaterialSurfaceCacheSamples);
    surface->update(history);
    return *surface;
  }

  MaterialEvalOptions eval_options() const {
    MaterialEvalOptions eo;
    eo.samples = opt.check_samples;
    eo.seed = opt.check_seed;
    eo.data_weight = opt.data_weight;
    return eo;
  }

  Layout& current() { return held ? *held : initial; }
  const Layout& current() const { return held ? *held : initial; }

  /// \p l's texel map and its material source: the surface cache when \p from_cache, else the
  /// history replayed onto its texels.
  void make_layout(Layout& l, bool from_cache = false) {
    const int N = opt.paint.size;
    l.map = build_texel_map(*l.mesh, l.param, N, N);
    l.terms = height_normal_terms(*l.mesh, l.param);
    l.from_cache = from_cache;
    if (from_cache)
      l.painted = -1;
    else if (l.texels)
      l.texels->reset(*l.mesh, texel_points(l.map), history);
    else
      l.texels = std::make_unique<MaterialPointCache>(*l.mesh, texel_points(l.map), history);
    l.painted = -1;
  }

  /// The initial layout's per-face terms of the height's normals (made with its texel map).
  const HeightNormalTerms& initial_normal_terms() const { return *initial.terms; }

  /// The textures of \p l with the whole history: made anew for a new layout, then (the initial
  /// layout) updated where the composite changed.
  const MaterialTextures& textures_of(Layout& l) {
    if (l.from_cache) return cached_textures_of(l);
    l.texels->update(history);
    if (l.painted == l.texels->strokes()) return l.textures;
    const bool incremental = l.painted >= 0 && !l.last.empty();
    if (incremental) l.recomputed.resize(l.last.size(), 0);
    const std::vector<MaterialValue>& v =
        incremental ? l.texels->values(history, [&l](size_t k, const MaterialValue&) { l.recomputed[k] = 1; })
                    : l.texels->values(history);
    if (incremental) {
      update_textures(l, v);
    } else {
      material_textures_from_values(*l.mesh, l.param, l.map, v, history.background, opt.paint.padding, height_scale,
                                    l.textures, painted_channels(history), &*l.terms);
      if (&l == &initial) {  // kept for the updates
        initial_check.reset();
        initial_changed.assign(static_cast<size_t>(l.map.width) * l.map.height, 0);
        l.last = v;
        l.pad = build_seam_padding(l.map, opt.paint.padding);
        l.height.assign(static_cast<size_t>(l.map.width) * l.map.height, 0.0);
        for (size_t k = 0; k < v.size(); ++k) l.height[l.map.inside[k]] = (v[k][6] - 0.5) * height_scale;
        l.normals.assign(l.height.size(), Vec3f(0, 0, 1));
        update_height_normals(*l.mesh, l.param, *l.terms, l.map, l.height, l.map.inside, l.normals);
        l.mark.assign(l.height.size(), 0);
      }
    }
    l.painted = l.texels->strokes();
    return l.textures;
  }

  /// The textures of a layout of the surface cache, interpolated anew when strokes came since.
  const MaterialTextures& cached_textures_of(Layout& l) {
    MaterialSurfaceCache& c = surface_now();
    if (l.painted == c.strokes()) return l.textures;
    std::vector<MaterialValue>& v = l.interpolated;
    c.texel_values(history, l.map, *l.mesh, l.parent_face.empty() ? nullptr : &l.parent_face, v);
    material_textures_from_values(*l.mesh, l.param, l.map, v, history.background, opt.paint.padding, height_scale,
                                  l.textures, kAllChannels, &*l.terms);
    l.painted = c.strokes();
    return l.textures;
  }

  /// The texels of the initial layout \p l whose material changed since the last textures (among those
  /// its cache recomputed), their channels, and the normals of them and their 4-neighbours (the
  /// height's differences read the neighbours); then the padding.
  void update_textures(Layout& l, const std::vector<MaterialValue>& v) {
    const TexelMap& map = l.map;
    std::vector<int> changed;
    for (size_t k = 0; k < v.size(); ++k)
      if (l.recomputed[k]) {
        l.recomputed[k] = 0;
        if (v[k] != l.last[k]) changed.push_back(static_cast<int>(k));
      }
    std::vector<int> around;
    const int W = map.width, H = map.height;
    for (int k : changed) {
      const int t = map.inside[k];
      set_material_texel(l.textures, t, v[k]);
      initial_changed[t] = 1;
      l.height[t] = (v[k][6] - 0.5) * height_scale;
      l.last[k] = v[k];
      const int i = t % W, j = t / W;
      for (const auto& [di, dj] : {std::pair{0, 0}, {-1, 0}, {1, 0}, {0, -1}, {0, 1}}) {
        if (i + di < 0 || i + di >= W || j + dj < 0 || j + dj >= H) continue;
        const int u = t + di + dj * W;
        if (map.face[u] >= 0 && !l.mark[u]) l.mark[u] = 1, around.push_back(u);
      }
    }
    update_height_normals(*l.mesh, l.param, initial_normal_terms(), map, l.height, around, l.normals);
    for (int u : around) set_normal_texel(l.textures.normal, u, l.normals[u]), l.mark[u] = 0, initial_changed[u] = 1;
    for (int u : l.pad.padded)
      if (initial_changed[l.pad.source[u]]) initial_changed[u] = 1;
    for (ImageRGBA8* img : {&l.textures.base_color, &l.textures.roughness, &l.textures.metallic, &l.textures.height,
                            &l.textures.metallic_roughness, &l.textures.normal})
      apply_seam_padding(*img, l.pad);
  }

  /// The caches of the model and the check, built on first use, brought up to date.
  void update_caches() {
    const int N = opt.paint.size;
    if (!plane_maps) {
      plane_maps = error_plane_maps(*initial.mesh, initial.param, N, opt.adapt.density_flow.density);
      reference = std::make_unique<MaterialPointCache>(*initial.mesh, texel_points(plane_maps->reference), history);
      half = std::make_unique<MaterialPointCache>(*initial.mesh, texel_points(plane_maps->half), history);
      check_points = material_eval_points(*initial.mesh, true, eval_options());
      check = std::make_unique<MaterialPointCache>(*initial.mesh, check_points.probes, history);
      check_changed.assign(check_points.probes.size(), 0);
    }
    for (MaterialPointCache* c : {reference.get(), half.get(), check.get()}) c->update(history);
    refresh_planes(plane_maps->reference, *reference, reference_planes);
    refresh_planes(plane_maps->half, *half, half_planes);
    if (uses_surface_cache()) surface_now();
  }

  /// \p n brought up to the material of \p cache (at \p map's chart texels): all of it at first, then
  /// the texels that changed, and the normals of the heights that changed and of their 4-neighbours
  /// (as update_textures()).
  void refresh_planes(const TexelMap& map, MaterialPointCache& cache, ExactPlanes& n) {
    const TriMesh& mesh = *initial.mesh;
    if (n.normals.empty()) {
      const std::vector<MaterialValue>& v = cache.values(history);
      const size_t texels = static_cast<size_t>(map.width) * map.height;
      n.height.assign(texels, 0.0);
      for (int p : {0, 1}) n.planes[p].assign(texels, Vec3f::Zero());
      for (size_t k = 0; k < v.size(); ++k) set_texel(n, map.inside[k], v[k]);
      n.normals.assign(texels, Vec3f(0, 0, 1));
      update_height_normals(mesh, initial.param, initial_normal_terms(), map, n.height, map.inside, n.normals);
      n.planes[2].resize(texels);
      for (size_t t = 0; t < texels; ++t) n.planes[2][t] = normal_plane_value(n.normals[t]);
      n.changed.assign(v.size(), 0);
      n.mark.assign(texels, 0);
      return;
    }
    const std::vector<MaterialValue>& v = cache.values(history, [&n](size_t k, const MaterialValue&) { n.changed[k] = 1; });
    const int W = map.width, H = map.height;
    std::vector<int> around;
    for (size_t k = 0; k < v.size(); ++k) {
      if (!n.changed[k]) continue;
      n.changed[k] = 0;
      const int t = map.inside[k];
      const double h = n.height[t];
      set_texel(n, t, v[k]);
      if (h == n.height[t]) continue;
      const int i = t % W, j = t / W;
      for (const auto& [di, dj] : {std::pair{0, 0}, {-1, 0}, {1, 0}, {0, -1}, {0, 1}}) {
        if (i + di < 0 || i + di >= W || j + dj < 0 || j + dj >= H) continue;
        const int u = t + di + dj * W;
        if (map.face[u] >= 0 && !n.mark[u]) n.mark[u] = 1, around.push_back(u);
      }
    }
    update_height_normals(mesh, initial.param, initial_normal_terms(), map, n.height, around, n.normals);
    for (int u : around) n.planes[2][u] = normal_plane_value(n.normals[u]), n.mark[u] = 0;
  }

  /// Texel \p t's base colour, data channels and height from its material \p v.
  void set_texel(ExactPlanes& n, int t, const MaterialValue& v) const {
    n.planes[0][t] = material_plane_value(0, v);
    n.planes[1][t] = material_plane_value(1, v);
    n.height[t] = (v[6] - 0.5) * height_scale;
  }

  /// The source of the planes' exact values: those kept at the reference and N/2 maps.
  MaterialPlaneSource exact_planes() {
    return [this](int plane, const TexelMap& at) -> const std::vector<Vec3f>& {
      if (&at == &plane_maps->reference) return reference_planes.planes[plane];
      if (&at == &plane_maps->half) return half_planes.planes[plane];
      throw Error("material session: the model asked for another texel map");
    };
  }

  /// The exact material at the check's probes, the probes recomputed since flagged in check_changed.
  const std::vector<MaterialValue>& check_values() {
    return check->values(history, [this](size_t k, const MaterialValue&) { check_changed[k] = 1; });
  }

  MaterialError judge(const Layout& l, const MaterialTextures& tex) {
    const std::vector<MaterialValue>& exact = check_values();
    if (&l == &initial) {
      const MaterialError e = initial_check.evaluate(*l.mesh, l.param, tex, check_points, exact, check_changed,
                                                     initial_changed, eval_options());
      std::fill(check_changed.begin(), check_changed.end(), char(0));
      std::fill(initial_changed.begin(), initial_changed.end(), char(0));
      return e;
    }
    MaterialEvalPoints pts;
    const MaterialEvalPoints* use = &check_points;
    if (!l.parent_face.empty()) {  // the same 3-D points on the refined mesh: the same exact values
      pts.samples = transfer_points(check_points.samples, *initial.mesh, *l.mesh, l.parent_face);
      pts.directions = check_points.directions;
      pts.per_sample = check_points.per_sample;
      pts.step = check_points.step;
      use = &pts;
    }
    return evaluate_material_textures(*l.mesh, l.param, tex, *use, exact, eval_options(), &*l.terms);
  }

  const AdaptReport& cycle(bool gated);
  const AdaptReport& skip(AdaptReport rep, std::chrono::steady_clock::time_point t0);
};

const AdaptReport& MaterialPaintSession::Impl::skip(AdaptReport rep, std::chrono::steady_clock::time_point t0) {
  rep.skipped = true;
  rep.accepted = false;
  rep.damping = 0;
  rep.faces_before = rep.faces_after = current().mesh->num_faces();
  rep.time_total = seconds_since(t0);
  reports.push_back(rep);
  return reports.back();
}

const AdaptReport& MaterialPaintSession::Impl::cycle(bool gated) {
  const auto t_all = std::chrono::steady_clock::now();
  auto t0 = t_all;
  update_caches();
  const MaterialTextures& base = textures_of(initial);
  const ErrorDensity model = compute_error_density(
      *initial.mesh, initial.param, initial.map,
      material_error_planes(initial.map, base, exact_planes(), opt.data_weight),
      *plane_maps, plane_memory, opt.adapt.density_flow.density);
  AdaptReport gate;
  gate.mode = opt.adapt.mode;
  gate.signal_fraction = model.signal_fraction;
  gate.predicted_gain_db = model.predicted_gain_db;
  const double least = predicted_error(model, model.density);
  const double at_held = held ? (held->density.data.empty() ? -1.0 : predicted_error(model, held->density))
                              : predicted_error(model, ImageF{});
  gate.gain_over_held_db = at_held > 0 && least > 0 ? 10 * std::log10(at_held / least) : 0.0;
  gate.time_density = seconds_since(t0);
  if (gated && opt.min_gain_db > 0 && at_held >= 0 && gate.gain_over_held_db < opt.min_gain_db) return skip(gate, t_all);

  if (!method) method = make_adapt_method(opt.adapt.mode);
  const WarpInput in{*initial.mesh, initial.param, base.base_color, initial.map, nullptr, opt.adapt, &model};
  AdaptResult res = adapt_with(*method, in);
  AdaptReport& rep = res.report;
  rep.time_density += gate.time_density;
  rep.gain_over_held_db = gate.gain_over_held_db;
  std::unique_ptr<Layout> cand = spare ? std::move(spare) : std::make_unique<Layout>();
  cand->mesh = res.refined_mesh ? res.refined_mesh : initial.mesh;
  cand->param = res.param;
  cand->parent_face = res.refined_mesh ? res.parent_face : FaceData<int>{};
  cand->density = res.report.damping == 1 ? res.density : ImageF{};
  bool accept = rep.accepted;
  if (accept) {
    t0 = std::chrono::steady_clock::now();
    make_layout(*cand, uses_surface_cache());  // from the surface cache, or the history replayed
    textures_of(*cand);
    rep.time_texture_update = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    rep.error_before = judge(initial, base).weighted;
    rep.error_after = judge(*cand, cand->textures).weighted;
    rep.time_safeguard = seconds_since(t0);
    accept = rep.error_after < rep.error_before * (1 - opt.check_margin);
  }
  if (accept) {
    spare = std::move(held);
    held = std::move(cand);
  } else {
    if (held) spare = std::move(held);
    else spare = std::move(cand);
    rep.accepted = false;
    rep.damping = 0;
    rep.faces_after = initial.mesh->num_faces();
  }
  rep.time_total = seconds_since(t_all);
  reports.push_back(rep);
  return reports.back();
}

MaterialPaintSession::MaterialPaintSession(TriMesh mesh, Parameterization initial, MaterialStrokeFile file,
                                           const MaterialSessionOptions& options)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  const AdaptMode mode = options.adapt.mode;
  if (mode != AdaptMode::None && mode != AdaptMode::DensityFlow)
    throw InvalidInputError(std::string("material session: layered materials adapt with density-flow or none (got ") +
                            to_string(mode) + ")");
  if (initial.uv_faces.size() != mesh.faces.size())
    throw InvalidInputError("material session: the layout and the mesh have different face counts");
  if (options.paint.size < 1 || options.paint.size > kMaxTextureSize || options.paint.padding < 0)
    throw InvalidInputError("material session: texture size must be in [1, " + std::to_string(kMaxTextureSize) +
                            "] and padding >= 0");
  if (options.check_samples < 1 || options.check_samples > 10'000'000)
    throw InvalidInputError("material session: check_samples must be in [1, 10000000]");
  if (!(options.surface_cache >= 0) || !std::isfinite(options.surface_cache) ||
      !(options.surface_cache_coverage >= 0) || !std::isfinite(options.surface_cache_coverage))
    throw InvalidInputError("material session: surface_cache and surface_cache_coverage must be finite numbers >= 0");
  if (!(options.check_margin >= 0 && options.check_margin < 1) || !(options.min_gain_db >= 0) ||
      !std::isfinite(options.min_gain_db) || !(options.data_weight >= 0) || !std::isfinite(options.data_weight))
    throw InvalidInputError("material session: check_margin must be in [0, 1), min_gain_db and data_weight >= 0");
  m.opt = options;
  m.history = std::move(file);
  m.initial.mesh = std::make_shared<const TriMesh>(std::move(mesh));
  m.initial.param = std::move(initial);
  m.height_scale = material_height_scale(*m.initial.mesh, m.history);
  m.make_layout(m.initial);
  const TriMesh& input = *m.initial.mesh;
  m.area = std::max(surface_area(input), 1e-300);
  m.texel_spacing = std::sqrt(m.area / std::max<size_t>(1, m.initial.map.inside.size()));
  m.surface_fits = options.surface_cache > 0 &&
                   MaterialSurfaceCache::count_samples(input, m.texel_spacing / options.surface_cache) <=
                       kMaxMaterialSurfaceCacheSamples;
  for (const MaterialLayer& l : m.history.layers) {
    for (const MaterialStroke& s : l.strokes) m.add_coverage(s);
    if (l.mask)
      for (const MaterialStroke& s : l.mask->strokes) m.add_coverage(s);
  }
}

MaterialPaintSession::~MaterialPaintSession() = default;

void MaterialPaintSession::add_strokes(int layer, const std::vector<MaterialStroke>& strokes) {
  Impl& m = *impl_;
  if (layer < 0 || layer >= static_cast<int>(m.history.layers.size()))
    throw InvalidInputError("material session: layer " + std::to_string(layer) + " of " +
                            std::to_string(m.history.layers.size()));
  for (size_t k = 0; k < strokes.size(); ++k)
    validate_material_stroke(strokes[k], false,
                             "material session: layer " + std::to_string(layer) + ", stroke " + std::to_string(k));
  if (strokes.empty()) return;
  for (const MaterialStroke& s : strokes) m.history.layers[layer].strokes.push_back(s), m.add_coverage(s);
  if (m.opt.adapt.mode != AdaptMode::None) m.cycle(true);
}

void MaterialPaintSession::add_stroke(int layer, const MaterialStroke& stroke, bool to_mask) {
  Impl& m = *impl_;
  if (!to_mask) return add_strokes(layer, {stroke});
  if (layer < 0 || layer >= static_cast<int>(m.history.layers.size()) || !m.history.layers[layer].mask)
    throw InvalidInputError("material session: layer " + std::to_string(layer) + " has no mask");
  validate_material_stroke(stroke, true, "material session: mask of layer " + std::to_string(layer));
  m.history.layers[layer].mask->strokes.push_back(stroke);
  m.add_coverage(stroke);
  if (m.opt.adapt.mode != AdaptMode::None) m.cycle(true);
}

const AdaptReport& MaterialPaintSession::reparameterize() {
  if (impl_->opt.adapt.mode == AdaptMode::None)
    throw InvalidInputError("material session: reparameterize() with adaptation mode none");
  return impl_->cycle(false);
}

const TriMesh& MaterialPaintSession::mesh() const { return *impl_->current().mesh; }
const Parameterization& MaterialPaintSession::param() const { return impl_->current().param; }
const FaceData<int>& MaterialPaintSession::parent_face() const { return impl_->current().parent_face; }
const MaterialTextures& MaterialPaintSession::textures() { return impl_->textures_of(impl_->current()); }
const MaterialStrokeFile& MaterialPaintSession::history() const { return impl_->history; }
const std::vector<AdaptReport>& MaterialPaintSession::reports() const { return impl_->reports; }
bool MaterialPaintSession::adapted() const { return impl_->held != nullptr; }
long long MaterialPaintSession::surface_cache_samples() const {
  return impl_->surface ? impl_->surface->num_samples() : 0;
}
bool MaterialPaintSession::held_from_cache() const { return impl_->current().from_cache; }

MaterialError MaterialPaintSession::held_error() {
  Impl& m = *impl_;
  m.update_caches();
  return m.judge(m.current(), m.textures_of(m.current()));
}

MaterialError MaterialPaintSession::initial_error() {
  Impl& m = *impl_;
  m.update_caches();
  return m.judge(m.initial, m.textures_of(m.initial));
}

}  // namespace adaptex
