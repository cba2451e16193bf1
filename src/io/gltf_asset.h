#pragma once
/// \file gltf_asset.h
/// Internal to the io area: the pieces of read_textured_asset() shared by its OBJ and glTF readers
/// (asset_io.cpp, read_gltf_asset.cpp). Not installed.
#include <filesystem>
#include <string>
#include <vector>

#include "adaptex/io/asset_io.h"

namespace adaptex::io_detail {

/// read_textured_asset() of a .gltf / .glb held in memory.
TexturedAsset read_gltf_asset(const std::string& bytes, const std::filesystem::path& name,
                              const AssetReadOptions& options, ReadReport& report);

/// Finds every map file of \p materials (as written, with '\' as '/', or by its file name next to the
/// material file), and decodes them when options.load_images. \p not_images are the asset's own files.
/// \throw IoError a map missing or naming one of \p not_images; InvalidInputError a UDIM token
void load_material_maps(std::vector<Material>& materials, const std::vector<std::filesystem::path>& not_images,
                        const AssetReadOptions& options, std::vector<std::string>& warnings);

/// The asset from a textured mesh: atlas counts, UDIM check and chart wrapping (wrap_uv_charts()),
/// with a warning line per kind of change in \p report.
TexturedAsset finish_asset(TexturedMesh tm, std::vector<int> face_material, std::vector<Material> materials,
                           const std::string& name, const AssetReadOptions& options, ReadReport& report);

}  // namespace adaptex::io_detail
