/// \file brush_preset.cpp
#include "brush_preset.h"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "adaptex/core/atomic_output.h"
#include "adaptex/core/errors.h"
#include "adaptex/io/input_file.h"
#include "brush.h"

namespace adaptex::studio {

namespace {

using json = nlohmann::json;
constexpr const char* kFormat = "adaptex.brush-preset";

json curve_json(const PressureCurve& c) {
  json a = json::array();
  for (const Vec2& p : c.points) a.push_back({p.x(), p.y()});
  return a;
}

/// The stroke contract's rules for the curves alone (a brush stroke with them and nothing else wrong).
void check_curves(const BrushSettings& b, const std::string& where) {
  MaterialStroke s;
  s.channels = channel_bit(Channel::BaseColor);
  s.dabs = {Vec3::Zero()};
  s.radius_curve = b.radius_curve;
  s.opacity_curve = b.opacity_curve;
  validate_material_stroke(s, false, where.size() >= 2 ? where.substr(0, where.size() - 2) : where);
}

/// Reads one preset's fields with one-line errors ("NAME: brush: \"field\" ...").
struct Reader {
  std::string where;
  [[noreturn]] void fail(const std::string& msg) const { throw InvalidInputError(where + msg); }
  double number(const json& v, const std::string& field) const {
    if (!v.is_number()) fail("\"" + field + "\" must be a number (got " + std::string(v.type_name()) + ")");
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail("\"" + field + "\" must be finite");
    return x;
  }
  PressureCurve curve(const json& v, const std::string& field) const {
    if (!v.is_array()) fail("\"" + field + "\" must be an array of [pressure, factor] points");
    PressureCurve c;
    for (size_t k = 0; k < v.size(); ++k) {
      const std::string f = field + "[" + std::to_string(k) + "]";
      if (!v[k].is_array() || v[k].size() != 2) fail("\"" + f + "\" must be a [pressure, factor] pair");
      c.points.emplace_back(number(v[k][0], f + "[0]"), number(v[k][1], f + "[1]"));
    }
    return c;
  }
  void channels(const json& v, BrushSettings& b) const {
    if (!v.is_object()) fail("\"channels\" must be an object of channel values");
    b.channels = 0;
    for (auto it = v.begin(); it != v.end(); ++it) {
      const auto c = channel_from_name(it.key());
      if (!c || *c == Channel::Alpha) fail("unknown brush channel \"" + it.key() + "\"");
      const std::string f = "channels." + it.key();
      if (*c == Channel::BaseColor) {
        if (!it->is_array() || it->size() != 3) fail("\"" + f + "\" must be an array of 3 numbers");
        b.color = Vec3(number((*it)[0], f + "[0]"), number((*it)[1], f + "[1]"), number((*it)[2], f + "[2]"));
      } else {
        double& value = *c == Channel::Roughness ? b.roughness : *c == Channel::Metallic ? b.metallic : b.height;
        value = number(*it, f);
      }
      b.channels |= channel_bit(*c);
    }
  }
};

/// The stroke contract's rules for what the preset paints (values, hardness, opacity, curves).
void validate_brush(const BrushSettings& b, const std::string& name) {
  MaterialStroke s;
  s.channels = b.channels ? b.channels : channel_bit(Channel::BaseColor);
  for (int k = 0; k < 3; ++k) s.value[channel_offset(Channel::BaseColor) + k] = b.color[k];
  s.value[channel_offset(Channel::Roughness)] = b.roughness;
  s.value[channel_offset(Channel::Metallic)] = b.metallic;
  s.value[channel_offset(Channel::Height)] = b.height;
  s.hardness = b.hardness;
  s.opacity = b.opacity;
  s.dabs = {Vec3::Zero()};
  s.radius_curve = b.radius_curve;
  s.opacity_curve = b.opacity_curve;
  validate_material_stroke(s, false, name + ": brush");
  s.mask_value = b.mask_value;
  validate_material_stroke(s, true, name + ": brush");  // the mask value
}

}  // namespace

std::string brush_preset_json(const BrushSettings& b) {
  json channels = json::object();
  if (b.channels & channel_bit(Channel::BaseColor)) channels["base_color"] = {b.color.x(), b.color.y(), b.color.z()};
  if (b.channels & channel_bit(Channel::Roughness)) channels["roughness"] = b.roughness;
  if (b.channels & channel_bit(Channel::Metallic)) channels["metallic"] = b.metallic;
  if (b.channels & channel_bit(Channel::Height)) channels["height"] = b.height;
  json brush = {{"channels", channels}, {"hardness", b.hardness}, {"opacity", b.opacity},
                {"spacing", b.spacing}, {"mask_value", b.mask_value}};
  if (b.screen_space)
    brush["radius_px"] = b.pixel_radius;
  else
    brush["radius"] = b.radius;
  if (json pressure = pressure_curves_to_json(b); !pressure.empty()) brush["pressure"] = pressure;
  const json j = {{"format", kFormat}, {"version", 1}, {"brush", brush}};
  return j.dump(2) + "\n";
}

void write_brush_preset(const std::filesystem::path& path, const BrushSettings& brush) {
  AtomicOutput out;
  std::ofstream os(out.add(path), std::ios::binary);
  os << brush_preset_json(brush);
  os.close();
  if (!os) throw OutputError(path.string() + ": cannot write the brush preset");
  out.commit();
}

BrushSettings parse_brush_preset(const std::string& text, const std::string& name, const BrushSettings& base) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    throw IoError(name + ": not valid JSON (" + e.what() + ")");
  }
  Reader top{name + ": "};
  if (!j.is_object()) top.fail("must be a JSON object (a brush preset)");
  if (!j.contains("format") || j["format"] != kFormat)
    top.fail(std::string("\"format\" must be \"") + kFormat + "\" (not a brush preset)");
  if (!j.contains("version") || !j["version"].is_number_integer() || j["version"] != 1)
    top.fail("\"version\" must be 1");
  for (auto it = j.begin(); it != j.end(); ++it)
    if (it.key() != "format" && it.key() != "version" && it.key() != "brush") top.fail("unknown field \"" + it.key() + "\"");
  if (!j.contains("brush") || !j["brush"].is_object()) top.fail("\"brush\" must be an object");
  const Reader r{name + ": brush: "};
  BrushSettings b = base;
  for (auto it = j["brush"].begin(); it != j["brush"].end(); ++it) {
    const std::string& k = it.key();
    if (k == "channels") {
      r.channels(*it, b);
    } else if (k == "radius_px") {
      b.pixel_radius = r.number(*it, k);
      b.screen_space = true;
      if (!(b.pixel_radius >= kMinPixelRadius && b.pixel_radius <= kMaxPixelRadius))
        r.fail("\"radius_px\" must be in [1, 1000] pixels");
    } else if (k == "radius") {
      b.radius = r.number(*it, k);
      b.screen_space = false;
      if (!(b.radius >= kMinRadiusFraction && b.radius <= kMaxRadiusFraction))
        r.fail("\"radius\" must be in [0.0001, 0.5] (a fraction of the model's diagonal)");
    } else if (k == "hardness" || k == "opacity" || k == "mask_value") {
      (k == "hardness" ? b.hardness : k == "opacity" ? b.opacity : b.mask_value) = r.number(*it, k);
    } else if (k == "spacing") {
      b.spacing = r.number(*it, k);
      if (!(b.spacing >= 0.02 && b.spacing <= 2)) r.fail("\"spacing\" must be in [0.02, 2] (of the radius)");
    } else if (k == "pressure") {
      pressure_curves_from_json(*it, r.where, b);
    } else {
      r.fail("unknown field \"" + k + "\"");
    }
  }
  validate_brush(b, name);
  return b;
}

json pressure_curves_to_json(const BrushSettings& b) {
  json pressure = json::object();
  if (!b.radius_curve.points.empty()) pressure["radius"] = curve_json(b.radius_curve);
  if (!b.opacity_curve.points.empty()) pressure["opacity"] = curve_json(b.opacity_curve);
  return pressure;
}

void pressure_curves_from_json(const json& pressure, const std::string& where, BrushSettings& b) {
  const Reader r{where};
  if (!pressure.is_object()) r.fail("\"pressure\" must be an object with \"radius\" and/or \"opacity\" curves");
  b.radius_curve = b.opacity_curve = PressureCurve{};
  for (auto c = pressure.begin(); c != pressure.end(); ++c) {
    if (c.key() != "radius" && c.key() != "opacity") r.fail("\"pressure\" has an unknown curve \"" + c.key() + "\"");
    (c.key() == "radius" ? b.radius_curve : b.opacity_curve) = r.curve(*c, "pressure." + c.key());
  }
  check_curves(b, where);
}

BrushSettings read_brush_preset(const std::filesystem::path& path, const BrushSettings& base) {
  return parse_brush_preset(read_input_file(path), path.string(), base);
}

}  // namespace adaptex::studio
