#pragma once
/// \file material_strokes.h
/// The stroke file, version 2 (docs/strokes.md, "Version 2: layered materials"): layers with blend
/// modes, opacity and masks, painting five channels (base colour, alpha, roughness, metallic,
/// height) with pressure-sensitive brushes, fills and erasers. Version 1 files read as one layer.
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "adaptex/core/types.h"
#include "adaptex/paint/strokes.h"

namespace adaptex {

/// A painted channel of the material.
enum class Channel { BaseColor, Alpha, Roughness, Metallic, Height };
inline constexpr int kNumChannels = 5;
/// Components of a MaterialValue: r, g, b, alpha, roughness, metallic, height.
inline constexpr int kMaterialComponents = 7;
/// Every channel's value at a point, components in [0,1] (layout of kMaterialComponents).
using MaterialValue = std::array<double, kMaterialComponents>;

/// First component of \p c in a MaterialValue (0, 3, 4, 5, 6).
int channel_offset(Channel c);
/// Components of \p c (3 for base colour, else 1).
int channel_components(Channel c);
/// The file's name of \p c: "base_color", "alpha", "roughness", "metallic", "height".
const char* channel_name(Channel c);
/// The channel named \p name, or nothing.
std::optional<Channel> channel_from_name(std::string_view name);
/// Bit of \p c in a channel set (MaterialStroke::channels).
inline unsigned channel_bit(Channel c) { return 1u << static_cast<int>(c); }
inline constexpr unsigned kAllChannels = (1u << kNumChannels) - 1;
/// Unpainted surface: base colour white, alpha 1, roughness 0.5, metallic 0, height 0.5.
MaterialValue default_material_background();

/// How a layer combines with what lies below it (docs/strokes.md, "Blending the layers").
enum class BlendMode { Normal, Multiply, Screen, Overlay, Add, Subtract };
/// B(a, b) for backdrop component \p a and layer component \p b, both in [0,1]; result in [0,1].
double blend_component(BlendMode mode, double a, double b);
/// The file's name of \p mode ("normal", "multiply", ...).
const char* blend_mode_name(BlendMode mode);

/// Piecewise-linear map from pen pressure to a factor: control points (p_k, f_k), p from 0 to 1
/// increasing, f in [0,1]. No points: the factor is 1 at every pressure.
struct PressureCurve {
  std::vector<Vec2> points;
  /// f(\p pressure), \p pressure clamped to [0,1].
  double operator()(double pressure) const;
};

/// One stroke of a layer or of a mask.
struct MaterialStroke {
  enum class Type { Brush, Fill, Erase, Decal };
  Type type = Type::Brush;
  unsigned channels = 0;      ///< Channel bits painted (or erased) by the stroke; unused in masks.
  MaterialValue value{};      ///< Values of the painted channels (other components unused).
  /// Decal only: a painted base colour is the image's RGB at each point (`"base_color": "image"`),
  /// not value's. A parsed decal without "channels" paints base colour from the image.
  bool image_color = true;
  double mask_value = 1;      ///< Mask brush / fill only: the value painted into the mask, in [0,1].
  double radius = 0.01;       ///< Brush and erase: world units, > 0.
  double hardness = 0.5;      ///< Brush and erase: in [0,1].
  double opacity = 1;         ///< In [0,1].
  std::vector<Vec3> dabs;     ///< Brush and erase: dab centres in painting order.
  std::vector<double> pressure;  ///< Empty (every dab at pressure 1) or one pressure per dab, in [0,1].
  PressureCurve radius_curve;    ///< Pressure -> factor of radius.
  PressureCurve opacity_curve;   ///< Pressure -> factor of opacity.
  Stroke decal;               ///< Decal only: the version 1 decal stroke (image, camera, opacity).
};

/// A layer's mask: a scalar M in [0,1] that starts at `value` and is painted by its strokes.
struct LayerMask {
  double value = 1;
  std::vector<MaterialStroke> strokes;  ///< Brush and fill paint mask_value; erase paints `value` back.
};

/// One layer of the material.
struct MaterialLayer {
  std::string name;
  bool visible = true;
  double opacity = 1;  ///< In [0,1].
  BlendMode blend = BlendMode::Normal;
  std::optional<LayerMask> mask;
  std::vector<MaterialStroke> strokes;  ///< Applied in this order.
};

/// A whole stroke file of version 2 (or a version 1 file read as one).
struct MaterialStrokeFile {
  int source_version = 2;  ///< The version the file was read from (1 or 2); written files are 2.
  MaterialValue background = default_material_background();
  /// World units of displacement per unit of height; 0: the default, 1 % of the mesh's bounding-box
  /// diagonal (resolved by the code that knows the mesh).
  double height_scale = 0;
  std::vector<MaterialLayer> layers;  ///< The first is the lowest.
  /// One line per ignored unknown field, as StrokeFile::warnings. Never written.
  std::vector<std::string> warnings;
  /// Brush and erase dabs over every layer and mask.
  long long num_dabs() const;
};

/// Checks a stroke in memory against the rules of docs/strokes.md, the same rules and messages as
/// the parser (for strokes built in code, e.g. by the desktop app): values in [0,1], radius > 0 and
/// finite, finite non-empty dabs, one pressure per dab or none, curves from pressure 0 to 1 with
/// increasing pressures, at least one channel (a decal too), no decal in a mask. \p in_mask: a mask's stroke
/// (mask_value is painted, channels are unused). \p where prefixes the message (e.g. "layer 2:
/// stroke 3"; empty: no prefix).
/// \pre nothing (any stroke may be passed)
/// \throw InvalidInputError the first rule broken, one line naming the field
void validate_material_stroke(const MaterialStroke& stroke, bool in_mask, const std::string& where);
/// Checks a layer (opacity, mask value, every stroke of the layer and of its mask) as
/// validate_material_stroke() does; messages name "mask: stroke k" or "stroke k" after \p where.
/// \throw InvalidInputError the first rule broken
void validate_material_layer(const MaterialLayer& layer, const std::string& where);

/// The version 1 file \p v1 as a version 2 file (docs/strokes.md, "Reading version 1 files").
MaterialStrokeFile material_from_v1(const StrokeFile& v1);

/// Parses a stroke file of version 1 or 2 strictly (every rule of docs/strokes.md; one-line errors
/// naming the file, the layer, the stroke and the field). \p name is used in messages, \p base_dir
/// resolves decal images.
/// \throw IoError not JSON; InvalidInputError any content error
MaterialStrokeFile parse_material_strokes(const std::string& json, const std::string& name,
                                          const std::filesystem::path& base_dir);
/// A stroke file as read: version 1 (StrokeFile) or version 2 (MaterialStrokeFile).
using AnyStrokeFile = std::variant<StrokeFile, MaterialStrokeFile>;
/// Parses a file of either version once, keeping a version 1 file as read_strokes() gives it (for the
/// commands that paint version 1 exactly as before). \throw as parse_material_strokes()
AnyStrokeFile parse_any_strokes(const std::string& json, const std::string& name, const std::filesystem::path& base_dir);
/// Reads and parses \p path (decal images relative to its folder). \throw as read_material_strokes()
AnyStrokeFile read_any_strokes(const std::filesystem::path& path);

/// Reads and parses \p path (decal images relative to its folder).
/// \throw IoError unreadable file or not JSON; InvalidInputError any content error
MaterialStrokeFile read_material_strokes(const std::filesystem::path& path);
/// \p file as the text write_material_strokes() writes (a version 2 stroke file).
std::string material_strokes_json(const MaterialStrokeFile& file);
/// Writes \p file as version 2 (shortest round-trip numbers; defaults written explicitly).
/// \throw OutputError cannot write
void write_material_strokes(const std::filesystem::path& path, const MaterialStrokeFile& file);

}  // namespace adaptex
