/// \file stroke_json.cpp
#include "stroke_json.h"

#include <cmath>

#include "adaptex/core/errors.h"
#include "backend.h"

namespace adaptex::studio {
namespace {

nlohmann::json vec(const Vec3& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); }

Vec3 read_vec(const nlohmann::json& j, const std::string& where) {
  if (!j.is_array() || j.size() != 3) throw InvalidInputError(where + ": expected an array of 3 numbers");
  Vec3 v;
  for (int k = 0; k < 3; ++k) {
    if (!j[k].is_number()) throw InvalidInputError(where + ": expected numbers");
    v[k] = j[k].get<double>();
    if (!std::isfinite(v[k])) throw InvalidInputError(where + ": not a finite number");
  }
  return v;
}

double read_unit(const nlohmann::json& s, const char* key, double def, const std::string& where) {
  if (!s.contains(key)) return def;
  if (!s[key].is_number()) throw InvalidInputError(where + "." + key + ": expected a number");
  const double v = s[key].get<double>();
  if (!std::isfinite(v) || v < 0 || v > 1) throw InvalidInputError(where + "." + key + ": must be in [0,1]");
  return v;
}

}  // namespace

nlohmann::json strokes_to_json(const StrokeFile& file) {
  nlohmann::json j;
  j["format"] = "adaptex.strokes";
  j["version"] = 1;
  j["background"] = vec(file.background);
  nlohmann::json arr = nlohmann::json::array();
  for (const Stroke& s : file.strokes) {
    nlohmann::json o;
    if (s.type == Stroke::Type::Decal) {
      o["type"] = "decal";
      o["image"] = s.image_path;
      o["opacity"] = s.opacity;
      o["camera"] = {{"eye", vec(s.camera.eye)},
                     {"target", vec(s.camera.target)},
                     {"up", vec(s.camera.up)},
                     {"fov_y", s.camera.fov_y_degrees},
                     {"aspect", s.camera.aspect}};
    } else {
      o["color"] = vec(s.color);
      o["radius"] = s.radius;
      o["hardness"] = s.hardness;
      o["opacity"] = s.opacity;
      nlohmann::json dabs = nlohmann::json::array();
      for (const Vec3& d : s.dabs) dabs.push_back(vec(d));
      o["dabs"] = std::move(dabs);
    }
    arr.push_back(std::move(o));
  }
  j["strokes"] = std::move(arr);
  return j;
}

StrokeFile strokes_from_json(const nlohmann::json& j, const std::string& name,
                             const std::filesystem::path& base_dir) {
  if (!j.is_object() || j.value("format", "") != "adaptex.strokes")
    throw InvalidInputError(name + ": not an adaptex.strokes object");
  if (!j.contains("version") || !j["version"].is_number_integer() || j["version"].get<int>() != 1)
    throw InvalidInputError(name + ": unsupported version (expected 1)");
  StrokeFile f;
  if (j.contains("background")) f.background = read_vec(j["background"], name + ": background");
  if (!j.contains("strokes") || !j["strokes"].is_array()) throw InvalidInputError(name + ": missing strokes array");
  int i = 0;
  for (const auto& s : j["strokes"]) {
    const std::string where = name + ": strokes[" + std::to_string(i++) + "]";
    if (!s.is_object()) throw InvalidInputError(where + ": expected an object");
    Stroke st;
    const std::string type = s.value("type", "brush");
    st.opacity = read_unit(s, "opacity", 1.0, where);
    if (type == "decal") {
      st.type = Stroke::Type::Decal;
      if (!s.contains("image") || !s["image"].is_string()) throw InvalidInputError(where + ".image: missing");
      st.image_path = s["image"].get<std::string>();
      std::filesystem::path p = st.image_path;
      st.image = load_image(p.is_absolute() ? p : base_dir / p);
      if (!s.contains("camera") || !s["camera"].is_object()) throw InvalidInputError(where + ".camera: missing");
      const auto& c = s["camera"];
      st.camera.eye = read_vec(c.at("eye"), where + ".camera.eye");
      st.camera.target = read_vec(c.at("target"), where + ".camera.target");
      st.camera.up = read_vec(c.at("up"), where + ".camera.up");
      st.camera.fov_y_degrees = c.value("fov_y", 45.0);
      st.camera.aspect = c.value("aspect", 1.0);
    } else if (type == "brush") {
      if (!s.contains("color")) throw InvalidInputError(where + ".color: missing");
      st.color = read_vec(s["color"], where + ".color");
      if (!s.contains("radius") || !s["radius"].is_number()) throw InvalidInputError(where + ".radius: missing");
      st.radius = s["radius"].get<double>();
      if (!std::isfinite(st.radius) || st.radius <= 0) throw InvalidInputError(where + ".radius: must be > 0");
      st.hardness = read_unit(s, "hardness", 0.5, where);
      if (!s.contains("dabs") || !s["dabs"].is_array() || s["dabs"].empty())
        throw InvalidInputError(where + ".dabs: missing or empty");
      int k = 0;
      for (const auto& d : s["dabs"]) st.dabs.push_back(read_vec(d, where + ".dabs[" + std::to_string(k++) + "]"));
    } else {
      throw InvalidInputError(where + ".type: unknown type '" + type + "'");
    }
    f.strokes.push_back(std::move(st));
  }
  return f;
}

}  // namespace adaptex::studio
