/// \file brush_panel.cpp
#include "brush_panel.h"

#include <imgui.h>

#include <array>
#include <cstdio>
#include <string>

namespace adaptex::studio {

void tooltip(const char* text) {
  if (!ImGui::IsItemHovered()) return;
  ImGui::BeginTooltip();
  ImGui::PushTextWrapPos(ImGui::GetFontSize() * 28);
  ImGui::TextUnformatted(text);
  ImGui::PopTextWrapPos();
  ImGui::EndTooltip();
}

void mask_panel(App& app, const TraceWidget& trace) {
  const MaterialDocument* doc = app.material();
  const int active = doc ? doc->active() : 0;
  const bool has_mask = doc && doc->file().layers[size_t(active)].mask.has_value();
  BrushSettings& b = app.brush();
  if (!has_mask) {
    if (ImGui::Button("Add mask")) app.edit_material([active](MaterialDocument& d) { d.add_mask(active, 1); });
    tooltip("Give the active layer a mask: white (1) shows the layer, black (0) hides it. It starts white.");
    trace("Add mask");
  } else {
    if (ImGui::Button("Remove mask")) app.edit_material([active](MaterialDocument& d) { d.remove_mask(active); });
    tooltip("Remove the active layer's mask with its strokes (undo brings it back).");
    trace("Remove mask");
    ImGui::SameLine();
    ImGui::Text("mask strokes: %zu", doc->file().layers[size_t(active)].mask->strokes.size());
  }
  ImGui::BeginDisabled(!has_mask);
  ImGui::Checkbox("Paint on the mask", &b.on_mask);
  tooltip("Brush and eraser strokes paint the active layer's mask with the value below (the eraser paints "
          "the mask's start value back) instead of the layer's channels.");
  trace("Paint on the mask");
  float v = float(b.mask_value);
  if (ImGui::SliderFloat("Mask value", &v, 0.f, 1.f, "%.2f")) b.mask_value = v;
  tooltip("What the mask brush and Fill mask paint: 0 hides the layer, 1 shows it.");
  trace("Mask value");
  ImGui::EndDisabled();
  if (ImGui::Button("Fill layer")) app.fill_active(false);
  tooltip("Fill the whole active layer with the brush's channels and values at the brush's opacity.");
  trace("Fill layer");
  ImGui::SameLine();
  ImGui::BeginDisabled(!has_mask);
  if (ImGui::Button("Fill mask")) app.fill_active(true);
  tooltip("Fill the whole mask with the mask value at the brush's opacity.");
  trace("Fill mask");
  ImGui::EndDisabled();
  if (has_mask && b.on_mask) ImGui::TextColored(ImVec4(0.5f, 0.8f, 1, 1), "The brush paints the mask");
}

namespace {

/// One curve: on/off and the factors at pressure 0, 0.5 and 1, with a plot of f(p).
void curve_editor(const char* label, PressureCurve& curve, const TraceWidget& trace) {
  ImGui::PushID(label);
  bool on = !curve.points.empty();
  if (ImGui::Checkbox(label, &on)) curve.points = on ? std::vector<Vec2>{{0, 0.2}, {0.5, 0.6}, {1, 1}} : std::vector<Vec2>{};
  tooltip("Pen pressure scales this: the factor at pressure 0, 0.5 and 1 (straight lines between). Off: "
          "the pressure does not change it. A mouse paints at pressure 1.");
  trace(label);
  if (on && curve.points.size() == 3) {
    for (int k = 0; k < 3; ++k) {
      float f = float(curve.points[size_t(k)].y());
      const std::string id = std::string("##p") + std::to_string(k);
      ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x / float(3 - k) - 4);
      if (ImGui::SliderFloat(id.c_str(), &f, 0.f, 1.f, k == 0 ? "p0: %.2f" : k == 1 ? "p.5: %.2f" : "p1: %.2f"))
        curve.points[size_t(k)].y() = f;
      if (k < 2) ImGui::SameLine();
    }
    std::array<float, 32> samples{};
    for (size_t k = 0; k < samples.size(); ++k) samples[k] = float(curve(double(k) / double(samples.size() - 1)));
    ImGui::PlotLines("##curve", samples.data(), int(samples.size()), 0, nullptr, 0.f, 1.f,
                     ImVec2(ImGui::GetContentRegionAvail().x, ImGui::GetFontSize() * 2));
  }
  ImGui::PopID();
}

}  // namespace

void pressure_panel(BrushSettings& brush, const TraceWidget& trace) {
  curve_editor("Pressure -> radius", brush.radius_curve, trace);
  curve_editor("Pressure -> opacity", brush.opacity_curve, trace);
}

void stamp_option(App& app, const TraceWidget& trace) {
  ImGui::BeginDisabled(!app.decal_image());
  ImGui::Checkbox("Stamp the decal image", &app.brush().stamp);
  ImGui::EndDisabled();
  tooltip("An alpha stamp: a click places the loaded decal image (Load decal; its alpha is the stamp's "
          "shape) centred at the cursor, as tall as the brush's diameter, at the brush's opacity: a decal "
          "stroke on the active layer that paints the brush's checked channels, base colour from the image's "
          "colours, roughness, metallic and height at the brush's values (an engraving into height, a worn "
          "patch into roughness).");
  trace("Stamp the decal image");
}

void preset_panel(App& app, std::string& path, const TraceWidget& trace,
                  const std::function<void(FileKind)>& choose) {
  if (path.empty()) path = (app.last_folder() / "brush.json").string();
  char buf[1024];
  std::snprintf(buf, sizeof buf, "%s", path.c_str());
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x);
  if (ImGui::InputText("##preset", buf, sizeof buf)) path = buf;
  tooltip("The brush preset file (JSON: channels and values, radius, hardness, opacity, spacing, mask value, "
          "pressure curves).");
  trace("Preset path");
  if (ImGui::Button("Save preset")) app.save_brush_preset(path);
  trace("Save preset");
  ImGui::SameLine();
  if (ImGui::Button("Load preset")) app.load_brush_preset(path);
  trace("Load preset");
  if (ImGui::Button("Open preset...")) choose(FileKind::LoadBrushPreset);
  tooltip("Choose a brush preset file to load.");
  trace("Open preset");
  ImGui::SameLine();
  if (ImGui::Button("Save preset as...")) choose(FileKind::SaveBrushPreset);
  tooltip("Choose where to save the brush as a preset.");
  trace("Save preset as");
}

}  // namespace adaptex::studio
