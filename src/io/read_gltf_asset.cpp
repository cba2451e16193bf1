/// \file read_gltf_asset.cpp
/// read_textured_asset() for glTF / GLB.
#include "adaptex/core/errors.h"
#include "gltf_asset.h"

namespace adaptex::io_detail {

TexturedAsset read_gltf_asset(const std::string&, const std::filesystem::path& name, const AssetReadOptions&,
                              ReadReport&) {
  throw InvalidInputError(name.string() + ": textured glTF/GLB is not read yet (OBJ + MTL is)");
}

}  // namespace adaptex::io_detail
