#pragma once
/// \file texture_update.h
/// Texture update after a re-parameterization (thesis §3.7.3), two modes:
/// - resample: every texel of the new texture stands for a surface point (new texel map: face +
///   barycentrics); the same face and barycentrics in the *old* parameterization give the old UV,
///   where the old texture is sampled bilinearly. The thesis' method, and the only one for a texture
///   without stroke history; it blurs a little every time.
/// - replay: a new Painter re-paints the stroke history exactly on the new parameterization
///   (no accumulated blur). The default whenever a history exists.
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

/// Resamples \p old_texture (drawn with \p old_param) onto \p new_map (texel map of the new
/// parameterization, same faces). Texels outside the new charts get \p outside, then seam padding of
/// \p padding texels is applied (paint/padding.h, as the Painter does).
/// \pre old/new parameterization have the same faces as the mesh the map was built from
/// \throw InvalidInputError empty texture/map, or the map covers a face that \p old_param lacks
ImageRGBA8 resample_texture(const Parameterization& old_param, const ImageRGBA8& old_texture,
                            const TexelMap& new_map, int padding,
                            std::array<std::uint8_t, 4> outside = {255, 255, 255, 255});

/// The texture of a layout whose Painter \p new_painter was just built: \p mode Replay paints
/// \p history into \p new_painter and returns its texture; Resample returns \p old_texture (drawn
/// with \p old_param) resampled onto the painter's texel map, texels outside the charts in
/// \p history's background (alpha 0), then \p padding texels of seam padding; the painter stays blank.
/// Replay reports ("texture", k / strokes) to \p progress before each stroke k, so a long replay can
/// be cancelled.
/// \pre old_param and the painter's layout have the same faces (Resample)
/// \throw InvalidInputError as resample_texture; CancelledError \p progress returned false
ImageRGBA8 update_texture(TextureUpdate mode, Painter& new_painter, const StrokeFile& history,
                          const Parameterization& old_param, const ImageRGBA8& old_texture, int padding,
                          const ProgressCallback& progress = {});

/// Resample mode's view of strokes painted after a resample (thesis §3.7.3 keeps painting on the
/// resampled texture): \p base is the resampled texture, \p over_black / \p over_white the same
/// strokes painted on black / white. Compositing is affine in the colour underneath, so with
/// S = over_black and T = over_white - S the result is C = base * T + S on every texel inside a chart
/// of \p map (RGB), then \p padding texels of seam padding.
/// \pre base, over_black, over_white have map's size
/// \throw InvalidInputError the sizes differ
ImageRGBA8 composite_over_base(const ImageRGBA8& base, const ImageRGBA8& over_black, const ImageRGBA8& over_white,
                               const TexelMap& map, int padding);

/// Replays \p history on \p new_param with a fresh Painter (exact). The Painter keeps references to
/// \p mesh and \p new_param: they must outlive it.
Painter replay_texture(const TriMesh& mesh, const Parameterization& new_param,
                       const StrokeFile& history, const PainterOptions& options);

}  // namespace adaptex
