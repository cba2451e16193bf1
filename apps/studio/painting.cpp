/// \file painting.cpp
/// Strokes, history and surface swaps (see painting.h).
#include "painting.h"

#include <algorithm>
#include <utility>

namespace adaptex::studio {

namespace {
void merge_rect(std::array<int, 4>& a, const std::array<int, 4>& b) {
  if (b[2] < b[0]) return;
  if (a[2] < a[0]) {
    a = b;
    return;
  }
  a = {std::min(a[0], b[0]), std::min(a[1], b[1]), std::max(a[2], b[2]), std::max(a[3], b[3])};
}
}  // namespace

void Painting::set_model(std::shared_ptr<const Model> model, std::unique_ptr<Surface> surface,
                         std::vector<Stroke> strokes, const Vec3& background) {
  if (stroke_open_) end_stroke();
  model_ = std::move(model);
  history_.reset(std::move(strokes), background);
  if (history_.strokes().empty()) surface->generation = history_.generation();
  swap_surface(std::move(surface));
}

void Painting::clear() {
  if (stroke_open_) end_stroke();
  history_.reset({}, history_.background());
  surface_.reset();
  model_.reset();
  ++serial_;
}

bool Painting::accept_rebuilt(std::unique_ptr<Surface> s, int texture_size) {
  if (s->generation != history_.generation() || s->model != model_ || s->size != texture_size) return false;
  // Strokes finished while the job ran, then the open stroke: painted before the swap.
  const auto& strokes = history_.strokes();
  while (s->painted < strokes.size()) s->canvas->paint_stroke(strokes[s->painted++]);
  swap_surface(std::move(s));
  return true;
}

bool Painting::accept_material(std::unique_ptr<Surface> s, int texture_size) {
  if (s->model != model_ || s->size != texture_size) return false;
  swap_surface(std::move(s));
  return true;
}

void Painting::swap_surface(std::unique_ptr<Surface> s) {
  if (stroke_open_ && surface_) {  // the open stroke continues on the new canvas
    surface_->canvas->end_stroke();
    s->canvas->begin_stroke(current_);
    for (const Vec3& d : current_.dabs) s->canvas->add_dab(d);
  }
  const bool new_param = !surface_ || surface_->param != s->param;
  surface_ = std::move(s);
  ++serial_;
  texture_full_upload_ = true;
  if (new_param) mesh_upload_ = true;
}

void Painting::catch_up() {
  if (!surface_ || stroke_open_ || stale(surface_->size)) return;
  const auto& strokes = history_.strokes();
  while (surface_->painted < strokes.size()) {
    surface_->canvas->paint_stroke(strokes[surface_->painted++]);
    texture_full_upload_ = true;
  }
}

bool Painting::stale(int texture_size) const {
  return surface_ && (surface_->generation != history_.generation() || surface_->size != texture_size);
}

bool Painting::in_sync() const {
  return !surface_ ||
         (surface_->generation == history_.generation() && surface_->painted == history_.strokes().size());
}

bool Painting::on_initial_layout() const { return !surface_ || surface_->param == model_->initial; }

void Painting::begin_stroke(const Stroke& style) {
  current_ = style;
  current_.dabs.clear();
  stroke_open_ = true;
  last_dab_.reset();
  surface_->canvas->begin_stroke(current_);
}

void Painting::add_dab(const Hit& h, const Ray& ray, int symmetry_axis) {
  merge_rect(dirty_, surface_->canvas->add_dab(h.point));
  current_.dabs.push_back(h.point);
  last_dab_ = h.point;
  if (symmetry_axis >= 0) {
    if (auto mh = mirror_hit(ray, h, symmetry_axis)) {
      merge_rect(dirty_, surface_->canvas->add_dab(mh->point));
      current_.dabs.push_back(mh->point);
    }
  }
}

bool Painting::end_stroke() {
  if (!stroke_open_) return false;
  surface_->canvas->end_stroke();
  stroke_open_ = false;
  if (current_.dabs.empty()) return false;
  const bool in_sync_before = in_sync();
  history_.push(std::move(current_));
  current_ = Stroke();
  if (in_sync_before) surface_->painted = history_.strokes().size();
  return true;
}

Stroke Painting::take_stroke() {
  if (!stroke_open_) return Stroke();
  surface_->canvas->end_stroke();
  stroke_open_ = false;
  return std::exchange(current_, Stroke());
}

bool Painting::undo() { return !stroke_open_ && history_.undo(); }
bool Painting::redo() { return !stroke_open_ && history_.redo(); }

std::optional<Hit> Painting::pick(const Ray& ray) const {
  if (!surface_) return std::nullopt;
  auto h = surface_->caster->intersect(ray);
  if (!h || !h->front_facing) return std::nullopt;
  return h;
}

std::optional<Hit> Painting::mirror_hit(const Ray& ray, const Hit& h, int axis) const {
  if (!surface_) return std::nullopt;
  const double c = 0.5 * (model_->box.min[axis] + model_->box.max[axis]);
  Ray m = ray;
  m.origin[axis] = 2 * c - m.origin[axis];
  m.dir[axis] = -m.dir[axis];
  auto mh = surface_->caster->intersect(m);
  if (!mh || !mh->front_facing || (mh->point - h.point).norm() <= 1e-9 * (1 + model_->box.diagonal()))
    return std::nullopt;
  return mh;
}

Vec3 Painting::sample_colour(const Hit& h) const {
  if (!surface_) return history_.background();
  const Parameterization& p = *surface_->param;
  const Face& uf = p.uv_faces[h.face];
  const Vec2 uv = h.b0 * p.uv[uf[0]] + h.b1 * p.uv[uf[1]] + (1 - h.b0 - h.b1) * p.uv[uf[2]];
  return sample_bilinear(surface_->canvas->texture(), uv.x(), uv.y());
}

void Painting::upload(Renderer& renderer) {
  if (!surface_) return;
  if (mesh_upload_) {
    renderer.set_mesh(*surface_->mesh, *surface_->param, surface_->normals.get());
    mesh_upload_ = false;
  }
  if (texture_full_upload_) {
    renderer.set_texture(surface_->canvas->texture());
    if (const MaterialTextures* m = surface_->material.get())
      renderer.set_material_maps(m->metallic_roughness, m->normal);
    else
      renderer.set_material_maps({}, {});
    texture_full_upload_ = false;
    dirty_ = {0, 0, -1, -1};
  } else if (dirty_[2] >= dirty_[0]) {
    renderer.update_texture(surface_->canvas->texture(), dirty_);
    dirty_ = {0, 0, -1, -1};
  }
}

}  // namespace adaptex::studio
