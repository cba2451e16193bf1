#pragma once
/// \file shrink_output.h
/// What `adaptex shrink` writes for an asset with several materials: file and material names, the
/// materials to export, and report.json's per-material section (docs/shrink.md).
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "adaptex/adapt/shrink_asset.h"
#include "adaptex/paint/export.h"

namespace adaptex::cli {

/// Output names of the materials of \p asset (parallel to asset.materials): letters, digits, '-' and
/// '_' kept, anything else '_' ("material<i>" when empty), unique without regard to case.
std::vector<std::string> output_material_names(const TexturedAsset& asset);

/// The materials of the shrunk asset: every input material (untextured ones with their factors) and
/// "default" for faces without one; every output map once, as NAME_<material>.png (base colour) or
/// NAME_<material>_<slot>.png, named after the first material that uses it.
ExportMaterials shrink_export_materials(const TexturedAsset& asset, const AssetShrinkResult& res,
                                        const std::vector<std::string>& names, const std::string& name);

/// (slot, file) of every map of every material (parallel to asset.materials) in \p set.
std::vector<std::vector<std::pair<std::string, std::string>>> material_files(const TexturedAsset& asset,
                                                                             const ExportMaterials& set);

/// report.json's "materials": per input material its faces and map files (\p files, as material_files()),
/// and for a textured one the figures of its group's shrink (size, psnr, psnr_downsized, chosen,
/// shrunk_with, and the shrink's report unless it is report.json's "shrink": one group of one material).
nlohmann::ordered_json materials_report(const TexturedAsset& asset, const AssetShrinkResult& res,
                                        const std::vector<std::string>& names,
                                        const std::vector<std::vector<std::pair<std::string, std::string>>>& files);

}  // namespace adaptex::cli
