#pragma once
/// \file generate.h
/// Seeded, reproducible test stroke sets on a mesh (`adaptex strokes generate`). Dabs are produced
/// by walking on the surface (a step in the tangent plane, then projection to the closest surface
/// point), spaced <= 0.4 radius apart (dots: 0.5-1 radius), so every dab lies on the surface. Sizes are
/// fractions of the bounding-box diagonal d, written in world units.
#include <cstdint>
#include <string>

#include "adaptex/core/mesh.h"
#include "adaptex/paint/strokes.h"

namespace adaptex {

/// Kind of generated stroke set.
enum class StrokeKind {
  Lines,  ///< Many thin hard strokes in one region: radius 0.2-0.5% d, hardness 0.8-1, length 5-15% d,
          ///< starting within 12% d of one random surface point.
  Blobs,  ///< A few broad soft strokes anywhere: radius 4-10% d, hardness 0-0.3, opacity 0.4-0.8.
  Mixed,  ///< Blobs first (1/8 of the count, at least 1), then lines on top.
  Dots,   ///< Speckle (text-like): 150-400 tiny hard dots sprinkled in one region, a Euclidean ball around
          ///< a random surface point holding 10-20% of the surface area. Each dot is 1-3 dabs (a dab
          ///< 0.5-1 radius from the previous one); radius 0.1-0.2% d (0.3-0.6x the mean lines radius),
          ///< hardness 0.8-1, opacity 1, saturated colours (saturation 0.8-1, value 0.6-1).
};

/// Settings of generate_strokes().
struct GenerateOptions {
  StrokeKind kind = StrokeKind::Mixed;  ///< What to generate.
  std::uint64_t seed = 1;               ///< Same mesh + options + seed: the same file, bit for bit.
  int count = -1;  ///< Number of strokes; -1: 60 lines, 6 blobs, 48 mixed, 150-400 dots (drawn from the seed).
  Vec3 background = Vec3(1, 1, 1);      ///< Background written to the file.
};

/// The region a Dots set is confined to: every dab centre p satisfies |p - centre| <= radius.
struct GeneratedRegion {
  Vec3 centre = Vec3::Zero();  ///< A surface point (world units).
  double radius = 0;           ///< Ball radius (world units); 0 when the kind has no such region.
  double area_fraction = 0;    ///< Target share of the surface area inside the ball, in [0.1, 0.2].
};

/// "lines" / "blobs" / "mixed" / "dots" -> kind. \throw InvalidInputError anything else
StrokeKind parse_stroke_kind(const std::string& name);
/// Kind -> "lines" / "blobs" / "mixed" / "dots".
std::string to_string(StrokeKind kind);

/// Generates a stroke set on \p mesh.
/// \param region if not null, receives the ball of a Dots set (radius 0 for the other kinds)
/// \pre mesh has faces of positive area
/// \throw InvalidInputError no face of positive area, count < 1 (other than -1)
StrokeFile generate_strokes(const TriMesh& mesh, const GenerateOptions& options = {},
                            GeneratedRegion* region = nullptr);

}  // namespace adaptex
