/// \file strokes.cpp
/// Strict reader / writer of the stroke file (`adaptex.strokes`, version 1) and the contract's
/// brush falloff (shared/docs/strokes.md, mirrored in docs/strokes.md). Thesis §3.4 paints what
/// this file records.
#include "adaptex/paint/strokes.h"

#include <cmath>
#include <fstream>

#include "adaptex/core/errors.h"
#include "adaptex/io/image_io.h"
#include "adaptex/io/input_file.h"
#include "json_fields.h"

namespace adaptex {

using namespace detail;  // NOLINT: the shared field readers

namespace {

void check_camera(const DecalCamera& cam, const Where& w) {
  const Vec3 dir = cam.target - cam.eye;
  if (!(dir.norm() > 0)) w.fail("\"target\" must differ from \"eye\"");
  if (!(cam.up.norm() > 0) || dir.normalized().cross(cam.up.normalized()).norm() < 1e-9)
    w.fail("\"up\" must be non-zero and not parallel to the viewing direction (target - eye)");
  if (!(cam.fov_y_degrees > 0 && cam.fov_y_degrees < 180))
    w.fail("\"fov\" must be in (0, 180) degrees (got " + num(cam.fov_y_degrees) + ")");
  if (!(cam.aspect > 0 && std::isfinite(cam.aspect)))
    w.fail("\"aspect\" must be > 0 (got " + num(cam.aspect) + ")");
}

}  // namespace

Stroke detail::parse_v1_stroke(const json& js, const Where& w, const std::filesystem::path& base_dir,
                               std::vector<std::string>& warnings) {
  if (!js.is_object()) w.fail("must be a JSON object (got " + describe(js) + ")");
  Stroke s;
  std::string type = "brush";
  if (auto it = js.find("type"); it != js.end()) {
    if (!it->is_string()) w.fail("\"type\" must be \"brush\" or \"decal\" (got " + describe(*it) + ")");
    type = it->get<std::string>();
    if (type != "brush" && type != "decal")
      w.fail("\"type\" must be \"brush\" or \"decal\" (got \"" + type + "\")");
  }
  if (auto it = js.find("opacity"); it != js.end()) s.opacity = get_in_range(*it, "opacity", 0, 1, w);

  if (type == "brush") {
    s.type = Stroke::Type::Brush;
    warn_unknown(js, {"type", "color", "radius", "hardness", "opacity", "dabs"}, w, warnings);
    s.color = get_color(require(js, "color", w), "color", w);
    s.radius = get_number(require(js, "radius", w), "radius", w);
    if (!(s.radius > 0)) w.fail("\"radius\" must be > 0 (got " + num(s.radius) + ")");
    if (auto it = js.find("hardness"); it != js.end()) s.hardness = get_in_range(*it, "hardness", 0, 1, w);
    const json& dabs = require(js, "dabs", w);
    if (!dabs.is_array()) w.fail("\"dabs\" must be an array of [x, y, z] points (got " + describe(dabs) + ")");
    if (dabs.empty()) w.fail("\"dabs\" must not be empty");
    s.dabs.reserve(dabs.size());
    for (size_t k = 0; k < dabs.size(); ++k) s.dabs.push_back(get_vec3(dabs[k], "dabs[" + std::to_string(k) + "]", w));
    return s;
  }

  s.type = Stroke::Type::Decal;
  warn_unknown(js, {"type", "image", "eye", "target", "up", "fov", "aspect", "opacity"}, w, warnings);
  const json& img = require(js, "image", w);
  if (!img.is_string() || img.get<std::string>().empty())
    w.fail("\"image\" must be a non-empty path string (got " + describe(img) + ")");
  s.image_path = img.get<std::string>();
  s.camera.eye = get_vec3(require(js, "eye", w), "eye", w);
  s.camera.target = get_vec3(require(js, "target", w), "target", w);
  if (auto it = js.find("up"); it != js.end()) s.camera.up = get_vec3(*it, "up", w);
  if (auto it = js.find("fov"); it != js.end()) s.camera.fov_y_degrees = get_number(*it, "fov", w);
  const std::filesystem::path img_path = base_dir / s.image_path;
  try {
    s.image = read_image(img_path);
  } catch (const Error& e) {
    w.fail("\"image\": cannot read \"" + img_path.string() + "\" (" + e.what() + ")");
  }
  s.camera.aspect = static_cast<double>(s.image.width) / s.image.height;
  if (auto it = js.find("aspect"); it != js.end()) s.camera.aspect = get_number(*it, "aspect", w);
  check_camera(s.camera, w);
  return s;
}


long long StrokeFile::num_dabs() const {
  long long n = 0;
  for (const Stroke& s : strokes) n += static_cast<long long>(s.dabs.size());
  return n;
}

double brush_falloff(double t, double hardness) {
  if (t <= hardness) return 1.0;
  if (t >= 1.0) return 0.0;
  const double s = (t - hardness) / (1.0 - hardness);
  return 1.0 - (3.0 * s * s - 2.0 * s * s * s);
}

void validate_stroke(const Stroke& s, const std::string& where) {
  const Where w{where.empty() ? std::string() : where + ": "};
  auto in01 = [&](double x, const char* field) {
    if (!std::isfinite(x) || x < 0 || x > 1)
      w.fail(std::string("\"") + field + "\" must be in [0, 1] (got " + num(x) + ")");
  };
  in01(s.opacity, "opacity");
  if (s.type == Stroke::Type::Decal) {
    if (s.image.empty()) w.fail("\"image\" is empty");
    check_camera(s.camera, w);
    return;
  }
  for (int k = 0; k < 3; ++k) in01(s.color[k], "color");
  if (!std::isfinite(s.radius) || !(s.radius > 0)) w.fail("\"radius\" must be > 0 (got " + num(s.radius) + ")");
  in01(s.hardness, "hardness");
  if (s.dabs.empty()) w.fail("\"dabs\" must not be empty");
  for (size_t k = 0; k < s.dabs.size(); ++k)
    if (!s.dabs[k].allFinite()) w.fail("\"dabs[" + std::to_string(k) + "]\" must be finite");
}

StrokeFile parse_strokes(const std::string& text, const std::string& name,
                         const std::filesystem::path& base_dir) {
  return detail::strokes_from_json(parse_stroke_json(text, name), name, base_dir);
}

StrokeFile detail::strokes_from_json(const json& js, const std::string& name, const std::filesystem::path& base_dir) {
  const Where top{name + ": "};
  StrokeFile out;
  const json& version = stroke_file_version(js, top);
  if (!version.is_number_integer() || version.get<long long>() != 1)
    top.fail("\"version\" must be 1 (got " + describe(version) + ")");
  warn_unknown(js, {"format", "version", "background", "strokes"}, top, out.warnings);
  if (auto it = js.find("background"); it != js.end()) out.background = get_color(*it, "background", top);
  const json& strokes = require(js, "strokes", top);
  if (!strokes.is_array()) top.fail("\"strokes\" must be an array (got " + describe(strokes) + ")");
  out.strokes.reserve(strokes.size());
  for (size_t k = 0; k < strokes.size(); ++k)
    out.strokes.push_back(
        parse_v1_stroke(strokes[k], Where{name + ": stroke " + std::to_string(k) + ": "}, base_dir, out.warnings));
  return out;
}

StrokeFile read_strokes(const std::filesystem::path& path) {
  return parse_strokes(read_input_file(path), path.string(), path.parent_path());
}

void write_strokes(const std::filesystem::path& path, const StrokeFile& file) {
  std::ofstream os(path, std::ios::binary);
  if (!os) throw OutputError(path.string() + ": cannot open for writing");
  os << "{\n  \"format\": \"adaptex.strokes\",\n  \"version\": 1,\n  \"background\": ";
  put_vec(os, file.background);
  os << ",\n  \"strokes\": [";
  for (size_t k = 0; k < file.strokes.size(); ++k) {
    const Stroke& s = file.strokes[k];
    os << (k ? ",\n" : "\n") << "    {";
    if (s.type == Stroke::Type::Brush) {
      os << "\"color\": ";
      put_vec(os, s.color);
      os << ", \"radius\": " << num(s.radius) << ", \"hardness\": " << num(s.hardness)
         << ", \"opacity\": " << num(s.opacity) << ",\n     \"dabs\": [";
      for (size_t d = 0; d < s.dabs.size(); ++d) {
        os << (d == 0 ? "" : (d % 4 == 0 ? ",\n              " : ", "));
        put_vec(os, s.dabs[d]);
      }
      os << "]}";
    } else {
      put_decal(os, s);
      os << "}";
    }
  }
  os << (file.strokes.empty() ? "]\n}\n" : "\n  ]\n}\n");
  os.flush();
  if (!os) throw OutputError(path.string() + ": write error");
}

}  // namespace adaptex
