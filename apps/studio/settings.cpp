/// \file settings.cpp
/// Project file read / write (see settings.h).
#include "settings.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>

#include "adaptex/adapt/adapt.h"
#include "adaptex/core/atomic_output.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "adaptex/io/input_file.h"
#include "brush_preset.h"
#include "stroke_json.h"

namespace adaptex::studio {
namespace {
using nlohmann::json;
json v3(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }
Vec3 get_v3(const json& j, const Vec3& def) {
  if (!j.is_array() || j.size() != 3) return def;
  return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
}
/// The integer \p key of \p j (or \p def when absent), clamped to [lo, hi]. The number is clamped as a
/// double first: a float or a number beyond int's range (1e300, 5e123) converted straight to int is
/// undefined behaviour (fuzz_project found `texture_size: 5166...62`). Not a number: the json
/// type_error that read_project() reports as InvalidInputError.
int clamped_int(const json& j, const char* key, int def, int lo, int hi) {
  if (!j.contains(key)) return std::clamp(def, lo, hi);
  const json& v = j[key];
  if (!v.is_number()) return v.get<int>();  // throws type_error
  return static_cast<int>(std::clamp(v.get<double>(), static_cast<double>(lo), static_cast<double>(hi)));
}
json session_to_json(const PaintSessionOptions& o) {
  const AdaptOptions& a = o.adapt;
  return {{"mode", to_string(a.mode)},
          {"alpha", a.thesis.alpha},
          {"beta", a.thesis.beta},
          {"geometry_scale", a.thesis.geometry_scale},
          {"coarse_grid", a.thesis.coarse_grid},
          {"fine_grid", a.thesis.fine_grid},
          {"refine", a.refine.enabled},
          {"texture_size", o.texture_size},
          {"padding", o.padding},
          {"reparam", enum_name(o.schedule)}};
}

/// Missing keys keep the library's defaults; bad names and sizes are errors (InvalidInputError).
PaintSessionOptions session_from_json(const json& j) {
  PaintSessionOptions o = studio_session_options();
  AdaptOptions& a = o.adapt;
  if (j.contains("mode")) a.mode = parse_adapt_mode(j["mode"].get<std::string>());
  a.thesis.alpha = j.value("alpha", a.thesis.alpha);
  a.thesis.beta = j.value("beta", a.thesis.beta);
  a.thesis.geometry_scale = j.value("geometry_scale", a.thesis.geometry_scale);
  a.thesis.coarse_grid = clamped_int(j, "coarse_grid", a.thesis.coarse_grid, 2, kMaxGridCells);
  a.thesis.fine_grid = clamped_int(j, "fine_grid", a.thesis.fine_grid, 2, kMaxGridCells);
  a.refine.enabled = j.value("refine", a.refine.enabled);
  o.texture_size = clamped_int(j, "texture_size", o.texture_size, 16, kMaxTextureSize);
  o.padding = clamped_int(j, "padding", o.padding, 0, 256);
  if (j.contains("reparam")) {
    const std::string r = j["reparam"].get<std::string>();
    const std::vector<std::string> names = enum_choices<ReparamSchedule>();
    if (std::find(names.begin(), names.end(), r) == names.end())
      throw InvalidInputError("adapt.reparam must be " + or_list(names) + ", got " + r);
    o.schedule = parse_enum<ReparamSchedule>(r, "reparam schedule");
  }
  return o;
}

/// How a project file names a file it refers to (the mesh, a decal image): relative to the project's
/// folder when the file lies inside it, so that the folder can be moved or sent whole; otherwise the
/// absolute path, so that a file elsewhere (a shared library of decals) is still found after the
/// project moves. "builtin:" names and empty paths are kept.
std::string path_in_project(const std::string& p, const std::filesystem::path& project_dir) {
  if (p.empty() || p.rfind("builtin:", 0) == 0) return p;
  const std::filesystem::path abs = std::filesystem::absolute(p).lexically_normal();
  const std::filesystem::path rel = abs.lexically_relative(std::filesystem::absolute(project_dir).lexically_normal());
  if (rel.empty() || rel.is_absolute() || *rel.begin() == "..") return abs.string();
  return rel.generic_string();
}

/// The absolute path of a file that a project file names (path_in_project()'s inverse).
std::string path_from_project(const std::string& p, const std::filesystem::path& project_dir) {
  if (p.empty() || p.rfind("builtin:", 0) == 0 || std::filesystem::path(p).is_absolute()) return p;
  return std::filesystem::absolute(project_dir / p).lexically_normal().string();
}

/// Applies \p map to the image path of every decal stroke of \p strokes and \p material.
template <class Map>
void map_decal_paths(StrokeFile& strokes, std::optional<MaterialStrokeFile>& material, Map&& map) {
  for (Stroke& s : strokes.strokes)
    if (s.type == Stroke::Type::Decal) s.image_path = map(s.image_path);
  if (!material) return;
  for (MaterialLayer& l : material->layers)
    for (MaterialStroke& s : l.strokes)
      if (s.type == MaterialStroke::Type::Decal) s.decal.image_path = map(s.decal.image_path);
}
}  // namespace

std::string session_options_key(const PaintSessionOptions& options) { return session_to_json(options).dump(); }

PaintSessionOptions studio_session_options() {
  PaintSessionOptions o;
  o.schedule = ReparamSchedule::EachStroke;
  return o;
}

void write_project(const std::filesystem::path& path, const Project& project) {
  const std::filesystem::path dir = path.parent_path().empty() ? "." : path.parent_path();
  Project p = project;
  const auto in_project = [&dir](const std::string& f) { return path_in_project(f, dir); };
  map_decal_paths(p.strokes, p.material, in_project);
  json j;
  j["format"] = "adaptex.studio-project";
  j["version"] = p.material ? 2 : 1;  // version 1 readers refuse a layered material, not drop it
  j["mesh"] = in_project(p.mesh_path);
  if (!p.project_file.empty()) j["project"] = p.project_file;
  j["strokes"] = strokes_to_json(p.strokes);
  const BrushSettings& b = p.brush;
  j["brush"] = {{"tool", int(b.tool)},       {"color", v3(b.color)},       {"radius", b.radius},
                {"hardness", b.hardness},    {"opacity", b.opacity},       {"spacing", b.spacing},
                {"symmetry_axis", b.symmetry_axis}, {"screen_space", b.screen_space},
                {"pixel_radius", b.pixel_radius}, {"roughness", b.roughness}, {"metallic", b.metallic},
                {"height", b.height}};
  json channels = json::array();
  for (int c = 0; c < kNumChannels; ++c)
    if (b.channels & channel_bit(Channel(c))) channels.push_back(channel_name(Channel(c)));
  j["brush"]["channels"] = channels;
  j["brush"]["mask_value"] = b.mask_value;
  j["brush"]["on_mask"] = b.on_mask;
  if (json pressure = pressure_curves_to_json(b); !pressure.empty()) j["brush"]["pressure"] = pressure;
  if (p.material) {
    j["material"] = json::parse(material_strokes_json(*p.material));
    j["active_layer"] = p.active_layer;
  }
  j["view"] = {{"wireframe", p.view.wireframe}, {"background", v3(p.view.background)}};
  j["adapt"] = session_to_json(p.session);
  j["layout"] = p.unwrap ? "unwrap" : "atlas";
  if (p.adapted_strokes) j["adapted_strokes"] = *p.adapted_strokes;
  if (p.camera)
    j["camera"] = {{"target", v3(p.camera->target)}, {"distance", p.camera->distance}, {"yaw", p.camera->yaw},
                   {"pitch", p.camera->pitch},       {"fov_y", p.camera->fov_y_degrees}};
  AtomicOutput out;
  const auto tmp = out.add(path);
  std::ofstream o(tmp);
  if (!o) throw OutputError(path.string() + ": cannot write (" + std::strerror(errno) + ")");
  o << j.dump(1) << "\n";
  o.close();  // flushes: a full disk is reported here, before the file replaces the old one
  if (!o) throw OutputError(path.string() + ": write failed");
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
  if (!j.contains("version") || (j["version"] != 1 && j["version"] != 2))
    throw InvalidInputError(path.string() + ": unsupported project version");
  if (j["version"] == 2 && !j.contains("material"))
    throw InvalidInputError(path.string() + ": a project of version 2 needs \"material\"");
  const std::filesystem::path dir = path.parent_path().empty() ? "." : path.parent_path();
  try {
    Project p;
    p.mesh_path = path_from_project(j.at("mesh").get<std::string>(), dir);
    p.project_file = j.value("project", std::string());
    const std::string layout = j.value("layout", std::string("unwrap"));
    if (layout != "unwrap" && layout != "atlas")
      throw InvalidInputError(path.string() + ": \"layout\" must be \"atlas\" or \"unwrap\", got \"" + layout + "\"");
    p.unwrap = layout == "unwrap";
    p.strokes = strokes_from_json(j.at("strokes"), path.string(), path.parent_path());
    if (j.contains("material")) {
      p.material = parse_material_strokes(j["material"].dump(), path.string() + ": material", path.parent_path());
      p.active_layer = clamped_int(j, "active_layer", int(p.material->layers.size()) - 1, 0,
                                   std::max(0, int(p.material->layers.size()) - 1));
    }
    map_decal_paths(p.strokes, p.material, [&dir](const std::string& f) { return path_from_project(f, dir); });
    if (j.contains("adapted_strokes")) {
      const json& a = j["adapted_strokes"];
      if (!a.is_number_unsigned() || a.get<size_t>() > p.strokes.strokes.size())
        throw InvalidInputError(path.string() + ": \"adapted_strokes\" must be a count of strokes, at most " +
                                std::to_string(p.strokes.strokes.size()));
      p.adapted_strokes = a.get<size_t>();
    }
    if (j.contains("brush")) {
      const json& b = j["brush"];
      p.brush.tool = Tool(clamped_int(b, "tool", 0, 0, 2));
      p.brush.color = get_v3(b.value("color", json()), p.brush.color);
      p.brush.radius = b.value("radius", p.brush.radius);
      p.brush.hardness = b.value("hardness", p.brush.hardness);
      p.brush.opacity = b.value("opacity", p.brush.opacity);
      p.brush.spacing = b.value("spacing", p.brush.spacing);
      p.brush.symmetry_axis = clamped_int(b, "symmetry_axis", -1, -1, 2);
      p.brush.screen_space = b.value("screen_space", p.brush.screen_space);
      p.brush.pixel_radius = b.value("pixel_radius", p.brush.pixel_radius);
      p.brush.roughness = b.value("roughness", p.brush.roughness);
      p.brush.metallic = b.value("metallic", p.brush.metallic);
      p.brush.height = b.value("height", p.brush.height);
      for (double v : {p.brush.roughness, p.brush.metallic, p.brush.height})
        if (!(v >= 0 && v <= 1))
          throw InvalidInputError(path.string() + ": brush: roughness, metallic and height must be in [0, 1]");
      if (b.contains("channels")) {
        p.brush.channels = 0;
        for (const json& c : b.at("channels")) {
          const auto ch = channel_from_name(c.get<std::string>());
          if (!ch) throw InvalidInputError(path.string() + ": brush: unknown channel " + c.dump());
          p.brush.channels |= channel_bit(*ch);
        }
      }
      p.brush.mask_value = b.value("mask_value", p.brush.mask_value);
      if (!(p.brush.mask_value >= 0 && p.brush.mask_value <= 1))
        throw InvalidInputError(path.string() + ": brush: mask_value must be in [0, 1]");
      p.brush.on_mask = b.value("on_mask", p.brush.on_mask);
      if (b.contains("pressure")) pressure_curves_from_json(b["pressure"], path.string() + ": brush: ", p.brush);
      if (!(p.brush.pixel_radius >= 1 && p.brush.pixel_radius <= 1000))
        throw InvalidInputError(path.string() + ": brush: pixel_radius must be in [1, 1000]");
      // The brush paints strokes: the stroke contract's rules (colour, hardness, opacity in [0, 1],
      // radius > 0) apply, here rather than as an exception in the middle of a drag.
      Stroke style;
      style.color = p.brush.color;
      style.radius = p.brush.radius;
      style.hardness = p.brush.hardness;
      style.opacity = p.brush.opacity;
      style.dabs = {Vec3::Zero()};
      validate_stroke(style, path.string() + ": brush");
    }
    if (j.contains("view")) {
      p.view.wireframe = j["view"].value("wireframe", false);
      p.view.background = get_v3(j["view"].value("background", json()), p.view.background);
    }
    if (j.contains("adapt")) {
      try {
        p.session = session_from_json(j["adapt"]);
      } catch (const InvalidInputError& e) {
        throw InvalidInputError(path.string() + ": " + e.what());
      }
    }
    if (j.contains("camera")) {
      Camera c;
      const json& cj = j["camera"];
      c.target = get_v3(cj.value("target", json()), c.target);
      c.distance = cj.value("distance", c.distance);
      c.yaw = cj.value("yaw", 0.0);
      c.pitch = cj.value("pitch", 0.0);
      c.fov_y_degrees = cj.value("fov_y", c.fov_y_degrees);
      if (!(c.distance > 0) || !(c.fov_y_degrees > 0 && c.fov_y_degrees < 180) || !c.target.allFinite())
        throw InvalidInputError(path.string() + ": camera: distance must be > 0 and fov_y in (0, 180)");
      p.camera = c;
    }
    return p;
  } catch (const json::exception& e) {
    throw InvalidInputError(path.string() + ": bad project content (" + std::string(e.what()) + ")");
  } catch (const std::filesystem::filesystem_error& e) {
    throw IoError(path.string() + ": cannot resolve a path it names (" + std::string(e.what()) + ")");
  }
}

}  // namespace adaptex::studio
