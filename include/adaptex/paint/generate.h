#pragma once
/// \file generate.h
/// Seeded, reproducible test stroke sets on a mesh (`adaptex strokes generate`). Dabs are produced
/// by walking on the surface (a step in the tangent plane, then projection to the closest surface
/// point), spaced <= 0.4 radius apart, so every dab lies on the surface. Sizes are fractions of the
/// bounding-box diagonal d, written in world units.
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
};

/// Settings of generate_strokes().
struct GenerateOptions {
  StrokeKind kind = StrokeKind::Mixed;  ///< What to generate.
  std::uint64_t seed = 1;               ///< Same mesh + options + seed: the same file, bit for bit.
  int count = -1;                       ///< Number of strokes; -1: 60 lines, 6 blobs, 48 mixed.
  Vec3 background = Vec3(1, 1, 1);      ///< Background written to the file.
};

/// "lines" / "blobs" / "mixed" -> kind. \throw InvalidInputError anything else
StrokeKind parse_stroke_kind(const std::string& name);
/// Kind -> "lines" / "blobs" / "mixed".
std::string to_string(StrokeKind kind);

/// Generates a stroke set on \p mesh.
/// \pre mesh has faces of positive area
/// \throw InvalidInputError no face of positive area, count < 1 (other than -1)
StrokeFile generate_strokes(const TriMesh& mesh, const GenerateOptions& options = {});

}  // namespace adaptex
