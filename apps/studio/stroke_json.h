#pragma once
/// \file stroke_json.h
/// Stroke history <-> JSON in the stroke-file format (shared/docs/strokes.md), for project and
/// recovery files, which embed the history as a stroke-file object.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "adaptex/paint/strokes.h"

namespace adaptex::studio {

/// The stroke-file JSON object ("format": "adaptex.strokes", "version": 1). Decal image paths are
/// written as stored in Stroke::image_path.
nlohmann::json strokes_to_json(const StrokeFile& file);
/// Parses a stroke-file object strictly (adaptex::parse_strokes).
/// Decal images are loaded relative to \p base_dir. \throw InvalidInputError naming \p name
StrokeFile strokes_from_json(const nlohmann::json& j, const std::string& name,
                             const std::filesystem::path& base_dir);

}  // namespace adaptex::studio
