/// \file material_doc.cpp
#include "material_doc.h"

#include <algorithm>
#include <cmath>

#include "adaptex/core/errors.h"

namespace adaptex::studio {

namespace {
void check_unit(double v, const char* what) {
  if (!(v >= 0 && v <= 1)) throw InvalidInputError(std::string(what) + " must be in [0, 1]");
}

MaterialEdit make_edit(MaterialEdit::Kind kind, int layer) {
  MaterialEdit e;
  e.kind = kind;
  e.layer = layer;
  return e;
}
}  // namespace

MaterialDocument::MaterialDocument(MaterialStrokeFile file) : base_(std::move(file)) {
  base_.warnings.clear();
  if (base_.layers.empty()) base_.layers.push_back(MaterialLayer{"Layer 1", true, 1, BlendMode::Normal, {}, {}});
  file_ = base_;
  active_ = num_layers() - 1;
}

void MaterialDocument::set_active(int layer) {
  check_layer(layer, "active layer");
  active_ = layer;
}

void MaterialDocument::check_layer(int layer, const char* what) const {
  if (layer < 0 || layer >= num_layers())
    throw InvalidInputError(std::string(what) + ": no layer " + std::to_string(layer + 1) + " (the material has " +
                            std::to_string(num_layers()) + ")");
}

void MaterialDocument::apply(const MaterialEdit& e) {
  using K = MaterialEdit::Kind;
  auto& layers = file_.layers;
  switch (e.kind) {
    case K::AddLayer:
      layers.insert(layers.begin() + e.layer, MaterialLayer{e.name, true, 1, BlendMode::Normal, {}, {}});
      active_ = e.layer;
      break;
    case K::DeleteLayer:
      layers.erase(layers.begin() + e.layer);
      active_ = std::min(active_, num_layers() - 1);
      break;
    case K::MoveLayer: {
      MaterialLayer l = std::move(layers[e.layer]);
      layers.erase(layers.begin() + e.layer);
      layers.insert(layers.begin() + e.target, std::move(l));
      active_ = e.target;
      break;
    }
    case K::Visible: layers[e.layer].visible = e.flag; break;
    case K::Opacity: layers[e.layer].opacity = e.value; break;
    case K::Blend: layers[e.layer].blend = e.blend; break;
    case K::Rename: layers[e.layer].name = e.name; break;
    case K::Stroke: layers[e.layer].strokes.push_back(e.stroke); break;
    case K::AddMask: layers[e.layer].mask = LayerMask{e.value, {}}; break;
    case K::RemoveMask: layers[e.layer].mask.reset(); break;
    case K::MaskStroke: layers[e.layer].mask->strokes.push_back(e.stroke); break;
  }
}

void MaterialDocument::push(MaterialEdit e) {
  apply(e);
  log_.push_back(std::move(e));
  redo_.clear();
  ++version_;
}

void MaterialDocument::add_layer(const std::string& name) {
  MaterialEdit e = make_edit(MaterialEdit::Kind::AddLayer, active_ + 1);
  e.name = name.empty() ? next_layer_name() : name;
  push(std::move(e));
}

void MaterialDocument::delete_layer(int layer) {
  check_layer(layer, "delete layer");
  if (num_layers() == 1) throw InvalidInputError("delete layer: the material keeps at least one layer");
  MaterialEdit e = make_edit(MaterialEdit::Kind::DeleteLayer, layer);
  push(std::move(e));
}

void MaterialDocument::move_layer(int layer, int to) {
  check_layer(layer, "move layer");
  check_layer(to, "move layer to");
  if (layer == to) return;
  MaterialEdit e = make_edit(MaterialEdit::Kind::MoveLayer, layer);
  e.target = to;
  push(std::move(e));
}

void MaterialDocument::set_visible(int layer, bool visible) {
  check_layer(layer, "layer visibility");
  if (file_.layers[layer].visible == visible) return;
  MaterialEdit e = make_edit(MaterialEdit::Kind::Visible, layer);
  e.flag = visible;
  push(std::move(e));
}

void MaterialDocument::set_opacity(int layer, double opacity, bool merge) {
  check_layer(layer, "layer opacity");
  check_unit(opacity, "layer opacity");
  if (file_.layers[layer].opacity == opacity) return;
  if (merge && !log_.empty() && redo_.empty() && log_.back().kind == MaterialEdit::Kind::Opacity &&
      log_.back().layer == layer) {
    log_.back().value = opacity;
    apply(log_.back());
    ++version_;
    return;
  }
  MaterialEdit e = make_edit(MaterialEdit::Kind::Opacity, layer);
  e.value = opacity;
  push(std::move(e));
}

void MaterialDocument::set_blend(int layer, BlendMode blend) {
  check_layer(layer, "layer blend mode");
  if (file_.layers[layer].blend == blend) return;
  MaterialEdit e = make_edit(MaterialEdit::Kind::Blend, layer);
  e.blend = blend;
  push(std::move(e));
}

void MaterialDocument::rename(int layer, const std::string& name) {
  check_layer(layer, "rename layer");
  if (file_.layers[layer].name == name) return;
  MaterialEdit e = make_edit(MaterialEdit::Kind::Rename, layer);
  e.name = name;
  push(std::move(e));
}

void MaterialDocument::add_stroke(MaterialStroke stroke) {
  validate_material_stroke(stroke, false, "painted stroke");
  MaterialEdit e = make_edit(MaterialEdit::Kind::Stroke, active_);
  e.stroke = std::move(stroke);
  push(std::move(e));
}

void MaterialDocument::add_mask(int layer, double value) {
  check_layer(layer, "add mask");
  check_unit(value, "mask value");
  if (file_.layers[layer].mask) throw InvalidInputError("add mask: the layer has a mask already");
  MaterialEdit e = make_edit(MaterialEdit::Kind::AddMask, layer);
  e.value = value;
  push(std::move(e));
}

void MaterialDocument::remove_mask(int layer) {
  check_layer(layer, "remove mask");
  if (!file_.layers[layer].mask) return;
  push(make_edit(MaterialEdit::Kind::RemoveMask, layer));
}

void MaterialDocument::add_mask_stroke(MaterialStroke stroke) {
  if (!file_.layers[active_].mask)
    throw InvalidInputError("painting on the mask: \"" + file_.layers[active_].name + "\" has no mask (Add mask)");
  validate_material_stroke(stroke, true, "painted mask stroke");
  MaterialEdit e = make_edit(MaterialEdit::Kind::MaskStroke, active_);
  e.stroke = std::move(stroke);
  push(std::move(e));
}

bool MaterialDocument::undo() {
  if (log_.empty()) return false;
  redo_.push_back(std::move(log_.back()));
  log_.pop_back();
  const int active = active_;
  file_ = base_;
  for (const MaterialEdit& e : log_) apply(e);
  active_ = std::clamp(active, 0, num_layers() - 1);
  ++version_;
  return true;
}

bool MaterialDocument::redo() {
  if (redo_.empty()) return false;
  MaterialEdit e = std::move(redo_.back());
  redo_.pop_back();
  apply(e);
  log_.push_back(std::move(e));
  ++version_;
  return true;
}

size_t MaterialDocument::num_strokes() const {
  size_t n = 0;
  for (const MaterialLayer& l : file_.layers) n += l.strokes.size();
  return n;
}

std::string MaterialDocument::next_layer_name() const {
  for (int k = num_layers() + 1;; ++k) {
    const std::string name = "Layer " + std::to_string(k);
    if (std::none_of(file_.layers.begin(), file_.layers.end(), [&](const MaterialLayer& l) { return l.name == name; }))
      return name;
  }
}

}  // namespace adaptex::studio
