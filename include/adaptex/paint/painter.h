#pragma once
/// \file painter.h
/// Texture-space painting: every dab is evaluated exactly (stroke-file contract) at the 3-D point of
/// each texel it can touch, found through a spatial index of the texel points.
#include <memory>
#include <vector>

#include "adaptex/core/image.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/paint/strokes.h"
#include "adaptex/paint/texel_map.h"

namespace adaptex {

/// Settings of a Painter.
struct PainterOptions {
  int width = 1024;   ///< Texture width in texels (any size, power of two not required).
  int height = 1024;  ///< Texture height in texels.
  int padding = 4;    ///< Seam padding P in texels (dilation of chart texels), 0 = none.
};

/// Paints strokes into the texture of one parameterization. Keeps an exact floating-point colour
/// per texel (so 8-bit rounding never accumulates) and the RGBA8 texture derived from it.
/// Usage: whole strokes with paint_stroke(), or interactively begin_stroke/add_dab/end_stroke.
class Painter {
 public:
  /// Builds the texel map, the spatial index of texel points and the seam padding (docs/painting.md).
  /// \pre mesh and param stay alive and unchanged while the painter is used
  /// \throw InvalidInputError size outside [1, kMaxTextureSize] (core/limits.h), padding < 0, background outside [0,1],
  ///        param not parallel to mesh
  Painter(const TriMesh& mesh, const Parameterization& param, const PainterOptions& options,
          const Vec3& background = Vec3(1, 1, 1));
  /// A copy of \p other painting on \p mesh and \p param, which equal other's (copies of them, so the
  /// copy may outlive other's mesh and parameterization): the same texel map, index, colours and
  /// texture, copied rather than built again (the studio's canvas taking over a background session's).
  /// \throw InvalidInputError mesh or param differ from other's; Error other has an open stroke
  Painter(const Painter& other, const TriMesh& mesh, const Parameterization& param);
  ~Painter();
  Painter(Painter&&) noexcept;
  Painter& operator=(Painter&&) noexcept;

  /// Paints a whole stroke (brush or decal). Brush strokes with >= 16 dabs run in parallel (TBB);
  /// the result is identical to begin_stroke/add_dab/end_stroke.
  /// \throw InvalidInputError the stroke breaks the contract's rules (validate_stroke)
  /// \throw Error decal stroke without the decal module, or an interactive stroke is open
  void paint_stroke(const Stroke& stroke);
  /// Paints every stroke of a file in order (the background of \p file replaces the current one
  /// only if nothing was painted yet).
  void paint_all(const StrokeFile& file);

  /// Interactive: starts a brush stroke with the colour/radius/hardness/opacity of \p style
  /// (its dabs are ignored).
  void begin_stroke(const Stroke& style);
  /// Interactive: adds one dab to the open stroke (max coverage within the stroke).
  /// \return the texel rectangle touched, as (i0, j0, i1, j1) inclusive, grown by the padding P
  ///         (padded texels next to the touched ones change too); empty if i1 < i0.
  std::array<int, 4> add_dab(const Vec3& centre);
  /// Interactive: closes the open stroke.
  void end_stroke();

  /// Sets the colour of every chart texel at once (e.g. resampled from a surface signal cache,
  /// paint/surface_cache.h) instead of painting strokes; painting continues over these colours.
  /// \param colours shape [texel_map().inside.size()]: the colour of texel texel_map().inside[k], RGB in [0,1]
  ///        (clamped to it)
  /// \throw InvalidInputError wrong size, or a colour not finite (nothing is changed then)
  /// \throw Error an interactive stroke is open
  void fill_colours(const std::vector<Vec3f>& colours);
  /// The colour of every chart texel, the inverse of fill_colours(): another painter on the same
  /// parameterization given these colours paints on exactly as this one does. (To hand the whole
  /// painter over, the copy constructor below is cheaper: it also keeps the texel map.)
  /// \return shape [texel_map().inside.size()]: the colour of texel texel_map().inside[k], RGB in [0,1]
  /// \throw Error an interactive stroke is open (its colours are not final)
  std::vector<Vec3f> colours() const;
  /// The texture: chart texels round(255 * colour) with alpha 255; padded texels copy their source
  /// chart texel (alpha 255); other texels the background with alpha 0. Only the region changed
  /// since the last call is converted.
  const ImageRGBA8& texture();
  /// The texel -> surface map of this parameterization.
  const TexelMap& texel_map() const;
  /// Number of texel evaluations done so far (for throughput measurements).
  long long texel_updates() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace adaptex
