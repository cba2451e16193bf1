/// \file app_material.cpp
/// The layered material of adaptex-studio (see app.h, "the layered material").
#include <algorithm>
#include <iostream>

#include "adaptex/core/atomic_output.h"
#include "adaptex/core/errors.h"
#include "adaptex/paint/material_signal.h"
#include "app.h"
#include "brush_preset.h"

namespace adaptex::studio {

std::uint64_t App::document_version() const {
  // The history is emptied when the document becomes layered (a change of its version too).
  return history().version() + (material_ ? material_->version() : 0);
}

MaterialStrokeFile App::material_file() const {
  return material_ ? material_->file() : material_from_v1(history().to_file());
}

bool App::edit_material(const std::function<void(MaterialDocument&)>& edit) {
  if (!has_model()) {
    add_message("open a mesh first", true);
    return false;
  }
  std::optional<MaterialDocument> doc = material_;
  if (!doc) doc.emplace(material_file());
  try {
    edit(*doc);
  } catch (const std::exception& e) {
    add_message(e.what(), true);
    return false;
  }
  if (!material_) {  // the history lives on as the first layer
    if (painting_.stroke_open()) painting_.take_stroke();
    jobs_.stop_live();
    jobs_.cancel_rebuild();
    painting_.history().reset({}, history().background());
    comparison_.reset();
    view_.fixed_layout = false;
  }
  material_ = std::move(doc);
  material_changed();
  return true;
}

void App::open_material(MaterialStrokeFile file) {
  if (!has_model() || (jobs_.loading() && !pending_.reload)) {  // for the model being loaded
    pending_.material = std::move(file);
    pending_.active_layer = int(pending_.material->layers.size()) - 1;
    pending_.from_project = false;
    return;
  }
  edit_material([&](MaterialDocument& d) { d = MaterialDocument(std::move(file)); });
}

void App::material_changed() {
  ++material_generation_;
  store_.autosave_soon();
  maybe_start_material();
}

bool App::maybe_start_material() {
  if (!material_) {
    jobs_.stop_material();
    return false;
  }
  const Surface* s = painting_.surface();
  if (!s || jobs_.loading()) return true;
  // A session for this model, options and document, else a new one (a layer edit, undo, redo).
  if (!jobs_.material_serves(painting_.model().get(), session_, material_generation_))
    jobs_.start_material(painting_.model(), material_generation_, material_->file(), session_);
  return true;
}

void App::finish_material() {
  if (!material_) return;
  try {
    std::optional<RebuildResult> r = jobs_.finished_material();
    if (!r) return;
    auto phases = std::move(r->phase_ms);
    // An older generation is shown too (closer than the last one); the next composite follows.
    if (painting_.accept_material(std::move(r->surface), session_.texture_size)) last_cycle_ = std::move(phases);
  } catch (const std::exception& e) {
    add_message(e.what(), true);
    for (const MaterialExport& x : std::exchange(pending_exports_, {}))
      add_message("export to " + x.path.string() + " failed: " + e.what(), true);
  }
}

MaterialStroke App::material_brush_stroke(const Stroke& painted) const {
  MaterialStroke m;
  m.type = brush_.tool == Tool::Eraser ? MaterialStroke::Type::Erase : MaterialStroke::Type::Brush;
  m.channels = brush_.channels;
  m.value[channel_offset(Channel::BaseColor) + 0] = brush_.color.x();
  m.value[channel_offset(Channel::BaseColor) + 1] = brush_.color.y();
  m.value[channel_offset(Channel::BaseColor) + 2] = brush_.color.z();
  m.value[channel_offset(Channel::Alpha)] = 1;
  m.value[channel_offset(Channel::Roughness)] = brush_.roughness;
  m.value[channel_offset(Channel::Metallic)] = brush_.metallic;
  m.value[channel_offset(Channel::Height)] = brush_.height;
  m.radius = painted.radius;
  m.hardness = painted.hardness;
  m.opacity = brush_.opacity;
  m.dabs = painted.dabs;
  // Pressure: one per dab when the pen gave any (a mouse stroke keeps none: pressure 1).
  if (stroke_pressure_.size() == m.dabs.size() &&
      std::any_of(stroke_pressure_.begin(), stroke_pressure_.end(), [](double p) { return p != 1; }))
    m.pressure = stroke_pressure_;
  m.radius_curve = brush_.radius_curve;
  m.opacity_curve = brush_.opacity_curve;
  if (painting_mask()) {
    m.channels = 0;
    m.mask_value = brush_.mask_value;
  }
  return m;
}

void App::pick_channels(const Hit& h) {
  const Surface* surface = painting_.surface();
  if (!surface) return;
  MaterialValue v;
  try {
    v = evaluate_material(*surface->mesh, material_file(), {SurfacePoint{h.face, h.b0, h.b1}})[0];
  } catch (const std::exception& e) {
    return add_message(e.what(), true);
  }
  // The brush's checked channels (all of them when none is checked).
  const unsigned picked = brush_.channels ? brush_.channels : kAllChannels;
  if (picked & channel_bit(Channel::BaseColor)) brush_.color = Vec3(v[0], v[1], v[2]);
  if (picked & channel_bit(Channel::Roughness)) brush_.roughness = v[channel_offset(Channel::Roughness)];
  if (picked & channel_bit(Channel::Metallic)) brush_.metallic = v[channel_offset(Channel::Metallic)];
  if (picked & channel_bit(Channel::Height)) brush_.height = v[channel_offset(Channel::Height)];
}

bool App::save_brush_preset(const std::filesystem::path& path) {
  try {
    write_brush_preset(path, brush_);
  } catch (const std::exception& e) {
    add_message(e.what(), true);
    return false;
  }
  add_message("saved the brush preset " + path.string(), false);
  note_folder(path);
  return true;
}

bool App::load_brush_preset(const std::filesystem::path& path) {
  try {
    brush_ = read_brush_preset(path, brush_);
  } catch (const std::exception& e) {
    add_message(e.what(), true);
    return false;
  }
  add_message("loaded the brush preset " + path.string(), false);
  note_folder(path);
  return true;
}

bool App::painting_mask() const {
  return material_ && brush_.on_mask && material_->file().layers[material_->active()].mask.has_value();
}

bool App::fill_active(bool mask) {
  MaterialStroke m = material_brush_stroke(Stroke{});
  m.type = MaterialStroke::Type::Fill;
  m.dabs.clear();
  m.pressure.clear();
  m.radius_curve = m.opacity_curve = PressureCurve{};
  if (mask) {
    m.channels = 0;
    m.mask_value = brush_.mask_value;
    return edit_material([&](MaterialDocument& d) { d.add_mask_stroke(m); });
  }
  m.channels = brush_.channels;
  if (brush_.channels == 0) {
    add_message("the brush paints no channel: choose one in the Material window", true);
    return false;
  }
  return edit_material([&](MaterialDocument& d) { d.add_stroke(m); });
}

void App::record_stroke(Stroke s) {
  if (!material_) {
    painting_.push(std::move(s));
    store_.autosave_soon();
    return history_changed();
  }
  record_material_stroke(s.type == Stroke::Type::Decal ? material_decal_stroke(std::move(s), channel_bit(Channel::BaseColor))
                                                       : material_brush_stroke(s));
}

MaterialStroke App::material_decal_stroke(Stroke decal, unsigned channels) const {
  MaterialStroke m;
  m.type = MaterialStroke::Type::Decal;
  m.channels = channels;
  m.image_color = true;
  m.value[channel_offset(Channel::Alpha)] = 1;
  m.value[channel_offset(Channel::Roughness)] = brush_.roughness;
  m.value[channel_offset(Channel::Metallic)] = brush_.metallic;
  m.value[channel_offset(Channel::Height)] = brush_.height;
  m.opacity = decal.opacity;
  m.decal = std::move(decal);
  return m;
}

void App::record_material_stroke(MaterialStroke m) {
  stroke_pressure_.clear();
  // Appended to the active layer (or its mask): the material session composites and adapts it
  // incrementally.
  const bool mask = painting_mask() && m.type != MaterialStroke::Type::Decal;
  const int layer = material_->active();
  try {
    if (mask)
      material_->add_mask_stroke(m);
    else
      material_->add_stroke(m);
  } catch (const std::exception& e) {
    return add_message(e.what(), true);
  }
  ++material_generation_;
  store_.autosave_soon();
  if (!jobs_.feed_material(painting_.model().get(), session_, MaterialFeed{layer, mask, std::move(m), material_generation_}))
    maybe_start_material();
  else if (exporting())
    jobs_.settle_live_now();  // a waiting export: composited first, then the settle at once
}

void App::save_material_strokes(const std::filesystem::path& path) {
  try {
    AtomicOutput out;
    write_material_strokes(out.add(path), material_file());
    out.commit();
    add_message("saved the material strokes (version 2) to " + path.string(), false);
    note_folder(path);
  } catch (const std::exception& e) {
    add_message(e.what(), true);
  }
}

bool App::material_settled() const {
  const Surface* s = painting_.surface();
  return material_ && s && s->material && s->settled && s->generation == material_generation_ &&
         jobs_.material_serves(painting_.model().get(), session_, material_generation_);
}

void App::export_material(MaterialExport e) {
  e.model = painting_.model().get();
  if (material_settled()) return write_material_export(e);
  // Not settled yet: the session settles at once and finish_exports() writes the files when its
  // result is shown; the frame never waits for it. The same file asked again is written once.
  std::erase_if(pending_exports_, [&](const MaterialExport& p) { return p.glb == e.glb && p.path == e.path; });
  pending_exports_.push_back(e);
  maybe_start_material();
  jobs_.settle_live_now();
  add_message("Exporting... waiting for the final layout (" + e.path.string() + ")", false);
}

void App::write_material_export(const MaterialExport& e) {
  const Surface& s = *painting_.surface();
  try {
    if (e.glb) {
      export_material_glb(e.path, *s.mesh, *s.param, *s.material);
      add_message("exported the material (glTF metallic-roughness) to " + e.path.string(), false);
    } else {
      const std::string name = std::filesystem::path(mesh_path()).stem().string();
      export_material_obj(e.path, name.empty() ? "model" : name, *s.mesh, *s.param, *s.material);
      add_message("exported the material as OBJ+MTL+PNG (base colour, roughness, metallic, normal, height) to " +
                      e.path.string(), false);
    }
    note_folder(e.path);
  } catch (const std::exception& ex) {
    add_message(ex.what(), true);
  }
}

void App::finish_exports() {
  if (pending_exports_.empty()) return;
  if (!material_ || !has_model() ||
      std::any_of(pending_exports_.begin(), pending_exports_.end(),
                  [&](const MaterialExport& e) { return e.model != painting_.model().get(); })) {
    for (const MaterialExport& e : std::exchange(pending_exports_, {}))
      add_message("export to " + e.path.string() + " cancelled: the model was closed or reopened", true);
  } else {
    if (!material_settled()) return;
    for (const MaterialExport& e : std::exchange(pending_exports_, {})) write_material_export(e);
  }
  if (quit_after_exports_) quit_ = true;
}

}  // namespace adaptex::studio
