/// \file stroke_json.cpp
#include "stroke_json.h"

#include "adaptex/core/errors.h"

namespace adaptex::studio {
namespace {
nlohmann::json vec(const Vec3& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); }
}  // namespace

nlohmann::json strokes_to_json(const StrokeFile& file) {
  nlohmann::json j;
  j["format"] = "adaptex.strokes";
  j["version"] = 1;
  j["background"] = vec(file.background);
  nlohmann::json arr = nlohmann::json::array();
  for (const Stroke& s : file.strokes) {
    nlohmann::json o;
    if (s.type == Stroke::Type::Decal) {  // fields as in docs/decals.md
      o["type"] = "decal";
      o["image"] = s.image_path;
      o["eye"] = vec(s.camera.eye);
      o["target"] = vec(s.camera.target);
      o["up"] = vec(s.camera.up);
      o["fov"] = s.camera.fov_y_degrees;
      o["aspect"] = s.camera.aspect;
      o["opacity"] = s.opacity;
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
  return parse_strokes(j.dump(), name, base_dir);
}

}  // namespace adaptex::studio
