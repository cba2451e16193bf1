#include "shrink_output.h"

#include <algorithm>
#include <cctype>
#include <set>

#include "adaptex/adapt/shrink_report.h"

namespace adaptex::cli {

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/// \p base, or base_2, base_3, ... : the first not yet in \p taken (case-insensitive), then taken.
std::string unique_name(const std::string& base, std::set<std::string>& taken, const std::string& suffix = "") {
  std::string s = base;
  for (int k = 2; taken.count(lower(s + suffix)); ++k) s = base + "_" + std::to_string(k);
  taken.insert(lower(s + suffix));
  return s + suffix;
}

/// The group and the map of \p slot of material \p m, or {-1, -1}.
std::pair<int, int> group_map(const AssetShrinkResult& res, int m, MapSlot slot) {
  for (size_t g = 0; g < res.groups.size(); ++g)
    for (const GroupMapRef& r : res.groups[g].refs)
      if (r.material == m && r.slot == slot) return {static_cast<int>(g), r.map};
  return {-1, -1};
}

}  // namespace

std::vector<std::string> output_material_names(const TexturedAsset& asset) {
  std::vector<std::string> names;
  std::set<std::string> taken;
  for (size_t m = 0; m < asset.materials.size(); ++m) {
    std::string s = asset.materials[m].name;
    for (char& c : s)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
    if (s.empty()) s = "material" + std::to_string(m);
    names.push_back(unique_name(s, taken));
  }
  return names;
}

ExportMaterials shrink_export_materials(const TexturedAsset& asset, const AssetShrinkResult& res,
                                        const std::vector<std::string>& names, const std::string& name) {
  ExportMaterials set;
  std::vector<std::vector<int>> image_of(res.groups.size());  // group, map -> image
  for (size_t g = 0; g < res.groups.size(); ++g) image_of[g].assign(res.groups[g].result.maps.size(), -1);
  std::set<std::string> files;
  for (size_t m = 0; m < asset.materials.size(); ++m) {
    const Material& in = asset.materials[m];
    ExportMaterial out;
    out.name = names[m];
    out.base_color = in.base_color;
    out.emissive = in.emissive;
    out.metallic = in.metallic;
    out.roughness = in.roughness;
    for (const TextureMap& t : in.maps) {
      const auto [g, map] = group_map(res, static_cast<int>(m), t.slot);
      if (g < 0) continue;  // a material no face uses
      int& image = image_of[g][map];
      if (image < 0) {
        const std::string slot = map_slot_name(t.slot);
        const std::string base = name + "_" + names[m] + (t.slot == MapSlot::BaseColor ? "" : "_" + slot);
        image = static_cast<int>(set.images.size());
        set.images.push_back({unique_name(base, files, ".png"), res.groups[g].result.maps[map]});
      }
      out.maps.push_back({map_slot_name(t.slot), image});
    }
    // The map carries the colour (as the one-material export writes it); alpha and the rest stay.
    if (!out.maps.empty()) out.base_color = {1, 1, 1, in.base_color[3]};
    set.materials.push_back(std::move(out));
  }
  set.face_material.resize(asset.mesh.faces.size());
  for (size_t f = 0; f < asset.mesh.faces.size(); ++f) {
    const int m = f < asset.face_material.size() ? asset.face_material[f] : -1;
    if (m < 0 || m >= static_cast<int>(asset.materials.size())) {
      if (set.materials.size() == asset.materials.size()) {
        std::set<std::string> taken;
        for (const std::string& n : names) taken.insert(lower(n));
        set.materials.push_back({unique_name("default", taken), {}, {1, 1, 1, 1}, {0, 0, 0}, {}, {}});
      }
      set.face_material[f] = static_cast<int>(asset.materials.size());
    } else {
      set.face_material[f] = m;
    }
  }
  return set;
}

std::vector<std::vector<std::pair<std::string, std::string>>> material_files(const TexturedAsset& asset,
                                                                             const ExportMaterials& set) {
  std::vector<std::vector<std::pair<std::string, std::string>>> files(asset.materials.size());
  for (size_t m = 0; m < asset.materials.size(); ++m)
    for (const ExportMaterialMap& map : set.materials[m].maps) files[m].emplace_back(map.slot, set.images[map.image].file);
  return files;
}

nlohmann::ordered_json materials_report(const TexturedAsset& asset, const AssetShrinkResult& res,
                                        const std::vector<std::string>& names,
                                        const std::vector<std::vector<std::pair<std::string, std::string>>>& files) {
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  for (size_t m = 0; m < asset.materials.size(); ++m) {
    nlohmann::ordered_json j;
    j["name"] = asset.materials[m].name;
    j["output_name"] = names[m];
    j["faces"] = std::count(asset.face_material.begin(), asset.face_material.end(), static_cast<int>(m));
    nlohmann::ordered_json maps = nlohmann::ordered_json::array();
    for (const auto& [slot, file] : files[m]) maps.push_back({{"slot", slot}, {"file", file}});
    j["maps"] = maps;
    for (const MaterialGroupShrink& g : res.groups) {
      if (std::find(g.materials.begin(), g.materials.end(), static_cast<int>(m)) == g.materials.end()) continue;
      nlohmann::ordered_json with = nlohmann::ordered_json::array();
      for (int o : g.materials)
        if (o != static_cast<int>(m)) with.push_back(asset.materials[o].name);
      j["shrunk_with"] = with;
      if (g.materials.size() == 1) j["faces"] = g.faces.size();  // with the faces it took without a material
      j["size"] = g.size;
      j["psnr"] = g.result.psnr;
      j["psnr_downsized"] = g.result.psnr_downsized;
      j["chosen"] = g.result.chosen;
      j["group_area_share"] = 0.0;
      double area = 0;
      for (const MaterialGroupShrink& h : res.groups) area += h.area;
      if (area > 0) j["group_area_share"] = g.area / area;
      if (res.groups.size() > 1 || g.materials.size() > 1) j["shrink"] = shrink_report_json(g.result, g.slots);
    }
    all.push_back(j);
  }
  return all;
}

}  // namespace adaptex::cli
