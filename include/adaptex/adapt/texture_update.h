#pragma once
/// \file texture_update.h
/// Texture update after a re-parameterization (thesis §3.7.3), two modes:
/// - resample: every texel of the new texture stands for a surface point (new texel map: face +
///   barycentrics); the same face and barycentrics in the *old* parameterization give the old UV,
///   where the old texture is sampled bilinearly. The thesis' method, and the only one for a texture
///   without stroke history; it blurs a little every time.
/// - replay: a new Painter re-paints the stroke history exactly on the new parameterization
///   (no accumulated blur). The default whenever a history exists.
#include "adaptex/core/image.h"
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

/// Resamples \p old_texture (drawn with \p old_param) onto \p new_map (texel map of the new
/// parameterization, same faces). Texels outside the new charts get \p outside, then seam padding of
/// \p padding texels is applied (paint/padding.h, as the Painter does).
/// \pre old/new parameterization have the same faces as the mesh the map was built from
/// \throw InvalidInputError empty texture/map or face counts differ
ImageRGBA8 resample_texture(const Parameterization& old_param, const ImageRGBA8& old_texture,
                            const TexelMap& new_map, int padding,
                            std::array<std::uint8_t, 4> outside = {255, 255, 255, 255});

/// Replays \p history on \p new_param with a fresh Painter (exact). The Painter keeps references to
/// \p mesh and \p new_param: they must outlive it.
Painter replay_texture(const TriMesh& mesh, const Parameterization& new_param,
                       const StrokeFile& history, const PainterOptions& options);


}  // namespace adaptex
