/// \file material_strokes.cpp
/// Strict reader / writer of the stroke file version 2 (docs/strokes.md, "Version 2: layered
/// materials"); version 1 files go through the version 1 reader and are converted.
#include "adaptex/paint/material_strokes.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "adaptex/io/input_file.h"
#include "json_fields.h"

namespace adaptex {

using namespace detail;  // NOLINT: the shared field readers

namespace {

constexpr const char* kChannelNames[kNumChannels] = {"base_color", "alpha", "roughness", "metallic", "height"};
constexpr const char* kBlendNames[] = {"normal", "multiply", "screen", "overlay", "add", "subtract"};
constexpr int kNumBlendModes = 6;

std::string quoted_list(const char* const* names, int n) {
  std::string s;
  for (int k = 0; k < n; ++k) s += std::string(k ? ", " : "") + "\"" + names[k] + "\"";
  return s;
}

void check_unit(double x, const std::string& field, const Where& w) {
  if (!(x >= 0 && x <= 1)) w.fail("\"" + field + "\" must be in [0, 1] (got " + num(x) + ")");
}

/// The values of the channels in \p bits are in [0,1] (messages name "channels.<name>").
void check_channel_values(unsigned bits, const MaterialValue& v, const Where& w) {
  for (int c = 0; c < kNumChannels; ++c) {
    const auto ch = static_cast<Channel>(c);
    if (!(bits & channel_bit(ch))) continue;
    const std::string field = std::string("channels.") + kChannelNames[c];
    const int o = channel_offset(ch);
    if (ch != Channel::BaseColor) {
      check_unit(v[o], field, w);
      continue;
    }
    for (int k = 0; k < 3; ++k)
      if (!(v[o + k] >= 0 && v[o + k] <= 1))
        w.fail("\"" + field + "\"[" + std::to_string(k) + "] must be in [0, 1] (got " + num(v[o + k]) + ")");
  }
}

/// A pressure curve: none, or points in [0,1]^2 with increasing pressures from 0 to 1.
void check_curve(const PressureCurve& curve, const std::string& field, const Where& w) {
  if (curve.points.empty()) return;
  if (curve.points.size() < 2) w.fail("\"" + field + "\" must have at least 2 [pressure, factor] points");
  for (size_t k = 0; k < curve.points.size(); ++k) {
    const std::string f = field + "[" + std::to_string(k) + "]";
    check_unit(curve.points[k].x(), f + "[0]", w);
    check_unit(curve.points[k].y(), f + "[1]", w);
    if (k > 0 && !(curve.points[k].x() > curve.points[k - 1].x()))
      w.fail("\"" + field + "\" pressures must increase (point " + std::to_string(k) + ")");
  }
  if (curve.points.front().x() != 0 || curve.points.back().x() != 1)
    w.fail("\"" + field + "\" must start at pressure 0 and end at pressure 1");
}

/// Radius, hardness, dabs, pressures and curves of a brush or an eraser.
void check_dab_fields(const MaterialStroke& s, const Where& w) {
  if (!std::isfinite(s.radius)) w.fail("\"radius\" must be finite (got " + num(s.radius) + ")");
  if (!(s.radius > 0)) w.fail("\"radius\" must be > 0 (got " + num(s.radius) + ")");
  check_unit(s.hardness, "hardness", w);
  if (s.dabs.empty()) w.fail("\"dabs\" must not be empty");
  if (!s.pressure.empty() && s.pressure.size() != s.dabs.size())
    w.fail("\"dabs\": every dab must have a pressure, or none (" + std::to_string(s.pressure.size()) +
           " pressures for " + std::to_string(s.dabs.size()) + " dabs)");
  for (size_t k = 0; k < s.dabs.size(); ++k) {
    const std::string f = "dabs[" + std::to_string(k) + "]";
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(s.dabs[k][c]))
        w.fail("\"" + f + "[" + std::to_string(c) + "]\" must be finite (got " + num(s.dabs[k][c]) + ")");
    if (!s.pressure.empty()) check_unit(s.pressure[k], f + "[3]", w);
  }
  check_curve(s.radius_curve, "pressure.radius", w);
  check_curve(s.opacity_curve, "pressure.opacity", w);
}

/// At least one channel bit and no other.
void check_channel_bits(unsigned bits, const Where& w) {
  if ((bits & kAllChannels) == 0 || (bits & ~kAllChannels) != 0)
    w.fail("\"channels\" must name at least one of " + quoted_list(kChannelNames, kNumChannels) + " and no other");
}

void check_material_stroke(const MaterialStroke& s, bool in_mask, const Where& w) {
  using T = MaterialStroke::Type;
  if (s.type == T::Decal) {
    if (in_mask) w.fail("\"type\" must be \"brush\", \"fill\" or \"erase\" in a mask (got \"decal\")");
    validate_stroke(s.decal, w.prefix.empty() ? std::string() : w.prefix.substr(0, w.prefix.size() - 2));
    if (s.opacity != s.decal.opacity) w.fail("\"opacity\" of a decal must equal its image's opacity");
    check_channel_bits(s.channels, w);
    // A base colour from the image has no value of its own to check.
    check_channel_values(s.image_color ? s.channels & ~channel_bit(Channel::BaseColor) : s.channels, s.value, w);
    return;
  }
  check_unit(s.opacity, "opacity", w);
  if (in_mask) {
    if (s.type != T::Erase) check_unit(s.mask_value, "value", w);
  } else {
    check_channel_bits(s.channels, w);
    if (s.type != T::Erase) check_channel_values(s.channels, s.value, w);
  }
  if (s.type != T::Fill) check_dab_fields(s, w);
}

/// "channels": {"base_color": [r, g, b], "roughness": 0.3, ...} (at least one channel). \p decal: a
/// decal's, whose "base_color" may also be the string "image" (MaterialStroke::image_color).
void parse_channel_values(const json& js, MaterialStroke& s, const Where& w, bool decal = false) {
  if (!js.is_object() || js.empty())
    w.fail("\"channels\" must be an object with at least one of " + quoted_list(kChannelNames, kNumChannels) +
           " (got " + (js.is_object() ? std::string("an empty object") : describe(js)) + ")");
  for (auto it = js.begin(); it != js.end(); ++it) {
    const auto c = channel_from_name(it.key());
    if (!c) w.fail("unknown channel \"" + it.key() + "\"");
    const std::string field = "channels." + it.key();
    const int o = channel_offset(*c);
    if (*c == Channel::BaseColor && decal && it->is_string()) {
      if (it->get<std::string>() != "image")
        w.fail("\"" + field + "\" must be \"image\" or an array of 3 numbers in [0, 1] (got " + describe(*it) + ")");
      s.image_color = true;
    } else if (*c == Channel::BaseColor) {
      const Vec3 rgb = get_vec3(*it, field, w);
      for (int k = 0; k < 3; ++k) s.value[o + k] = rgb[k];
      if (decal) s.image_color = false;
    } else {
      s.value[o] = get_number(*it, field, w);
    }
    s.channels |= channel_bit(*c);
  }
}

/// An eraser's "channels": an array of names (missing: every channel).
unsigned parse_channel_names(const json& js, const Where& w) {
  if (!js.is_array() || js.empty())
    w.fail("\"channels\" of an eraser must be a non-empty array of channel names (got " + describe(js) + ")");
  unsigned bits = 0;
  for (const json& v : js) {
    const auto c = v.is_string() ? channel_from_name(v.get<std::string>()) : std::nullopt;
    if (!c) w.fail("unknown channel " + describe(v) + " (channels are " + quoted_list(kChannelNames, kNumChannels) + ")");
    bits |= channel_bit(*c);
  }
  return bits;
}

PressureCurve parse_curve(const json& js, const std::string& field, const Where& w) {
  if (!js.is_array() || js.size() < 2)
    w.fail("\"" + field + "\" must be an array of at least 2 [pressure, factor] points (got " + describe(js) + ")");
  PressureCurve curve;
  for (size_t k = 0; k < js.size(); ++k) {
    const std::string f = field + "[" + std::to_string(k) + "]";
    if (!js[k].is_array() || js[k].size() != 2) w.fail("\"" + f + "\" must be a [pressure, factor] pair");
    curve.points.emplace_back(get_number(js[k][0], f + "[0]", w), get_number(js[k][1], f + "[1]", w));
  }
  return curve;  // the ranges and the order: check_curve()
}

/// "dabs" of [x, y, z] or [x, y, z, pressure]: all with pressure or all without.
void parse_dabs(const json& js, MaterialStroke& s, const Where& w) {
  if (!js.is_array()) w.fail("\"dabs\" must be an array of [x, y, z] or [x, y, z, pressure] points (got " + describe(js) + ")");
  if (js.empty()) w.fail("\"dabs\" must not be empty");
  s.dabs.reserve(js.size());
  for (size_t k = 0; k < js.size(); ++k) {
    const std::string f = "dabs[" + std::to_string(k) + "]";
    const json& d = js[k];
    if (!d.is_array() || (d.size() != 3 && d.size() != 4))
      w.fail("\"" + f + "\" must be an array of 3 or 4 finite numbers (got " +
             (d.is_array() ? "an array of " + std::to_string(d.size()) : describe(d)) + ")");
    Vec3 p;
    for (int c = 0; c < 3; ++c) p[c] = get_number(d[c], f + "[" + std::to_string(c) + "]", w);
    s.dabs.push_back(p);
    if ((d.size() == 4) != (k == 0 ? d.size() == 4 : !s.pressure.empty()))
      w.fail("\"" + f + "\": every dab must have a pressure, or none");
    if (d.size() == 4) s.pressure.push_back(get_number(d[3], f + "[3]", w));
  }
}

/// Radius, hardness, opacity, dabs and pressure curves of a brush or an eraser.
void parse_dab_fields(const json& js, MaterialStroke& s, const Where& w) {
  s.radius = get_number(require(js, "radius", w), "radius", w);
  if (auto it = js.find("hardness"); it != js.end()) s.hardness = get_number(*it, "hardness", w);
  parse_dabs(require(js, "dabs", w), s, w);
  if (auto it = js.find("pressure"); it != js.end()) {
    if (!it->is_object()) w.fail("\"pressure\" must be an object with \"radius\" and/or \"opacity\" curves");
    for (auto c = it->begin(); c != it->end(); ++c) {
      if (c.key() == "radius")
        s.radius_curve = parse_curve(*c, "pressure.radius", w);
      else if (c.key() == "opacity")
        s.opacity_curve = parse_curve(*c, "pressure.opacity", w);
      else
        w.fail("\"pressure\" has an unknown curve \"" + c.key() + "\" (curves are \"radius\", \"opacity\")");
    }
  }
}

MaterialStroke::Type parse_type(const json& js, bool in_mask, const Where& w) {
  const char* allowed = in_mask ? "\"brush\", \"fill\" or \"erase\"" : "\"brush\", \"fill\", \"erase\" or \"decal\"";
  auto it = js.find("type");
  if (it == js.end()) return MaterialStroke::Type::Brush;
  const std::string t = it->is_string() ? it->get<std::string>() : std::string();
  if (t == "brush") return MaterialStroke::Type::Brush;
  if (t == "fill") return MaterialStroke::Type::Fill;
  if (t == "erase") return MaterialStroke::Type::Erase;
  if (t == "decal" && !in_mask) return MaterialStroke::Type::Decal;
  w.fail(std::string("\"type\" must be ") + allowed + " (got " + describe(*it) + ")");
}

MaterialStroke parse_material_stroke(const json& js, bool in_mask, const Where& w, const std::filesystem::path& base_dir,
                                     std::vector<std::string>& warnings) {
  if (!js.is_object()) w.fail("must be a JSON object (got " + describe(js) + ")");
  MaterialStroke s;
  s.type = parse_type(js, in_mask, w);
  if (s.type == MaterialStroke::Type::Decal) {
    // "channels" (version 2's) before the image is read, so that the fuzzer reaches them without one.
    if (auto it = js.find("channels"); it != js.end())
      parse_channel_values(*it, s, w, true);
    else
      s.channels = channel_bit(Channel::BaseColor);  // {"base_color": "image"}
    json camera = js;  // the version 1 decal's fields
    camera.erase("channels");
    s.decal = parse_v1_stroke(camera, w, base_dir, warnings);
    s.opacity = s.decal.opacity;
    check_material_stroke(s, in_mask, w);
    return s;
  }
  if (auto it = js.find("opacity"); it != js.end()) s.opacity = get_number(*it, "opacity", w);
  const bool dabs = s.type != MaterialStroke::Type::Fill;
  std::set<std::string> known = {"type", "opacity", in_mask ? "value" : "channels"};
  if (dabs) known.insert({"radius", "hardness", "dabs", "pressure"});
  warn_unknown(js, known, w, warnings);
  if (in_mask) {
    if (s.type != MaterialStroke::Type::Erase) s.mask_value = get_number(require(js, "value", w), "value", w);
  } else if (s.type == MaterialStroke::Type::Erase) {
    auto it = js.find("channels");
    s.channels = it == js.end() ? kAllChannels : parse_channel_names(*it, w);
  } else {
    parse_channel_values(require(js, "channels", w), s, w);
  }
  if (dabs) parse_dab_fields(js, s, w);
  check_material_stroke(s, in_mask, w);  // the ranges and rules, as for strokes built in memory
  return s;
}

std::vector<MaterialStroke> parse_stroke_list(const json& js, bool in_mask, const std::string& prefix, const Where& w,
                                              const std::filesystem::path& base_dir, std::vector<std::string>& warnings) {
  if (!js.is_array()) w.fail("\"strokes\" must be an array (got " + describe(js) + ")");
  std::vector<MaterialStroke> out;
  out.reserve(js.size());
  for (size_t k = 0; k < js.size(); ++k)
    out.push_back(parse_material_stroke(js[k], in_mask, Where{prefix + "stroke " + std::to_string(k) + ": "}, base_dir,
                                        warnings));
  return out;
}

LayerMask parse_mask(const json& js, const std::string& prefix, const std::filesystem::path& base_dir,
                     std::vector<std::string>& warnings) {
  const Where w{prefix};
  if (!js.is_object()) w.fail("\"mask\" must be an object with \"value\" and \"strokes\" (got " + describe(js) + ")");
  warn_unknown(js, {"value", "strokes"}, w, warnings);
  LayerMask mask;
  if (auto it = js.find("value"); it != js.end()) mask.value = get_in_range(*it, "mask.value", 0, 1, w);
  if (auto it = js.find("strokes"); it != js.end())
    mask.strokes = parse_stroke_list(*it, true, prefix + "mask: ", w, base_dir, warnings);
  return mask;
}

MaterialLayer parse_layer(const json& js, size_t index, const std::string& name, const std::filesystem::path& base_dir,
                          std::vector<std::string>& warnings) {
  const std::string prefix = name + ": layer " + std::to_string(index) + ": ";
  const Where w{prefix};
  if (!js.is_object()) w.fail("must be a JSON object (got " + describe(js) + ")");
  warn_unknown(js, {"name", "visible", "opacity", "blend", "mask", "strokes"}, w, warnings);
  MaterialLayer layer;
  layer.name = "Layer " + std::to_string(index + 1);
  if (auto it = js.find("name"); it != js.end()) {
    if (!it->is_string()) w.fail("\"name\" must be a string (got " + describe(*it) + ")");
    layer.name = it->get<std::string>();
  }
  if (auto it = js.find("visible"); it != js.end()) {
    if (!it->is_boolean()) w.fail("\"visible\" must be true or false (got " + describe(*it) + ")");
    layer.visible = it->get<bool>();
  }
  if (auto it = js.find("opacity"); it != js.end()) layer.opacity = get_in_range(*it, "opacity", 0, 1, w);
  if (auto it = js.find("blend"); it != js.end()) {
    const std::string b = it->is_string() ? it->get<std::string>() : std::string();
    const auto* found = std::find_if(kBlendNames, kBlendNames + kNumBlendModes, [&](const char* n) { return b == n; });
    if (found == kBlendNames + kNumBlendModes)
      w.fail("\"blend\" must be one of " + quoted_list(kBlendNames, kNumBlendModes) + " (got " + describe(*it) + ")");
    layer.blend = static_cast<BlendMode>(found - kBlendNames);
  }
  if (auto it = js.find("mask"); it != js.end()) layer.mask = parse_mask(*it, prefix, base_dir, warnings);
  layer.strokes = parse_stroke_list(require(js, "strokes", w), false, prefix, w, base_dir, warnings);
  return layer;
}

MaterialValue parse_background(const json& js, const Where& w) {
  MaterialValue bg = default_material_background();
  if (!js.is_object()) w.fail("\"background\" must be an object of channel values (got " + describe(js) + ")");
  MaterialStroke values;
  if (!js.empty()) parse_channel_values(js, values, w);
  check_channel_values(values.channels, values.value, w);
  for (int c = 0; c < kNumChannels; ++c)
    if (values.channels & channel_bit(static_cast<Channel>(c)))
      for (int k = 0; k < channel_components(static_cast<Channel>(c)); ++k)
        bg[channel_offset(static_cast<Channel>(c)) + k] = values.value[channel_offset(static_cast<Channel>(c)) + k];
  return bg;
}

}  // namespace

int channel_offset(Channel c) { return c == Channel::BaseColor ? 0 : static_cast<int>(c) + 2; }
int channel_components(Channel c) { return c == Channel::BaseColor ? 3 : 1; }
const char* channel_name(Channel c) { return kChannelNames[static_cast<int>(c)]; }
std::optional<Channel> channel_from_name(std::string_view name) {
  for (int c = 0; c < kNumChannels; ++c)
    if (name == kChannelNames[c]) return static_cast<Channel>(c);
  return std::nullopt;
}
MaterialValue default_material_background() { return {1, 1, 1, 1, 0.5, 0, 0.5}; }
const char* blend_mode_name(BlendMode mode) { return kBlendNames[static_cast<int>(mode)]; }

double blend_component(BlendMode mode, double a, double b) {
  switch (mode) {
    case BlendMode::Normal: return b;
    case BlendMode::Multiply: return a * b;
    case BlendMode::Screen: return 1 - (1 - a) * (1 - b);
    case BlendMode::Overlay: return a <= 0.5 ? 2 * a * b : 1 - 2 * (1 - a) * (1 - b);
    case BlendMode::Add: return std::min(1.0, a + b);
    case BlendMode::Subtract: return std::max(0.0, a - b);
  }
  return b;
}

double PressureCurve::operator()(double pressure) const {
  if (points.empty()) return 1;
  const double p = std::clamp(pressure, 0.0, 1.0);
  size_t k = 1;
  while (k + 1 < points.size() && points[k].x() < p) ++k;
  const Vec2 a = points[k - 1], b = points[k];
  const double t = (p - a.x()) / (b.x() - a.x());
  return a.y() + std::clamp(t, 0.0, 1.0) * (b.y() - a.y());
}

long long MaterialStrokeFile::num_dabs() const {
  long long n = 0;
  for (const MaterialLayer& l : layers) {
    for (const MaterialStroke& s : l.strokes) n += static_cast<long long>(s.dabs.size());
    if (l.mask)
      for (const MaterialStroke& s : l.mask->strokes) n += static_cast<long long>(s.dabs.size());
  }
  return n;
}

void validate_material_stroke(const MaterialStroke& stroke, bool in_mask, const std::string& where) {
  check_material_stroke(stroke, in_mask, Where{where.empty() ? std::string() : where + ": "});
}

void validate_material_layer(const MaterialLayer& layer, const std::string& where) {
  const std::string prefix = where.empty() ? std::string() : where + ": ";
  check_unit(layer.opacity, "opacity", Where{prefix});
  if (layer.mask) {
    check_unit(layer.mask->value, "mask.value", Where{prefix});
    for (size_t k = 0; k < layer.mask->strokes.size(); ++k)
      check_material_stroke(layer.mask->strokes[k], true, Where{prefix + "mask: stroke " + std::to_string(k) + ": "});
  }
  for (size_t k = 0; k < layer.strokes.size(); ++k)
    check_material_stroke(layer.strokes[k], false, Where{prefix + "stroke " + std::to_string(k) + ": "});
}

MaterialStrokeFile material_from_v1(const StrokeFile& v1) {
  MaterialStrokeFile out;
  out.source_version = 1;
  for (int k = 0; k < 3; ++k) out.background[k] = v1.background[k];
  out.warnings = v1.warnings;
  MaterialLayer layer;
  layer.name = "Layer 1";
  layer.strokes.reserve(v1.strokes.size());
  for (const Stroke& s : v1.strokes) {
    MaterialStroke m;
    m.channels = channel_bit(Channel::BaseColor);
    m.opacity = s.opacity;
    if (s.type == Stroke::Type::Decal) {
      m.type = MaterialStroke::Type::Decal;
      m.decal = s;
    } else {
      for (int k = 0; k < 3; ++k) m.value[k] = s.color[k];
      m.radius = s.radius;
      m.hardness = s.hardness;
      m.dabs = s.dabs;
    }
    layer.strokes.push_back(std::move(m));
  }
  out.layers.push_back(std::move(layer));
  return out;
}

namespace {

/// A version 2 file from its parsed JSON.
MaterialStrokeFile material_from_json(const json& js, const std::string& name, const std::filesystem::path& base_dir) {
  const Where top{name + ": "};
  MaterialStrokeFile out;
  warn_unknown(js, {"format", "version", "background", "height_scale", "layers"}, top, out.warnings);
  if (auto it = js.find("background"); it != js.end()) out.background = parse_background(*it, top);
  if (auto it = js.find("height_scale"); it != js.end()) {
    out.height_scale = get_number(*it, "height_scale", top);
    if (!(out.height_scale > 0)) top.fail("\"height_scale\" must be > 0 (got " + num(out.height_scale) + ")");
  }
  if (!js.contains("layers") && js.contains("strokes"))
    top.fail("missing required field \"layers\" (a version 2 file holds layers; a list of \"strokes\" is version 1)");
  const json& layers = require(js, "layers", top);
  if (!layers.is_array()) top.fail("\"layers\" must be an array (got " + describe(layers) + ")");
  for (size_t k = 0; k < layers.size(); ++k) out.layers.push_back(parse_layer(layers[k], k, name, base_dir, out.warnings));
  return out;
}

}  // namespace

AnyStrokeFile parse_any_strokes(const std::string& text, const std::string& name, const std::filesystem::path& base_dir) {
  const json js = parse_stroke_json(text, name);
  const Where top{name + ": "};
  const json& version = stroke_file_version(js, top);
  const long long v = version.is_number_integer() ? version.get<long long>() : 0;
  if (v == 1) return strokes_from_json(js, name, base_dir);
  if (v != 2) top.fail("\"version\" must be 1 or 2 (got " + describe(version) + ")");
  return material_from_json(js, name, base_dir);
}

AnyStrokeFile read_any_strokes(const std::filesystem::path& path) {
  return parse_any_strokes(read_input_file(path), path.string(), path.parent_path());
}

MaterialStrokeFile parse_material_strokes(const std::string& text, const std::string& name,
                                          const std::filesystem::path& base_dir) {
  AnyStrokeFile any = parse_any_strokes(text, name, base_dir);
  if (const StrokeFile* v1 = std::get_if<StrokeFile>(&any)) return material_from_v1(*v1);
  return std::get<MaterialStrokeFile>(std::move(any));
}

MaterialStrokeFile read_material_strokes(const std::filesystem::path& path) {
  return parse_material_strokes(read_input_file(path), path.string(), path.parent_path());
}

namespace {

/// \p image_color: a decal's base colour, written as "image".
void put_channels(std::ostream& os, unsigned bits, const MaterialValue& v, bool image_color = false) {
  os << '{';
  bool first = true;
  for (int c = 0; c < kNumChannels; ++c) {
    const auto ch = static_cast<Channel>(c);
    if (!(bits & channel_bit(ch))) continue;
    os << (first ? "" : ", ") << '"' << channel_name(ch) << "\": ";
    first = false;
    const int o = channel_offset(ch);
    if (ch == Channel::BaseColor && image_color)
      os << "\"image\"";
    else if (ch == Channel::BaseColor)
      put_vec(os, Vec3(v[o], v[o + 1], v[o + 2]));
    else
      os << num(v[o]);
  }
  os << '}';
}

void put_curve(std::ostream& os, const PressureCurve& c) {
  os << '[';
  for (size_t k = 0; k < c.points.size(); ++k) os << (k ? ", [" : "[") << num(c.points[k].x()) << ", " << num(c.points[k].y()) << ']';
  os << ']';
}

void put_dabs(std::ostream& os, const MaterialStroke& s) {
  os << ", \"radius\": " << num(s.radius) << ", \"hardness\": " << num(s.hardness);
  if (!s.radius_curve.points.empty() || !s.opacity_curve.points.empty()) {
    os << ", \"pressure\": {";
    if (!s.radius_curve.points.empty()) os << "\"radius\": ", put_curve(os, s.radius_curve);
    if (!s.opacity_curve.points.empty())
      os << (s.radius_curve.points.empty() ? "" : ", ") << "\"opacity\": ", put_curve(os, s.opacity_curve);
    os << '}';
  }
  os << ",\n         \"dabs\": [";
  for (size_t d = 0; d < s.dabs.size(); ++d) {
    os << (d == 0 ? "" : (d % 4 == 0 ? ",\n                  " : ", ")) << '[' << num(s.dabs[d][0]) << ", "
       << num(s.dabs[d][1]) << ", " << num(s.dabs[d][2]);
    if (!s.pressure.empty()) os << ", " << num(s.pressure[d]);
    os << ']';
  }
  os << ']';
}

void put_stroke(std::ostream& os, const MaterialStroke& s, bool in_mask) {
  using T = MaterialStroke::Type;
  if (s.type == T::Decal) {
    os << '{';
    put_decal(os, s.decal);
    if (s.channels != channel_bit(Channel::BaseColor) || !s.image_color) {  // else the default: not written
      os << ", \"channels\": ";
      put_channels(os, s.channels, s.value, s.image_color);
    }
    os << '}';
    return;
  }
  os << "{\"type\": \"" << (s.type == T::Brush ? "brush" : s.type == T::Fill ? "fill" : "erase") << '"';
  if (in_mask) {
    if (s.type != T::Erase) os << ", \"value\": " << num(s.mask_value);
  } else if (s.type == T::Erase) {
    os << ", \"channels\": [";
    bool first = true;
    for (int c = 0; c < kNumChannels; ++c)
      if (s.channels & channel_bit(static_cast<Channel>(c)))
        os << (first ? "" : ", ") << '"' << kChannelNames[c] << '"', first = false;
    os << ']';
  } else {
    os << ", \"channels\": ";
    put_channels(os, s.channels, s.value);
  }
  os << ", \"opacity\": " << num(s.opacity);
  if (s.type != T::Fill) put_dabs(os, s);
  os << '}';
}

void put_strokes(std::ostream& os, const std::vector<MaterialStroke>& strokes, bool in_mask) {
  os << '[';
  for (size_t k = 0; k < strokes.size(); ++k) {
    os << (k ? ",\n        " : "\n        ");
    put_stroke(os, strokes[k], in_mask);
  }
  os << (strokes.empty() ? "]" : "\n      ]");
}

}  // namespace

namespace {
void put_material_file(std::ostream& os, const MaterialStrokeFile& file) {
  os << "{\n  \"format\": \"adaptex.strokes\",\n  \"version\": 2,\n  \"background\": ";
  put_channels(os, kAllChannels, file.background);
  if (file.height_scale > 0) os << ",\n  \"height_scale\": " << num(file.height_scale);
  os << ",\n  \"layers\": [";
  for (size_t k = 0; k < file.layers.size(); ++k) {
    const MaterialLayer& l = file.layers[k];
    os << (k ? ",\n" : "\n") << "    {\"name\": " << json(l.name).dump() << ", \"visible\": " << (l.visible ? "true" : "false")
       << ", \"opacity\": " << num(l.opacity) << ", \"blend\": \"" << blend_mode_name(l.blend) << '"';
    if (l.mask) {
      os << ",\n      \"mask\": {\"value\": " << num(l.mask->value) << ", \"strokes\": ";
      put_strokes(os, l.mask->strokes, true);
      os << '}';
    }
    os << ",\n      \"strokes\": ";
    put_strokes(os, l.strokes, false);
    os << '}';
  }
  os << (file.layers.empty() ? "]\n}\n" : "\n  ]\n}\n");
}
}  // namespace

std::string material_strokes_json(const MaterialStrokeFile& file) {
  std::ostringstream os;
  put_material_file(os, file);
  return os.str();
}

void write_material_strokes(const std::filesystem::path& path, const MaterialStrokeFile& file) {
  std::ofstream os(path, std::ios::binary);
  if (!os) throw OutputError(path.string() + ": cannot open for writing");
  put_material_file(os, file);
  os.flush();
  if (!os) throw OutputError(path.string() + ": write error");
}

}  // namespace adaptex
