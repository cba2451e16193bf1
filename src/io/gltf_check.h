#pragma once
/// \file gltf_check.h
/// Internal to the io area: the glTF checks of read_gltf.cpp that read_gltf_asset.cpp shares (the
/// checked JSON document, buffer bytes), and the textured soup of a glTF. Not installed.
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "mesh_soup.h"

namespace adaptex::io_detail {

using json = nlohmann::json;

/// A glTF whose container, buffers, views, accessors and references check_gltf() accepted.
struct CheckedGltf {
  json doc;                        ///< The glTF JSON.
  bool glb = false;                ///< Binary container.
  std::uint64_t bin_offset = 0;    ///< The GLB BIN chunk's bytes in the file (length 0: none).
  std::uint64_t bin_length = 0;
};

/// Rejects anything that is not glTF 2.0 whose sizes all agree with the bytes that exist (see
/// read_gltf.cpp). \throw IoError naming \p name
CheckedGltf check_gltf(const std::string& name, const std::filesystem::path& base_dir, const std::string& bytes);

/// Standard base64 (RFC 4648) of \p text from \p from on; stops at the first character outside the alphabet.
std::string decode_base64(const std::string& text, std::size_t from);

/// The bytes of buffer \p b that has a `uri` (check_buffers() accepted it): a data: URI, or a file in \p dir.
std::string uri_buffer_bytes(const json& b, const std::filesystem::path& dir);

/// The soup of read_gltf_soup() with TEXCOORD_0 per corner (identical UV values share one index) and
/// the glTF material index of each corner's primitive (-1 without one). A primitive without
/// TEXCOORD_0 whose material has no map gets UV (0, 0) (TexturedSoup::untextured_polygons).
/// \throw IoError as read_gltf_soup(); InvalidInputError a primitive without TEXCOORD_0 whose material has maps
TexturedSoup read_gltf_textured_soup(const std::string& bytes, const SoupSource& source, const CheckedGltf& checked);

}  // namespace adaptex::io_detail
