#pragma once
/// \file strokes.h
/// The stroke file (`adaptex.strokes`, version 1): the exact, resolution-free record of what was
/// painted. Its semantics are the contract in shared/docs/strokes.md (mirrored in docs/strokes.md).
#include <filesystem>
#include <string>
#include <vector>

#include "adaptex/core/image.h"
#include "adaptex/core/types.h"

namespace adaptex {

/// Camera of a decal projection (thesis Figs. 4.6, 4.7).
struct DecalCamera {
  Vec3 eye = Vec3(0, 0, 1);
  Vec3 target = Vec3(0, 0, 0);
  Vec3 up = Vec3(0, 1, 0);
  double fov_y_degrees = 45.0;  ///< Vertical field of view.
  double aspect = 1.0;          ///< Width / height of the projected image.
};

/// One stroke: a brush stroke (dabs with falloff) or a decal (an image projected from a camera).
struct Stroke {
  enum class Type { Brush, Decal };
  Type type = Type::Brush;
  Vec3 color = Vec3(0, 0, 0);  ///< RGB in [0,1] (brush).
  double radius = 0.01;        ///< World units (brush).
  double hardness = 0.5;       ///< In [0,1] (brush).
  double opacity = 1.0;        ///< In [0,1] (brush and decal).
  std::vector<Vec3> dabs;      ///< Dab centres in painting order (brush).
  // --- decal ---
  std::string image_path;      ///< As written in the file (relative to the stroke file).
  ImageRGBA8 image;            ///< The loaded decal image (v = 0 is the bottom row).
  DecalCamera camera;
};

/// A whole stroke file.
struct StrokeFile {
  Vec3 background = Vec3(1, 1, 1);  ///< Colour of unpainted surface.
  std::vector<Stroke> strokes;       ///< Composited in this order.
  /// Filled by read_strokes()/parse_strokes(): one line per ignored unknown field
  /// (e.g. `s.json: stroke 2: unknown field "hardnes" ignored`). Never written.
  std::vector<std::string> warnings;

  /// Total number of brush dabs over all strokes.
  long long num_dabs() const;
};

/// Parses a stroke file strictly (unknown format, wrong version, missing fields, NaN/inf, values out
/// of range, empty dab lists, unreadable decal image all throw, naming the stroke index and field).
/// Decal images are loaded relative to the file's directory.
/// \throw IoError unreadable file or not JSON; InvalidInputError any content error
StrokeFile read_strokes(const std::filesystem::path& path);
/// Parses from a JSON string; \p name is used in messages, \p base_dir resolves decal images.
StrokeFile parse_strokes(const std::string& json, const std::string& name,
                         const std::filesystem::path& base_dir);
/// Writes a stroke file (decal image paths are written as stored). \throw OutputError
void write_strokes(const std::filesystem::path& path, const StrokeFile& strokes);

/// Checks a stroke in memory against the same rules as the parser (for strokes built in code, e.g.
/// by the desktop app). \p where prefixes the message (e.g. "stroke 3").
/// \throw InvalidInputError first violated rule, one line naming the field
void validate_stroke(const Stroke& stroke, const std::string& where);

/// The contract's falloff: 1 for t <= h, 0 for t >= 1, 1 - smoothstep in between.
double brush_falloff(double t, double hardness);

}  // namespace adaptex
