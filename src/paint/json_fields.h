#pragma once
/// \file json_fields.h
/// Internal: strict JSON field readers shared by the stroke file readers (version 1, strokes.cpp;
/// version 2, material_strokes.cpp): one-line errors that name the file, the place and the field.
#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "adaptex/core/errors.h"
#include "adaptex/core/types.h"
#include "adaptex/paint/strokes.h"

namespace adaptex::detail {

using json = nlohmann::json;

/// Shortest round-trip decimal form of a double ("inf", "-inf", "nan" for the non-finite).
inline std::string num(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  if (x == 0) return std::signbit(x) ? "-0.0" : "0";  // "-0" would read back as the integer 0
  char buf[64];
  auto res = std::to_chars(buf, buf + sizeof(buf), x);
  return std::string(buf, res.ptr);
}

/// Short description of a JSON value for messages: `string "abc"`, `array`, `null`, `1.5`.
inline std::string describe(const json& v) {
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

inline double get_number(const json& v, const std::string& field, const Where& w) {
  if (!v.is_number())
    w.fail("\"" + field + "\" must be a finite number (got " + describe(v) + ")");
  const double x = v.get<double>();
  if (!std::isfinite(x)) w.fail("\"" + field + "\" must be finite (got " + num(x) + ")");
  return x;
}

inline double get_in_range(const json& v, const std::string& field, double lo, double hi, const Where& w) {
  const double x = get_number(v, field, w);
  if (x < lo || x > hi)
    w.fail("\"" + field + "\" must be in [" + num(lo) + ", " + num(hi) + "] (got " + num(x) + ")");
  return x;
}

inline Vec3 get_vec3(const json& v, const std::string& field, const Where& w) {
  if (!v.is_array() || v.size() != 3)
    w.fail("\"" + field + "\" must be an array of 3 finite numbers (got " +
           (v.is_array() ? "an array of " + std::to_string(v.size()) : describe(v)) + ")");
  Vec3 out;
  for (int k = 0; k < 3; ++k) out[k] = get_number(v[k], field + "[" + std::to_string(k) + "]", w);
  return out;
}

inline Vec3 get_color(const json& v, const std::string& field, const Where& w) {
  const Vec3 c = get_vec3(v, field, w);
  for (int k = 0; k < 3; ++k)
    if (c[k] < 0 || c[k] > 1)
      w.fail("\"" + field + "\"[" + std::to_string(k) + "] must be in [0, 1] (got " + num(c[k]) + ")");
  return c;
}

inline const json& require(const json& obj, const std::string& field, const Where& w) {
  auto it = obj.find(field);
  if (it == obj.end()) w.fail("missing required field \"" + field + "\"");
  return *it;
}

inline void warn_unknown(const json& obj, const std::set<std::string>& known, const Where& w,
                  std::vector<std::string>& warnings) {
  for (auto it = obj.begin(); it != obj.end(); ++it)
    if (!known.count(it.key())) warnings.push_back(w.prefix + "unknown field \"" + it.key() + "\" ignored");
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
      const size_t k0 = place(msg);
      size_t k = k0;
      std::ostringstream field;
      for (; k < path_.size(); ++k) {
        if (path_[k].array)
          field << '[' << index(k) << ']';
        else
          field << (k > k0 ? "." : "") << path_[k].key;
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
  /// Index of the array element being read at depth k (the last frame has not counted it yet).
  size_t index(size_t k) const { return k + 1 == path_.size() ? path_[k].index : path_[k].index - 1; }
  bool key_then_array(size_t k, const char* key) const {
    return k + 1 < path_.size() && !path_[k].array && path_[k].key == key && path_[k + 1].array;
  }
  /// Writes the place ("stroke 3: ", "layer 1: stroke 2: ", "layer 0: mask: stroke 1: ") and
  /// returns the depth where the field starts.
  size_t place(std::ostream& msg) const {
    if (key_then_array(0, "strokes")) {
      msg << "stroke " << index(1) << ": ";
      return 2;
    }
    if (!key_then_array(0, "layers")) return 0;
    msg << "layer " << index(1) << ": ";
    if (key_then_array(2, "strokes")) {
      msg << "stroke " << index(3) << ": ";
      return 4;
    }
    if (path_.size() > 2 && !path_[2].array && path_[2].key == "mask" && key_then_array(3, "strokes")) {
      msg << "mask: stroke " << index(4) << ": ";
      return 5;
    }
    return 2;
  }
  void value() {
    if (!path_.empty() && path_.back().array) ++path_.back().index;
  }
  std::vector<Frame> path_;
};

inline void put_vec(std::ostream& os, const Vec3& v) {
  os << '[' << num(v[0]) << ", " << num(v[1]) << ", " << num(v[2]) << ']';
}

/// The fields of a decal stroke, from "type" to "opacity" (no braces).
inline void put_decal(std::ostream& os, const Stroke& s) {
  os << "\"type\": \"decal\", \"image\": " << json(s.image_path).dump() << ", \"eye\": ";
  put_vec(os, s.camera.eye);
  os << ", \"target\": ";
  put_vec(os, s.camera.target);
  os << ", \"up\": ";
  put_vec(os, s.camera.up);
  os << ", \"fov\": " << num(s.camera.fov_y_degrees) << ", \"aspect\": " << num(s.camera.aspect)
     << ", \"opacity\": " << num(s.opacity);
}

/// The JSON object of a stroke file (numbers that overflow a double named by place and field).
/// \throw IoError not JSON; InvalidInputError an overflowing number or a top level that is no object
inline json parse_stroke_json(const std::string& text, const std::string& name) {
  json js;
  try {
    LocatingParser sax(js);
    sax.name_ = name;
    json::sax_parse(text, &sax);
  } catch (const json::exception& e) {
    throw IoError(name + ": not valid JSON (" + e.what() + ")");
  }
  if (!js.is_object()) Where{name + ": "}.fail("the top level must be a JSON object (got " + describe(js) + ")");
  return js;
}

/// Checks "format" and returns the "version" value (unchecked). \throw InvalidInputError
inline const json& stroke_file_version(const json& js, const Where& top) {
  const json& format = require(js, "format", top);
  if (!format.is_string() || format.get<std::string>() != "adaptex.strokes")
    top.fail("\"format\" must be \"adaptex.strokes\" (got " + describe(format) + ")");
  return require(js, "version", top);
}

/// A version 1 stroke object (brush or decal; decal images read relative to \p base_dir), as the
/// version 1 reader parses it (strokes.cpp). \throw InvalidInputError the first broken rule
Stroke parse_v1_stroke(const json& js, const Where& w, const std::filesystem::path& base_dir,
                       std::vector<std::string>& warnings);

/// A version 1 stroke file from its parsed JSON (parse_strokes() without the parse).
StrokeFile strokes_from_json(const json& js, const std::string& name, const std::filesystem::path& base_dir);

}  // namespace adaptex::detail
