/// \file read_gltf_asset.cpp
/// read_textured_asset() for glTF / GLB: the mesh and TEXCOORD_0 through the checked assimp path of
/// read_gltf.cpp, the materials straight from the checked JSON (glTF 2.0 spec, 3.9): baseColor,
/// metallicRoughness, normal, occlusion and emissive textures with their factors. Images are read from
/// the GLB's BIN chunk or a buffer (bufferView), a data: URI, or a file next to the glTF, and decoded
/// by read_image_from_memory() (PNG, JPEG, TGA: KTX2 and WebP images are rejected by name).
#include <algorithm>
#include <map>

#include "adaptex/core/errors.h"
#include "adaptex/io/image_io.h"
#include "gltf_asset.h"
#include "gltf_check.h"

namespace adaptex::io_detail {

namespace {

namespace fs = std::filesystem;

constexpr std::uint64_t kRepeat = 10497;  // glTF sampler wrap modes (OpenGL enums)

/// "%20" and the other percent escapes of a relative URI, decoded.
std::string percent_decoded(const std::string& uri) {
  std::string out;
  for (std::size_t k = 0; k < uri.size(); ++k) {
    const auto hex = [](char c) { return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1; };
    if (uri[k] == '%' && k + 2 < uri.size() && hex(uri[k + 1]) >= 0 && hex(uri[k + 2]) >= 0) {
      out.push_back(static_cast<char>(hex(uri[k + 1]) * 16 + hex(uri[k + 2])));
      k += 2;
    } else {
      out.push_back(uri[k]);
    }
  }
  return out;
}

double number_or(const json& obj, const char* key, double fallback) {
  const auto it = obj.find(key);
  return it != obj.end() && it->is_number() ? it->get<double>() : fallback;
}

/// Reads the materials and their images of one checked glTF.
class GltfMaterials {
 public:
  GltfMaterials(const CheckedGltf& gltf, const std::string& bytes, const fs::path& name, const AssetReadOptions& options,
                ReadReport& report)
      : gltf_(gltf), doc_(gltf.doc), bytes_(bytes), name_(name.string()), dir_(name.parent_path()), options_(options),
        report_(report) {}

  std::vector<Material> read() {
    std::vector<Material> out;
    const auto it = doc_.find("materials");
    if (it == doc_.end()) return out;
    if (!it->is_array()) throw IoError(name_ + ": corrupt glTF: 'materials' is not an array");
    for (std::size_t m = 0; m < it->size(); ++m) out.push_back(material((*it)[m], m));
    return out;
  }

  /// The first map whose sampler wraps other than REPEAT (then charts outside [0,1] cannot be moved), or "".
  const std::string& non_repeat_map() const { return non_repeat_map_; }

 private:
  [[noreturn]] void corrupt(const std::string& what) const { throw IoError(name_ + ": corrupt glTF: " + what); }

  Material material(const json& m, std::size_t index) {
    if (!m.is_object()) corrupt("material " + std::to_string(index) + " is not an object");
    Material out;
    out.name = m.contains("name") && m["name"].is_string() ? m["name"].get<std::string>() : "material" + std::to_string(index);
    const std::string where = name_ + ": material " + std::to_string(index) + " '" + out.name + "'";
    if (const auto pbr = m.find("pbrMetallicRoughness"); pbr != m.end() && pbr->is_object()) {
      if (const auto f = pbr->find("baseColorFactor"); f != pbr->end() && f->is_array() && f->size() == 4)
        for (int c = 0; c < 4; ++c) out.base_color[c] = (*f)[c].is_number() ? (*f)[c].get<double>() : 1.0;
      out.metallic = number_or(*pbr, "metallicFactor", 1.0);
      out.roughness = number_or(*pbr, "roughnessFactor", 1.0);
      add_map(out, *pbr, "baseColorTexture", MapSlot::BaseColor, where);
      add_map(out, *pbr, "metallicRoughnessTexture", MapSlot::MetallicRoughness, where);
    }
    if (const auto f = m.find("emissiveFactor"); f != m.end() && f->is_array() && f->size() == 3)
      for (int c = 0; c < 3; ++c) out.emissive[c] = (*f)[c].is_number() ? (*f)[c].get<double>() : 0.0;
    add_map(out, m, "normalTexture", MapSlot::Normal, where);
    add_map(out, m, "occlusionTexture", MapSlot::Occlusion, where);
    add_map(out, m, "emissiveTexture", MapSlot::Emissive, where);
    return out;
  }

  void add_map(Material& material, const json& owner, const char* key, MapSlot slot, const std::string& where) {
    const auto info = owner.find(key);
    if (info == owner.end()) return;
    const std::string origin = where + ": " + key;
    if (!info->is_object() || !info->contains("index") || !(*info)["index"].is_number_unsigned())
      corrupt(origin.substr(name_.size() + 2) + " has no texture index");
    if (info->value("texCoord", std::uint64_t{0}) != 0) {
      report_.warnings.push_back(origin + " uses TEXCOORD_" + std::to_string(info->value("texCoord", std::uint64_t{0})) +
                                 "; only TEXCOORD_0 is read, so this map is left out");
      return;
    }
    if (info->contains("extensions") && (*info)["extensions"].contains("KHR_texture_transform"))
      report_.warnings.push_back(origin + ": KHR_texture_transform is ignored: the map is read as if it were not there");
    TextureMap map;
    map.slot = slot;
    map.srgb = slot == MapSlot::BaseColor || slot == MapSlot::Emissive;
    map.scale = slot == MapSlot::Normal ? number_or(*info, "scale", 1.0)
                : slot == MapSlot::Occlusion ? number_or(*info, "strength", 1.0) : 1.0;
    const std::uint64_t texture = (*info)["index"].get<std::uint64_t>();
    const json& t = element("textures", texture, origin);
    if (!t.contains("source") || !t["source"].is_number_unsigned())
      corrupt(origin.substr(name_.size() + 2) + ": texture " + std::to_string(texture) +
              " has no PNG or JPEG source (KTX2 / WebP images are not read)");
    if (t.contains("sampler") && t["sampler"].is_number_unsigned()) {
      const json& s = element("samplers", t["sampler"].get<std::uint64_t>(), origin);
      if ((s.value("wrapS", kRepeat) != kRepeat || s.value("wrapT", kRepeat) != kRepeat) && non_repeat_map_.empty())
        non_repeat_map_ = origin;
    }
    const std::uint64_t image = t["source"].get<std::uint64_t>();
    map.origin = origin + " (image " + std::to_string(image) + ")";
    load_image(map, image);
    material.maps.push_back(std::move(map));
  }

  const json& element(const char* array, std::uint64_t index, const std::string& origin) const {
    const auto it = doc_.find(array);
    if (it == doc_.end() || !it->is_array() || index >= it->size() || !(*it)[index].is_object())
      corrupt(origin.substr(name_.size() + 2) + " refers to " + array + "[" + std::to_string(index) + "], which does not exist");
    return (*it)[index];
  }

  /// The image's bytes (from a buffer view, a data: URI or a file) decoded into \p map; an image used
  /// by several maps is decoded once.
  void load_image(TextureMap& map, std::uint64_t index) {
    if (const auto it = loaded_.find(index); it != loaded_.end()) {
      map.path = it->second.path;
      map.image = it->second.image;
      return;
    }
    read_image_source(map, index);
    loaded_[index] = map;
  }

  void read_image_source(TextureMap& map, std::uint64_t index) {
    const json& img = element("images", index, map.origin);
    std::string bytes;
    if (img.contains("bufferView")) {
      if (!img["bufferView"].is_number_unsigned()) corrupt("image " + std::to_string(index) + ": bufferView is not an index");
      map.path = name_ + "#image" + std::to_string(index);
      if (!options_.load_images) return;
      bytes = view_bytes(img["bufferView"].get<std::uint64_t>(), map.origin);
    } else if (img.contains("uri") && img["uri"].is_string()) {
      const std::string uri = img["uri"].get<std::string>();
      if (uri.rfind("data:", 0) == 0) {
        map.path = name_ + "#image" + std::to_string(index);
        if (!options_.load_images) return;
        bytes = decode_base64(uri, uri.find(',') + 1);
      } else {
        map.path = dir_ / percent_decoded(uri);
        std::error_code ec;
        if (!fs::exists(map.path, ec)) throw IoError(map.origin + ": file does not exist (" + map.path.string() + ")");
        if (fs::equivalent(map.path, name_, ec)) throw IoError(map.origin + ": names " + name_ + " itself, not an image");
        if (!options_.load_images) return;
        map.image = read_image(map.path);
        return;
      }
    } else {
      corrupt("image " + std::to_string(index) + " has neither a bufferView nor a uri");
    }
    map.image = read_image_from_memory(bytes, map.path.string());
  }

  std::string view_bytes(std::uint64_t view_index, const std::string& origin) {
    // check_gltf() checked every view against its buffer and every buffer against its bytes.
    const json& view = element("bufferViews", view_index, origin);
    const std::uint64_t buffer = view.value("buffer", std::uint64_t{0});
    const std::uint64_t offset = view.value("byteOffset", std::uint64_t{0}), length = view.value("byteLength", std::uint64_t{0});
    const json& b = element("buffers", buffer, origin);
    if (!b.contains("uri")) {
      if (offset + length > gltf_.bin_length) corrupt("bufferView " + std::to_string(view_index) + " lies outside the BIN chunk");
      return bytes_.substr(static_cast<std::size_t>(gltf_.bin_offset + offset), static_cast<std::size_t>(length));
    }
    const std::string data = uri_buffer_bytes(b, dir_);
    if (offset + length > data.size()) corrupt("bufferView " + std::to_string(view_index) + " lies outside its buffer");
    return data.substr(static_cast<std::size_t>(offset), static_cast<std::size_t>(length));
  }

  const CheckedGltf& gltf_;
  const json& doc_;
  const std::string& bytes_;
  std::string name_;
  fs::path dir_;
  const AssetReadOptions& options_;
  ReadReport& report_;
  std::string non_repeat_map_;
  std::map<std::uint64_t, TextureMap> loaded_;  ///< By image index.
};

}  // namespace

TexturedAsset read_gltf_asset(const std::string& bytes, const fs::path& name, const AssetReadOptions& options,
                              ReadReport& report) {
  const CheckedGltf checked = check_gltf(name.string(), name.parent_path(), bytes);
  report.format = checked.glb ? "glb" : "gltf";
  GltfMaterials reader(checked, bytes, name, options, report);
  std::vector<Material> materials;
  try {
    materials = reader.read();
  } catch (const json::exception& e) {  // a member of an unexpected type that the checks above let pass
    throw IoError(name.string() + ": corrupt glTF: a material cannot be read (" +
                  std::string(e.what()).substr(0, std::string(e.what()).find('\n')) + ")");
  }
  TexturedSoup soup = read_gltf_textured_soup(bytes, {name.string(), name.parent_path()}, checked);
  const int untextured = soup.untextured_polygons;
  std::vector<int> face_material;
  TexturedMesh tm = textured_from_soup(std::move(soup), name.string(), options.mesh, &report, &face_material);
  TexturedAsset out = finish_asset(std::move(tm), std::move(face_material), std::move(materials), name.string(), options, report);
  out.uv.untextured_faces = untextured;
  if (untextured > 0)
    report.warnings.push_back(name.string() + ": " + count_str(untextured, "face", "faces") +
                              " without texture coordinates (their material has no map) get UV (0, 0)");
  const int outside = out.uv.wrapped_charts + out.uv.straddling_charts;
  if (outside > 0 && !reader.non_repeat_map().empty())
    throw InvalidInputError(reader.non_repeat_map() + ": the sampler does not repeat, but " +
                            count_str(outside, "UV chart lies", "UV charts lie") +
                            " outside [0,1]; only repeat wrapping is supported there");
  return out;
}

}  // namespace adaptex::io_detail
