/// \file backend.cpp
/// The studio's bridge to the adaptex library (see backend.h).
#include "backend.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <fstream>
#include <functional>
#include <future>

#include <nlohmann/json.hpp>

#include "adaptex/adapt/material_adapt.h"
#include "adaptex/adapt/material_session.h"
#include "adaptex/adapt/report_json.h"
#include "adaptex/adapt/session.h"
#include "adaptex/adapt/shrink.h"
#include "adaptex/core/atomic_output.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "adaptex/core/shapes.h"
#include "adaptex/io/asset_io.h"
#include "adaptex/io/image_io.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/paint/eval.h"
#include "adaptex/paint/export.h"
#include "adaptex/paint/painter.h"
#include "adaptex/paint/tangent_frame.h"
#include "adaptex/paint/texel_map.h"
#include "adaptex/param/unwrap.h"

namespace adaptex::studio {

TriMesh load_mesh(const std::string& path) {
  if (path.rfind("builtin:", 0) == 0) {
    const std::string name = path.substr(8);
    if (name == "sphere") return shapes::sphere(64, 32, 1.0);
    if (name == "icosphere") return shapes::icosphere(4, 1.0);
    if (name == "torus") return shapes::torus(96, 48);
    if (name == "trefoil") return shapes::trefoil_knot();
    if (name == "plane") return shapes::plane(32, 2.0);
    throw InvalidInputError(path + ": unknown built-in shape (sphere, icosphere, torus, trefoil, plane)");
  }
  return read_mesh(path);
}

Parameterization unwrap_mesh(const TriMesh& mesh, int texture_size, int padding, const ProgressCallback& progress) {
  UnwrapOptions opt;
  opt.progress = progress;
  return unwrap(mesh, unwrap_options_for_texture(texture_size, padding, std::move(opt))).param;
}

struct Canvas::Impl {
  std::unique_ptr<PaintSession> session;
  std::unique_ptr<Painter> own;
  Painter* painter = nullptr;
};

Canvas::Canvas(const TriMesh& mesh, const Parameterization& param, int width, int height, const Vec3& background,
               int padding, const ImageRGBA8* base)
    : impl_(std::make_unique<Impl>()) {
  impl_->own = std::make_unique<Painter>(mesh, param, PainterOptions{width, height, padding}, background);
  impl_->painter = impl_->own.get();
  if (!base || base->width <= 0 || base->height <= 0) return;
  const TexelMap& map = impl_->own->texel_map();
  std::vector<Vec3f> colours(map.inside.size());
  for (size_t k = 0; k < colours.size(); ++k) {
    const int t = map.inside[k];
    colours[k] = sample_bilinear(*base, ((t % width) + 0.5) / width, ((t / width) + 0.5) / height).cast<float>();
  }
  impl_->own->fill_colours(colours);
}

std::optional<ArtistAtlas> read_artist_atlas(const std::string& path, std::string& why) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext != ".obj" && ext != ".gltf" && ext != ".glb") {
    why = "no UV atlas in " + (ext.empty() ? std::string("this file") : ext + " files");
    return std::nullopt;
  }
  TexturedAsset asset;
  try {
    asset = read_textured_asset(path);
  } catch (const Error& e) {
    why = e.what();
    return std::nullopt;
  }
  // One base-colour image for the whole atlas (the studio paints one texture).
  const TextureMap* map = nullptr;
  for (const Material& m : asset.materials) {
    const TextureMap* t = m.find(MapSlot::BaseColor);
    if (!t || t->image.width <= 0) continue;
    if (map && t->path != map->path) {
      why = "its materials use several base-colour textures (" + map->path.filename().string() + ", " +
            t->path.filename().string() + ")";
      return std::nullopt;
    }
    map = t;
  }
  if (!map) {
    why = "it has no base-colour texture";
    return std::nullopt;
  }
  ArtistAtlas a;
  a.texture = map->image;
  a.texture_path = map->path.string();
  a.mesh = std::move(asset.mesh);
  a.param = std::move(asset.param);
  a.shared_fraction = asset.uv.shared_fraction;
  a.mirrored_charts = asset.uv.mirrored_charts;
  a.degenerate_uv_faces = asset.uv.degenerate_uv_faces;
  a.straddling_charts = asset.uv.straddling_charts;
  return a;
}
AtlasAdaptation adapt_artist_atlas(const TriMesh& mesh, const Parameterization& atlas, const ImageRGBA8& base,
                                   const StrokeFile& history, int size, int padding, const ProgressCallback& progress) {
  // The reference: the painting on the atlas at twice the size, so that the strokes' detail finer
  // than the atlas's texels counts (at the same size the atlas would reproduce itself exactly).
  const int ref = std::min(2 * size, kMaxTextureSize);
  Canvas reference(mesh, atlas, ref, ref, history.background, 2 * padding, &base);
  for (size_t i = 0; i < history.strokes.size(); ++i) {
    report_progress(progress, "reference", double(i) / double(history.strokes.size()));
    reference.paint_stroke(history.strokes[i]);
  }
  std::vector<ShrinkMap> maps(2);
  maps[0].slot = "painted";
  maps[0].image = reference.texture();
  maps[1].slot = "baseColor";
  maps[1].image = base;
  ShrinkOptions opt;
  opt.size = size;
  opt.progress = progress;
  ShrinkResult r = shrink_textured_mesh(mesh, atlas, maps, opt);
  AtlasAdaptation a;
  a.chosen = r.chosen;
  a.psnr = r.psnr;
  a.psnr_before = r.psnr_downsized;
  a.reference_size = ref;
  a.flipped = r.after.flipped;
  a.shared_before = r.before.shared_surface;
  a.shared_after = r.after.shared_surface;
  if (r.chosen == "downsized" || r.chosen == "artist") return a;  // the atlas is kept as it is
  a.param = std::make_shared<const Parameterization>(std::move(r.param));
  a.base = std::make_shared<const ImageRGBA8>(std::move(r.maps[1]));
  return a;
}

Canvas::Canvas(std::unique_ptr<PaintSession> session) : impl_(std::make_unique<Impl>()) {
  impl_->session = std::move(session);
  impl_->painter = &impl_->session->painter();
}
Canvas::Canvas(const TriMesh& mesh, const Parameterization& param, const Painter& source)
    : impl_(std::make_unique<Impl>()) {
  impl_->own = std::make_unique<Painter>(source, mesh, param);
  impl_->painter = impl_->own.get();
}
Canvas::~Canvas() = default;
void Canvas::paint_stroke(const Stroke& s) { impl_->painter->paint_stroke(s); }
void Canvas::begin_stroke(const Stroke& s) { impl_->painter->begin_stroke(s); }
std::array<int, 4> Canvas::add_dab(const Vec3& c) { return impl_->painter->add_dab(c); }
void Canvas::end_stroke() { impl_->painter->end_stroke(); }
const ImageRGBA8& Canvas::texture() { return impl_->painter->texture(); }

namespace {
/// The input's smooth normals at the vertices of its refinement (parent_face: input face of every
/// refined face), interpolated with the vertex's barycentric coordinates in that face.
std::vector<Vec3> refined_normals(const TriMesh& input, const TriMesh& refined, const FaceData<int>& parent_face) {
  const std::vector<Vec3> vn = vertex_normals(input);
  std::vector<Vec3> out(refined.positions.size(), Vec3::Zero());
  std::vector<char> done(refined.positions.size(), 0);
  for (size_t c = 0; c < refined.faces.size(); ++c) {
    const Face& P = input.faces[size_t(parent_face[c])];
    const Vec3 a = input.positions[P[0]], e1 = input.positions[P[1]] - a, e2 = input.positions[P[2]] - a;
    const double a11 = e1.dot(e1), a12 = e1.dot(e2), a22 = e2.dot(e2), det = a11 * a22 - a12 * a12;
    for (int v : refined.faces[c]) {
      if (done[size_t(v)]) continue;
      done[size_t(v)] = 1;
      const Vec3 d = refined.positions[size_t(v)] - a;
      const double l1 = det > 0 ? (a22 * e1.dot(d) - a12 * e2.dot(d)) / det : 0.0;
      const double l2 = det > 0 ? (a11 * e2.dot(d) - a12 * e1.dot(d)) / det : 0.0;
      const Vec3 n = (1 - l1 - l2) * vn[P[0]] + l1 * vn[P[1]] + l2 * vn[P[2]];
      out[size_t(v)] = n.norm() > 0 ? n.normalized() : n;
    }
  }
  return out;
}

/// The phases of the report's "time_ms" (report_json.h) that took time, in the pipeline's order.
std::vector<std::pair<std::string, double>> phase_times(const AdaptReport& rep) {
  std::vector<std::pair<std::string, double>> out;
  const nlohmann::ordered_json report = adapt_report_json(rep);
  for (const auto& [name, ms] : report.at("time_ms").items())
    if (name != "total" && ms.get<double>() > 0) out.emplace_back(name, ms.get<double>());
  return out;
}
}  // namespace

namespace {
/// Everything of \p o but the canvas, from \p session (on \p mesh or its refinement).
void describe_session(const std::shared_ptr<const TriMesh>& mesh, PaintSession& session, SessionOutcome& o) {
  o.mesh = session.mesh().num_faces() == mesh->num_faces() ? mesh : std::make_shared<const TriMesh>(session.mesh());
  o.param = std::make_shared<const Parameterization>(session.param());
  if (!session.reports().empty()) {
    // The last cycle that was not skipped (a skipped one changed nothing and timed only the gate).
    const auto& reps = session.reports();
    auto it = std::find_if(reps.rbegin(), reps.rend(), [](const AdaptReport& r) { return !r.skipped; });
    const AdaptReport& rep = it != reps.rend() ? *it : reps.back();
    o.adapted = true;
    o.accepted = rep.accepted;
    o.damping = rep.damping;
    o.phase_ms = phase_times(reps.back());
  }
  if (const AdaptResult* r = session.last_result()) {
    o.importance = r->importance;
    o.stretch = r->stretch;
    o.ls2 = r->ls2;
    o.density = r->density;
    if (o.mesh != mesh && r->parent_face.size() == o.mesh->faces.size())
      o.normals = refined_normals(*mesh, *o.mesh, r->parent_face);
    const std::vector<GridWarp>& grids = r->warp ? r->warp->lattices() : std::vector<GridWarp>{};
    if (grids.size() == 2) o.coarse = grids[0];
    if (!grids.empty()) o.fine = grids.back();
  }
}
}  // namespace

SessionOutcome paint_history(const std::shared_ptr<const TriMesh>& mesh, const Parameterization& initial,
                             const StrokeFile& history, const PaintSessionOptions& options,
                             const ProgressCallback& progress) {
  PaintSessionOptions opt = options;
  opt.schedule = ReparamSchedule::End;  // one re-parameterization from the initial layout
  opt.update = TextureUpdate::Replay;   // the canvas keeps painting interactively afterwards
  opt.adapt.progress = progress;
  auto session = std::make_unique<PaintSession>(*mesh, initial, opt, history.background);
  for (size_t i = 0; i < history.strokes.size(); ++i) {
    report_progress(progress, "paint", double(i) / double(history.strokes.size()));
    session->add_stroke(history.strokes[i]);
  }
  session->finish();
  SessionOutcome o;
  describe_session(mesh, *session, o);
  o.canvas = std::make_unique<Canvas>(std::move(session));
  return o;
}

struct LiveSession::Impl {
  std::shared_ptr<const TriMesh> mesh;
  PaintSession session;
  // What the last snapshot() showed: its layout, and whether its texture was end mode's.
  std::vector<Vec2> shown_uv;
  int shown_faces = 0;
  bool shown_settled = true;
  Impl(std::shared_ptr<const TriMesh> m, const Parameterization& initial, const PaintSessionOptions& o, const Vec3& bg)
      : mesh(std::move(m)), session(*mesh, initial, o, bg), shown_uv(initial.uv),
        shown_faces(mesh->num_faces()) {}
};

LiveSession::LiveSession(std::shared_ptr<const TriMesh> mesh, const Parameterization& initial,
                         const PaintSessionOptions& options, const Vec3& background, const ProgressCallback& progress) {
  PaintSessionOptions opt = options;
  opt.schedule = ReparamSchedule::EachStroke;
  opt.update = TextureUpdate::Replay;
  opt.adapt.progress = progress;
  impl_ = std::make_unique<Impl>(std::move(mesh), initial, opt, background);
}
LiveSession::~LiveSession() = default;
void LiveSession::add(const std::vector<Stroke>& strokes) { impl_->session.add_strokes(strokes); }
void LiveSession::settle() { impl_->session.finish(); }
bool LiveSession::settled() const { return impl_->session.settled(); }
size_t LiveSession::strokes() const { return impl_->session.history().strokes.size(); }

bool LiveSession::changed() const {
  const Impl& m = *impl_;
  const bool settled = m.session.settled();
  return m.session.mesh().num_faces() != m.shown_faces || m.session.param().uv != m.shown_uv ||
         (settled && !m.shown_settled);
}

SessionOutcome LiveSession::snapshot(const std::function<void(const TriMesh&)>& alongside) {
  Impl& m = *impl_;
  SessionOutcome o;
  describe_session(m.mesh, m.session, o);
  std::future<void> side;
  if (alongside) side = std::async(std::launch::async, alongside, std::cref(*o.mesh));
  try {
    o.canvas = std::make_unique<Canvas>(*o.mesh, *o.param, m.session.painter());
  } catch (...) {
    if (side.valid()) side.wait();
    throw;
  }
  if (side.valid()) side.get();
  m.shown_uv = o.param->uv;
  m.shown_faces = o.mesh->num_faces();
  m.shown_settled = m.session.settled();
  return o;
}

double texture_psnr(const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& texture,
                    const StrokeFile& history, long long samples) {
  EvalOptions opt;
  opt.samples = samples;
  return evaluate_texture(mesh, param, texture, history, opt).psnr;
}

StrokeFile load_strokes(const std::filesystem::path& path) { return read_strokes(path); }
AnyStrokeFile load_any_strokes(const std::filesystem::path& path) { return read_any_strokes(path); }

void save_strokes(const std::filesystem::path& path, const StrokeFile& file) {
  AtomicOutput out;
  write_strokes(out.add(path), file);
  out.commit();
}

void export_obj(const std::filesystem::path& dir, const std::string& name, const TriMesh& mesh,
                const Parameterization& param, const ImageRGBA8& texture) {
  AtomicOutput out;
  ExportOptions opt;
  opt.glb = false;
  export_textured_mesh(out, dir, sanitize_export_name(name), mesh, param, texture, opt);
  out.commit();
}

namespace {
void write_glb_bytes(const std::filesystem::path& path, const std::vector<unsigned char>& bytes) {
  AtomicOutput out;
  const auto tmp = out.add(path);
  {
    std::ofstream o(tmp, std::ios::binary);
    o.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    if (!o) throw OutputError(path.string() + ": write failed");
  }
  out.commit();
}
}  // namespace

MaterialOutcome paint_material_history(const std::shared_ptr<const TriMesh>& mesh, const Parameterization& initial,
                                       const MaterialStrokeFile& file, const PaintSessionOptions& options,
                                       const ProgressCallback& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  MaterialAdaptOptions mo;
  mo.paint.size = options.texture_size;
  mo.paint.padding = options.padding;
  mo.adapt = options.adapt;
  if (mo.adapt.mode != AdaptMode::DensityFlow) mo.adapt.mode = AdaptMode::None;
  mo.adapt.progress = progress;
  MaterialAdaptResult r = adapt_material(*mesh, initial, file, mo);
  MaterialOutcome o;
  o.adapted = r.adapted;
  const bool same_mesh = r.mesh.faces == mesh->faces && r.mesh.positions == mesh->positions;
  o.mesh = same_mesh ? mesh : std::make_shared<const TriMesh>(std::move(r.mesh));
  if (!same_mesh && r.parent_face.size() == o.mesh->faces.size())
    o.normals = refined_normals(*mesh, *o.mesh, r.parent_face);
  o.param = std::make_shared<const Parameterization>(std::move(r.param));
  o.textures = std::make_shared<const MaterialTextures>(std::move(r.textures));
  o.phase_ms.emplace_back("material",
                          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  return o;
}

struct MaterialLiveSession::Impl {
  std::shared_ptr<const TriMesh> mesh;
  MaterialPaintSession session;
  MaterialOutcome shown;  // the layout of the last snapshot (textures not kept)
  Impl(std::shared_ptr<const TriMesh> m, const Parameterization& initial, MaterialStrokeFile f,
       const MaterialSessionOptions& o)
      : mesh(std::move(m)), session(*mesh, initial, std::move(f), o) {}
};

MaterialLiveSession::MaterialLiveSession(std::shared_ptr<const TriMesh> mesh, const Parameterization& initial,
                                         MaterialStrokeFile file, const PaintSessionOptions& options,
                                         const ProgressCallback& progress) {
  MaterialSessionOptions mo;
  mo.paint.size = options.texture_size;
  mo.paint.padding = options.padding;
  mo.adapt = options.adapt;
  if (mo.adapt.mode != AdaptMode::DensityFlow) mo.adapt.mode = AdaptMode::None;  // as paint_material_history()
  mo.adapt.progress = progress;
  impl_ = std::make_unique<Impl>(std::move(mesh), initial, std::move(file), mo);
}
MaterialLiveSession::~MaterialLiveSession() = default;
void MaterialLiveSession::add(int layer, const std::vector<MaterialStroke>& strokes, bool mask) {
  if (!mask) return impl_->session.add_strokes(layer, strokes);
  for (const MaterialStroke& s : strokes) impl_->session.add_stroke(layer, s, true);
}
const MaterialStrokeFile& MaterialLiveSession::history() const { return impl_->session.history(); }

MaterialOutcome MaterialLiveSession::snapshot() {
  Impl& m = *impl_;
  const auto t0 = std::chrono::steady_clock::now();
  MaterialPaintSession& s = m.session;
  MaterialOutcome o;
  o.adapted = s.adapted();
  if (m.shown.param && s.mesh().num_faces() == m.shown.mesh->num_faces() && s.param().uv == m.shown.param->uv &&
      s.param().uv_faces == m.shown.param->uv_faces) {
    o.mesh = m.shown.mesh;
    o.param = m.shown.param;
    o.normals = m.shown.normals;
  } else {
    const bool refined = !s.parent_face().empty();
    o.mesh = refined ? std::make_shared<const TriMesh>(s.mesh()) : m.mesh;
    o.param = std::make_shared<const Parameterization>(s.param());
    if (refined) o.normals = refined_normals(*m.mesh, *o.mesh, s.parent_face());
    m.shown.mesh = o.mesh;
    m.shown.param = o.param;
    m.shown.normals = o.normals;
  }
  o.textures = std::make_shared<const MaterialTextures>(s.textures());
  if (!s.reports().empty()) o.phase_ms = phase_times(s.reports().back());
  o.phase_ms.emplace_back("snapshot",
                          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  return o;
}

void export_material_obj(const std::filesystem::path& dir, const std::string& name, const TriMesh& mesh,
                         const Parameterization& param, const MaterialTextures& textures) {
  AtomicOutput out;
  export_material_textures(out, dir, name, mesh, param, textures, true, false);
  out.commit();
}

void export_material_glb(const std::filesystem::path& path, const TriMesh& mesh, const Parameterization& param,
                         const MaterialTextures& textures) {
  write_glb_bytes(path, encode_glb(mesh, param, textures.base_color, material_export_options(textures, true)));
}

void export_glb(const std::filesystem::path& path, const TriMesh& mesh, const Parameterization& param,
                const ImageRGBA8& texture) {
  // An artist's atlas may keep charts across the border of [0,1]^2 (as OBJ renderers repeat the
  // texture): the sampler then repeats too, so the file reads back and looks as the model did.
  ExportOptions opt;
  if (std::any_of(param.uv.begin(), param.uv.end(), [](const Vec2& t) { return t.minCoeff() < 0 || t.maxCoeff() > 1; }))
    opt.wrap = TextureAddress::Repeat;
  write_glb_bytes(path, encode_glb(mesh, param, texture, opt));
}

void save_png(const std::filesystem::path& path, const ImageRGBA8& img) {
  AtomicOutput out;
  write_png(out.add(path), img);
  out.commit();
}

ImageRGBA8 load_image(const std::filesystem::path& path) { return read_image(path); }

}  // namespace adaptex::studio
