#pragma once
/// \file brush_preset.h
/// Brush presets of adaptex-studio: a small JSON file holding what a brush paints with (docs/studio.md,
/// "Brush presets"): {"format": "adaptex.brush-preset", "version": 1, "brush": {"channels": {...},
/// "radius_px" | "radius", "hardness", "opacity", "spacing", "mask_value", "pressure": {...}}}.
/// Reading is strict: one error line naming the file and the field; nothing of a bad file is used.
#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "settings.h"

namespace adaptex::studio {

/// \p brush as a preset file's text (its tool, symmetry and on-mask switch are not part of a preset).
std::string brush_preset_json(const BrushSettings& brush);
/// Writes \p brush to \p path atomically. \throw OutputError cannot write
void write_brush_preset(const std::filesystem::path& path, const BrushSettings& brush);
/// \p base with the preset's fields from \p text (fields a preset leaves out keep \p base's values).
/// \p name is used in messages.
/// \throw IoError not JSON; InvalidInputError wrong format or version, an unknown field, a value of the
/// wrong type or out of range (the stroke contract's rules, validate_material_stroke())
BrushSettings parse_brush_preset(const std::string& text, const std::string& name, const BrushSettings& base);
/// Reads \p path (parse_brush_preset). \throw IoError unreadable; as parse_brush_preset
BrushSettings read_brush_preset(const std::filesystem::path& path, const BrushSettings& base);

/// The brush's pressure curves as a "pressure" object ({"radius": [[p, f], ...], "opacity": [...]}; {}
/// for none), as presets and projects write them.
nlohmann::json pressure_curves_to_json(const BrushSettings& brush);
/// Reads a "pressure" object into \p brush's curves (a curve left out: none). \p where prefixes the
/// messages (e.g. "p.json: brush: "). \throw InvalidInputError wrong shape or type, or a curve
/// breaking the stroke contract's rules (from pressure 0 to 1, increasing, factors in [0,1])
void pressure_curves_from_json(const nlohmann::json& pressure, const std::string& where, BrushSettings& brush);

}  // namespace adaptex::studio
