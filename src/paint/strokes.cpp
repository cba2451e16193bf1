/// \file strokes.cpp
/// Strict reader / writer of the stroke file (`adaptex.strokes`, version 1) and the contract's
/// brush falloff (shared/docs/strokes.md, mirrored in docs/strokes.md). Thesis §3.4 paints what
/// this file records.
#include "adaptex/paint/strokes.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "adaptex/core/errors.h"
#include "adaptex/io/image_io.h"
#include "adaptex/io/input_file.h"

namespace adaptex {

namespace {

using json = nlohmann::json;

/// Shortest round-trip decimal form of a double ("inf", "-inf", "nan" for the non-finite).
std::string num(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  if (x == 0) return std::signbit(x) ? "-0.0" : "0";  // "-0" would read back as the integer 0
  char buf[64];
  auto res = std::to_chars(buf, buf + sizeof(buf), x);
  return std::string(buf, res.ptr);
}

/// Short description of a JSON value for messages: `string "abc"`, `array`, `null`, `1.5`.
std::string describe(const json& v) {
  if (v.is_number()) return num(v.get<double>());
  if (v.is_string()) {
    std::string s = v.get<std::string>();
    if (s.size() > 40) s = s.substr(0, 40) + "...";
    return "string \"" + s + "\"";
  }
  return v.type_name();
}

/// Error context: "file: stroke 3: ".
struct Where {
  std::string prefix;
  [[noreturn]] void fail(const std::string& msg) const { throw InvalidInputError(prefix + msg); }
};

double get_number(const json& v, const std::string& field, const Where& w) {
  if (!v.is_number())
    w.fail("\"" + field + "\" must be a finite number (got " + describe(v) + ")");
  const double x = v.get<double>();
  if (!std::isfinite(x)) w.fail("\"" + field + "\" must be finite (got " + num(x) + ")");
  return x;
}

double get_in_range(const json& v, const std::string& field, double lo, double hi, const Where& w) {
  const double x = get_number(v, field, w);
  if (x < lo || x > hi)
    w.fail("\"" + field + "\" must be in [" + num(lo) + ", " + num(hi) + "] (got " + num(x) + ")");
  return x;
}

Vec3 get_vec3(const json& v, const std::string& field, const Where& w) {
  if (!v.is_array() || v.size() != 3)
    w.fail("\"" + field + "\" must be an array of 3 finite numbers (got " +
           (v.is_array() ? "an array of " + std::to_string(v.size()) : describe(v)) + ")");
  Vec3 out;
  for (int k = 0; k < 3; ++k) out[k] = get_number(v[k], field + "[" + std::to_string(k) + "]", w);
  return out;
}

Vec3 get_color(const json& v, const std::string& field, const Where& w) {
  const Vec3 c = get_vec3(v, field, w);
  for (int k = 0; k < 3; ++k)
    if (c[k] < 0 || c[k] > 1)
      w.fail("\"" + field + "\"[" + std::to_string(k) + "] must be in [0, 1] (got " + num(c[k]) + ")");
  return c;
}

const json& require(const json& obj, const std::string& field, const Where& w) {
  auto it = obj.find(field);
  if (it == obj.end()) w.fail("missing required field \"" + field + "\"");
  return *it;
}

void warn_unknown(const json& obj, const std::set<std::string>& known, const Where& w,
                  std::vector<std::string>& warnings) {
  for (auto it = obj.begin(); it != obj.end(); ++it)
    if (!known.count(it.key())) warnings.push_back(w.prefix + "unknown field \"" + it.key() + "\" ignored");
}

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

Stroke parse_stroke(const json& js, const Where& w, const std::filesystem::path& base_dir,
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

/// DOM builder that knows where it is ("strokes", 3, "radius"), so that numbers JSON cannot hold
/// (1e999 overflows a double) are reported like every other bad value: naming stroke and field.
class LocatingParser : public nlohmann::detail::json_sax_dom_parser<json> {
 public:
  using Base = nlohmann::detail::json_sax_dom_parser<json>;
  explicit LocatingParser(json& root) : Base(root, true) {}
  bool null() { return value(), Base::null(); }
  bool boolean(bool v) { return value(), Base::boolean(v); }
  bool number_integer(json::number_integer_t v) { return value(), Base::number_integer(v); }
  bool number_unsigned(json::number_unsigned_t v) { return value(), Base::number_unsigned(v); }
  bool number_float(json::number_float_t v, const std::string& s) { return value(), Base::number_float(v, s); }
  bool string(std::string& v) { return value(), Base::string(v); }
  bool binary(json::binary_t& v) { return value(), Base::binary(v); }
  bool start_object(std::size_t n) {
    value();
    path_.push_back({false, 0, {}});
    return Base::start_object(n);
  }
  bool key(std::string& k) {
    path_.back().key = k;
    return Base::key(k);
  }
  bool end_object() {
    path_.pop_back();
    return Base::end_object();
  }
  bool start_array(std::size_t n) {
    value();
    path_.push_back({true, 0, {}});
    return Base::start_array(n);
  }
  bool end_array() {
    path_.pop_back();
    return Base::end_array();
  }
  template <class Exception>
  bool parse_error(std::size_t pos, const std::string& token, const Exception& ex) {
    if (ex.id == 406 && !path_.empty()) {  // number overflow: name where it is
      std::ostringstream msg;
      msg << name_ << ": ";
      size_t k = 0;
      if (path_.size() >= 2 && !path_[0].array && path_[0].key == "strokes" && path_[1].array) {
        msg << "stroke " << (path_.size() == 2 ? path_[1].index : path_[1].index - 1) << ": ";
        k = 2;
      }
      std::ostringstream field;
      for (; k < path_.size(); ++k) {
        const Frame& f = path_[k];
        if (f.array)
          field << '[' << (k + 1 == path_.size() ? f.index : f.index - 1) << ']';
        else
          field << f.key;
      }
      if (!field.str().empty()) msg << '"' << field.str() << "\" ";
      msg << "must be finite (got " << token << ")";
      throw InvalidInputError(msg.str());
    }
    return Base::parse_error(pos, token, ex);
  }
  std::string name_;

 private:
  struct Frame {
    bool array;
    size_t index;  // values seen so far in an array
    std::string key;
  };
  void value() {
    if (!path_.empty() && path_.back().array) ++path_.back().index;
  }
  std::vector<Frame> path_;
};

}  // namespace

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
  json js;
  try {
    LocatingParser sax(js);
    sax.name_ = name;
    json::sax_parse(text, &sax);
  } catch (const json::exception& e) {
    throw IoError(name + ": not valid JSON (" + e.what() + ")");
  }
  const Where top{name + ": "};
  if (!js.is_object()) top.fail("the top level must be a JSON object (got " + describe(js) + ")");
  StrokeFile out;
  const json& format = require(js, "format", top);
  if (!format.is_string() || format.get<std::string>() != "adaptex.strokes")
    top.fail("\"format\" must be \"adaptex.strokes\" (got " + describe(format) + ")");
  const json& version = require(js, "version", top);
  if (!version.is_number_integer() || version.get<long long>() != 1)
    top.fail("\"version\" must be 1 (got " + describe(version) + ")");
  warn_unknown(js, {"format", "version", "background", "strokes"}, top, out.warnings);
  if (auto it = js.find("background"); it != js.end()) out.background = get_color(*it, "background", top);
  const json& strokes = require(js, "strokes", top);
  if (!strokes.is_array()) top.fail("\"strokes\" must be an array (got " + describe(strokes) + ")");
  out.strokes.reserve(strokes.size());
  for (size_t k = 0; k < strokes.size(); ++k)
    out.strokes.push_back(
        parse_stroke(strokes[k], Where{name + ": stroke " + std::to_string(k) + ": "}, base_dir, out.warnings));
  return out;
}

StrokeFile read_strokes(const std::filesystem::path& path) {
  return parse_strokes(read_input_file(path), path.string(), path.parent_path());
}

namespace {
void put_vec(std::ostream& os, const Vec3& v) {
  os << '[' << num(v[0]) << ", " << num(v[1]) << ", " << num(v[2]) << ']';
}
}  // namespace

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
      os << "\"type\": \"decal\", \"image\": " << json(s.image_path).dump() << ", \"eye\": ";
      put_vec(os, s.camera.eye);
      os << ", \"target\": ";
      put_vec(os, s.camera.target);
      os << ", \"up\": ";
      put_vec(os, s.camera.up);
      os << ", \"fov\": " << num(s.camera.fov_y_degrees) << ", \"aspect\": " << num(s.camera.aspect)
         << ", \"opacity\": " << num(s.opacity) << "}";
    }
  }
  os << (file.strokes.empty() ? "]\n}\n" : "\n  ]\n}\n");
  os.flush();
  if (!os) throw OutputError(path.string() + ": write error");
}

}  // namespace adaptex
