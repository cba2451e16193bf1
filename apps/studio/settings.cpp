/// \file settings.cpp
/// Project file read / write (see settings.h).
#include "settings.h"

#include <fstream>
#include <nlohmann/json.hpp>

#include "adaptex/adapt/adapt.h"
#include "adaptex/core/atomic_output.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "adaptex/io/input_file.h"
#include "stroke_json.h"

namespace adaptex::studio {
namespace {
using nlohmann::json;
json v3(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }
Vec3 get_v3(const json& j, const Vec3& def) {
  if (!j.is_array() || j.size() != 3) return def;
  return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
}
// The studio's modes are the library's, in the same order (adaptex::adapt_modes()).
const char* mode_name(AdaptMode m) { return adaptex::to_string(adaptex::adapt_modes().at(static_cast<size_t>(m))); }
AdaptMode mode_from(const std::string& s) {
  const auto& modes = adaptex::adapt_modes();
  for (size_t k = 0; k < modes.size(); ++k)
    if (s == adaptex::to_string(modes[k])) return AdaptMode(static_cast<int>(k));
  return AdaptMode::None;
}
}  // namespace

void write_project(const std::filesystem::path& path, const Project& p) {
  json j;
  j["format"] = "adaptex.studio-project";
  j["version"] = 1;
  j["mesh"] = p.mesh_path;
  j["strokes"] = strokes_to_json(p.strokes);
  const BrushSettings& b = p.brush;
  j["brush"] = {{"tool", int(b.tool)},       {"color", v3(b.color)},       {"radius", b.radius},
                {"hardness", b.hardness},    {"opacity", b.opacity},       {"spacing", b.spacing},
                {"symmetry_axis", b.symmetry_axis}};
  j["view"] = {{"wireframe", p.view.wireframe}, {"background", v3(p.view.background)}};
  j["adapt"] = {{"mode", mode_name(p.adapt.mode)}, {"alpha", p.adapt.alpha},           {"beta", p.adapt.beta},
                {"coarse_grid", p.adapt.coarse_grid}, {"fine_grid", p.adapt.fine_grid},
                {"texture_size", p.adapt.texture_size}};
  if (p.camera)
    j["camera"] = {{"target", v3(p.camera->target)}, {"distance", p.camera->distance}, {"yaw", p.camera->yaw},
                   {"pitch", p.camera->pitch},       {"fov_y", p.camera->fov_y_degrees}};
  AtomicOutput out;
  const auto tmp = out.add(path);
  {
    std::ofstream o(tmp);
    o << j.dump(1) << "\n";
    if (!o) throw OutputError(path.string() + ": write failed");
  }
  out.commit();
}

Project read_project(const std::filesystem::path& path) {
  const std::string text = read_input_file(path);
  json j;
  try {
    j = json::parse(text);
  } catch (const std::exception&) {
    throw IoError(path.string() + ": not valid JSON");
  }
  if (!j.is_object() || !j.contains("format") || j["format"] != "adaptex.studio-project")
    throw InvalidInputError(path.string() + ": not an adaptex.studio-project file");
  if (!j.contains("version") || j["version"] != 1)
    throw InvalidInputError(path.string() + ": unsupported project version");
  try {
    Project p;
    p.mesh_path = j.at("mesh").get<std::string>();
    p.strokes = strokes_from_json(j.at("strokes"), path.string(), path.parent_path());
    if (j.contains("brush")) {
      const json& b = j["brush"];
      p.brush.tool = Tool(std::clamp(b.value("tool", 0), 0, 2));
      p.brush.color = get_v3(b.value("color", json()), p.brush.color);
      p.brush.radius = b.value("radius", p.brush.radius);
      p.brush.hardness = b.value("hardness", p.brush.hardness);
      p.brush.opacity = b.value("opacity", p.brush.opacity);
      p.brush.spacing = b.value("spacing", p.brush.spacing);
      p.brush.symmetry_axis = std::clamp(b.value("symmetry_axis", -1), -1, 2);
    }
    if (j.contains("view")) {
      p.view.wireframe = j["view"].value("wireframe", false);
      p.view.background = get_v3(j["view"].value("background", json()), p.view.background);
    }
    if (j.contains("adapt")) {
      const json& a = j["adapt"];
      p.adapt.mode = mode_from(a.value("mode", "none"));
      p.adapt.alpha = a.value("alpha", p.adapt.alpha);
      p.adapt.beta = a.value("beta", p.adapt.beta);
      p.adapt.coarse_grid = a.value("coarse_grid", p.adapt.coarse_grid);
      p.adapt.fine_grid = a.value("fine_grid", p.adapt.fine_grid);
      p.adapt.texture_size = std::clamp(a.value("texture_size", p.adapt.texture_size), 16, kMaxTextureSize);
    }
    if (j.contains("camera")) {
      Camera c;
      const json& cj = j["camera"];
      c.target = get_v3(cj.value("target", json()), c.target);
      c.distance = cj.value("distance", c.distance);
      c.yaw = cj.value("yaw", 0.0);
      c.pitch = cj.value("pitch", 0.0);
      c.fov_y_degrees = cj.value("fov_y", c.fov_y_degrees);
      p.camera = c;
    }
    return p;
  } catch (const json::exception& e) {
    throw InvalidInputError(path.string() + ": bad project content (" + std::string(e.what()) + ")");
  }
}

}  // namespace adaptex::studio
