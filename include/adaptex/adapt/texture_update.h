#pragma once
/// \file texture_update.h
/// Texture update after a re-parameterization (thesis §3.7.3): exact replay of the history, or resample.
#include "adaptex/core/enum_names.h"
#include "adaptex/core/image.h"
#include "adaptex/core/progress.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/paint/painter.h"
#include "adaptex/paint/strokes.h"
#include "adaptex/paint/texel_map.h"

namespace adaptex {

/// How the texture follows a new parameterization.
enum class TextureUpdate {
  Replay,    ///< Re-paint the stroke history (exact). Default when a history exists.
  Resample,  ///< Sample the old texture through the old UVs of the same surface point.
};
/// "replay", "resample".
template <>
std::span<const EnumName<TextureUpdate>> enum_names<TextureUpdate>();

/// Resamples \p old_texture (drawn with \p old_param) onto \p new_map; \p outside elsewhere, then padding.
/// \pre same faces \throw InvalidInputError empty texture/map, or a face \p old_param lacks
ImageRGBA8 resample_texture(const Parameterization& old_param, const ImageRGBA8& old_texture,
                            const TexelMap& new_map, int padding,
                            std::array<std::uint8_t, 4> outside = {255, 255, 255, 255});

/// The texture of a new layout: Replay paints \p history into \p new_painter; Resample resamples
/// \p old_texture onto its texel map. Replay reports ("texture", k / strokes) to \p progress.
/// \throw InvalidInputError as resample_texture \throw CancelledError \p progress returned false
ImageRGBA8 update_texture(TextureUpdate mode, Painter& new_painter, const StrokeFile& history,
                          const Parameterization& old_param, const ImageRGBA8& old_texture, int padding,
                          const ProgressCallback& progress = {});

/// Strokes after a resample over \p base: C = base·(over_white − over_black) + over_black inside charts.
/// \pre all of map's size \throw InvalidInputError the sizes differ
ImageRGBA8 composite_over_base(const ImageRGBA8& base, const ImageRGBA8& over_black, const ImageRGBA8& over_white,
                               const TexelMap& map, int padding);

/// Replays \p history on \p new_param with a fresh Painter (which references \p mesh and \p new_param).
Painter replay_texture(const TriMesh& mesh, const Parameterization& new_param,
                       const StrokeFile& history, const PainterOptions& options);

}  // namespace adaptex
