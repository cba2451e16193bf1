/// \file asset_io.cpp
/// read_textured_asset(): an OBJ with its material files, or a glTF/GLB, with every texture map.
/// OBJ: the `mtllib` statements are found here (relative to the OBJ's folder; a name may contain
/// spaces), each material file is read once with read_input_file() and parsed by parse_mtl();
/// tinyobjloader only maps `usemtl` to the material names (it is given their list as its material
/// text, never a file). Maps are resolved against their material file's folder, then decoded with
/// read_image(). Then the atlas: UDIM check, whole charts moved into [0,1]^2, counts (uv_atlas.cpp).
#include "adaptex/io/asset_io.h"

#include <algorithm>
#include <map>

#include "adaptex/core/errors.h"
#include "adaptex/io/image_io.h"
#include "gltf_asset.h"
#include "mesh_soup.h"
#include "text_scanner.h"
#include "uv_atlas.h"

namespace adaptex {

namespace {

namespace fs = std::filesystem;

std::string lower_extension(const std::string& format) {
  std::string ext = format.empty() || format[0] == '.' ? format : "." + format;
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}


/// True when \p a and \p b are the same existing file.
bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  return fs::exists(a, ec) && fs::exists(b, ec) && fs::equivalent(a, b, ec);
}

/// The material files an OBJ names: every `mtllib` statement, each name relative to the OBJ's folder.
/// A statement's whole rest is one name when such a file exists (names with spaces), else its
/// blank-separated words are. Each file once, in order.
std::vector<std::pair<fs::path, std::string>> mtllib_files(const std::string& text, const fs::path& obj) {
  std::vector<std::pair<fs::path, std::string>> out;  // (path, "m.obj: line 3: mtllib 'x.mtl'")
  int line_no = 0;
  for (std::size_t pos = 0; pos < text.size();) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    ++line_no;
    std::size_t p = pos;
    pos = end + 1;
    while (p < end && io_detail::is_line_blank(text[p])) ++p;
    if (text.compare(p, 6, "mtllib") != 0 || p + 6 >= end || !io_detail::is_line_blank(text[p + 6])) continue;
    std::string rest = text.substr(p + 7, end - p - 7);
    rest.erase(0, rest.find_first_not_of(" \t\r"));
    rest.erase(rest.find_last_not_of(" \t\r") + 1);
    std::vector<std::string> names;
    std::error_code ec;
    if (rest.empty() || fs::is_regular_file(obj.parent_path() / rest, ec)) {
      names.push_back(rest);
    } else {
      for (std::size_t a = 0; a < rest.size();) {
        const std::size_t b = std::min(rest.find_first_of(" \t", a), rest.size());
        if (b > a) names.push_back(rest.substr(a, b - a));
        a = b + 1;
      }
    }
    for (const std::string& n : names) {
      const std::string where = obj.string() + ": line " + std::to_string(line_no) + ": mtllib '" + n + "'";
      if (n.empty()) throw IoError(where + ": no file name");
      const fs::path file = obj.parent_path() / n;
      if (same_file(file, obj)) throw IoError(where + " is the OBJ file itself");
      const bool seen = std::any_of(out.begin(), out.end(), [&](const auto& o) { return same_file(o.first, file); });
      if (!seen) out.emplace_back(file, where);
    }
  }
  return out;
}

/// Reads every material file (missing ones are an error naming the OBJ line) and returns their
/// materials; a name defined in an earlier file wins.
std::vector<Material> read_material_files(const std::vector<std::pair<fs::path, std::string>>& files,
                                          std::vector<std::string>& warnings) {
  std::vector<Material> materials;
  for (const auto& [file, where] : files) {
    std::error_code ec;
    if (!fs::exists(file, ec)) throw IoError(where + ": file does not exist (" + file.string() + ")");
    for (Material& m : parse_mtl(read_input_file(file), file, &warnings)) {
      if (std::any_of(materials.begin(), materials.end(), [&](const Material& o) { return o.name == m.name; })) {
        warnings.push_back(file.string() + ": material '" + m.name + "' was defined in an earlier file; that one is used");
        continue;
      }
      materials.push_back(std::move(m));
    }
  }
  return materials;
}

/// The material text tinyobjloader sees: one `newmtl` per material, in order, named as tinyobjloader
/// reads `usemtl` (its first word), so that its material ids are indices into \p materials.
std::string material_list_for_tinyobj(const std::vector<Material>& materials) {
  std::string text;
  for (const Material& m : materials) text += "newmtl " + m.name.substr(0, m.name.find_first_of(" \t")) + "\n";
  return text;
}

/// Where a map named in a material file is: as written, else with '\' read as '/', else its file name
/// alone next to the material file (exporters write absolute Windows paths). Empty when none exists.
fs::path find_map_file(const TextureMap& map) {
  std::error_code ec;
  if (fs::exists(map.path, ec)) return map.path;
  std::string slashed = map.path.string();
  std::replace(slashed.begin(), slashed.end(), '\\', '/');
  if (fs::exists(slashed, ec)) return slashed;
  const fs::path leaf = fs::path(slashed).filename();
  const fs::path dir = map.path.parent_path();
  if (!leaf.empty() && fs::exists(dir / leaf, ec)) return dir / leaf;
  return {};
}

/// A map's colours read as unit normals (a tangent-space normal map stored in map_Bump, as Blender's
/// OBJ exporter writes it): at least 90 % of texels decode to |n| in [0.8, 1.2] with n.z > 0, and the
/// image is not grey (a height map).
bool looks_like_normal_map(const ImageRGBA8& img) {
  if (img.empty()) return false;
  std::size_t unit = 0, coloured = 0, n = static_cast<std::size_t>(img.width) * img.height;
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint8_t* t = &img.data[4 * k];
    const double x = t[0] / 127.5 - 1, y = t[1] / 127.5 - 1, z = t[2] / 127.5 - 1;
    const double len2 = x * x + y * y + z * z;
    unit += z > 0 && len2 >= 0.64 && len2 <= 1.44;
    coloured += std::abs(int{t[2]} - int{t[0]}) > 24 || std::abs(int{t[2]} - int{t[1]}) > 24;
  }
  return unit >= n * 9 / 10 && coloured >= n / 2;
}

}  // namespace

namespace io_detail {

void load_material_maps(std::vector<Material>& materials, const std::vector<fs::path>& not_images,
                        const AssetReadOptions& options, std::vector<std::string>& warnings) {
  std::map<fs::path, ImageRGBA8> decoded;
  for (Material& m : materials)
    for (TextureMap& map : m.maps) {
      if (is_udim_path(map.path.string()) && map.path.string().find('<') != std::string::npos)
        throw InvalidInputError(map.origin + ": UDIM texture sets are not supported");
      const fs::path file = find_map_file(map);
      if (file.empty()) throw IoError(map.origin + ": file does not exist (" + map.path.string() + ")");
      for (const fs::path& own : not_images)
        if (same_file(file, own)) throw IoError(map.origin + ": names " + own.string() + " itself, not an image");
      if (file != map.path) warnings.push_back(map.origin + ": read from " + file.string());
      map.path = file;
      if (!options.load_images) continue;
      auto it = decoded.find(file);
      if (it == decoded.end()) it = decoded.emplace(file, read_image(file)).first;
      map.image = it->second;
      if (map.slot == MapSlot::Bump && looks_like_normal_map(map.image)) {
        map.slot = MapSlot::Normal;
        warnings.push_back(map.origin + ": holds a normal map (its texels are unit vectors); read as the normal map");
      }
    }
}

TexturedAsset finish_asset(TexturedMesh tm, std::vector<int> face_material, std::vector<Material> materials,
                           const std::string& name, const AssetReadOptions& options, ReadReport& report) {
  TexturedAsset out;
  out.mesh = std::move(tm.mesh);
  out.param = std::move(tm.param);
  out.face_material = std::move(face_material);
  out.materials = std::move(materials);
  out.uv = count_uvs(out.mesh, out.param);
  std::string udim_map;
  for (const Material& m : out.materials)
    for (const TextureMap& map : m.maps)
      if (udim_map.empty() && is_udim_path(map.path.string())) udim_map = map.path.filename().string();
  wrap_uv_charts(out.param, options, name, udim_map, out.uv);
  const TexelUsage usage = measure_texel_usage(out.param);  // on the charts as moved
  out.uv.covered_fraction = usage.covered_fraction;
  out.uv.shared_fraction = usage.shared_fraction;
  if (out.uv.wrapped_charts > 0)
    report.warnings.push_back(name + ": " + count_str(out.uv.wrapped_charts, "UV chart", "UV charts") +
                              " outside [0,1] moved into it by whole tiles (the same texels under repeat wrapping)");
  if (out.uv.straddling_charts > 0)
    report.warnings.push_back(name + ": " + count_str(out.uv.straddling_charts, "UV chart crosses", "UV charts cross") +
                              " a UV tile border and keeps its UVs outside [0,1] (repeat wrapping)");
  if (out.uv.clamped_uvs > 0)
    report.warnings.push_back(name + ": " + count_str(out.uv.clamped_uvs, "UV coordinate", "UV coordinates") +
                              " just outside their tile (within " + std::to_string(options.uv_tolerance) +
                              ") clamped to its border");
  return out;
}

}  // namespace io_detail

namespace {

TexturedAsset read_obj_asset(const std::string& bytes, const fs::path& name, const AssetReadOptions& options,
                             ReadReport& report) {
  using namespace io_detail;
  const auto files = mtllib_files(bytes, name);
  std::vector<Material> materials = read_material_files(files, report.warnings);
  std::vector<fs::path> not_images{name};
  for (const auto& f : files) not_images.push_back(f.first);
  // Maps are found (and UDIM names rejected) before the mesh work, decoded after the UV checks.
  AssetReadOptions find_only = options;
  find_only.load_images = false;
  load_material_maps(materials, not_images, find_only, report.warnings);
  std::vector<int> face_material;
  TexturedMesh tm = textured_from_soup(read_obj_data(bytes, name.string(), material_list_for_tinyobj(materials)),
                                       name.string(), options.mesh, &report, &face_material);
  TexturedAsset out = finish_asset(std::move(tm), std::move(face_material), std::move(materials), name.string(),
                                   options, report);
  load_material_maps(out.materials, not_images, options, report.warnings);
  return out;
}

}  // namespace

TexturedAsset read_textured_asset(const fs::path& path, const AssetReadOptions& options, ReadReport* report) {
  const std::string ext = lower_extension(path.extension().string());
  if (ext != ".obj" && ext != ".gltf" && ext != ".glb")
    throw IoError(path.string() + ": unknown textured asset format '" + (ext.empty() ? "(no extension)" : ext) +
                  "' (supported: .obj with .mtl, .gltf, .glb)");
  std::error_code ec;
  if (!fs::exists(path, ec)) throw IoError(path.string() + ": cannot read: file does not exist");
  return read_textured_asset_from_memory(read_input_file(path), ext, path, options, report);
}

TexturedAsset read_textured_asset_from_memory(const std::string& bytes, const std::string& format, const fs::path& name,
                                              const AssetReadOptions& options, ReadReport* report) {
  ReadReport local;
  ReadReport& rep = report ? *report : local;
  check_input_size(bytes.size(), name.string());
  const std::string ext = lower_extension(format);
  if (ext == ".obj") {
    rep.format = "obj";
    return read_obj_asset(bytes, name, options, rep);
  }
  if (ext == ".gltf" || ext == ".glb") return io_detail::read_gltf_asset(bytes, name, options, rep);
  throw IoError(name.string() + ": unknown textured asset format '" + (ext.empty() ? "(no extension)" : ext) +
                "' (supported: .obj with .mtl, .gltf, .glb)");
}

}  // namespace adaptex
