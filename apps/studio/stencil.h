#pragma once
/// \file stencil.h
/// The decal stencil of adaptex-studio (as Blender's Texture Paint stencil): the loaded decal image
/// lies over the 3-D view as a semi-transparent preview, fixed on the screen while the model is
/// turned behind it. The user moves it (right drag), scales it (Shift + right drag) and rotates it
/// (Ctrl + right drag), and only then projects it: the decal stroke's pinhole camera
/// (adaptex::DecalCamera) looks from the view's eye through the stencil. The preview's corners are
/// the projection of that camera's image corners, so what is shown is what is projected.
#include <array>

#include "adaptex/paint/strokes.h"
#include "camera.h"

namespace adaptex::studio {

/// What a right drag does to the stencil.
enum class StencilEdit { Move, Scale, Rotate };

/// A stencil on the screen (window pixels, origin top-left, y down).
struct Stencil {
  Vec2 centre = Vec2::Zero();  ///< Window position of the image centre.
  double height = 200;         ///< On-screen height of the image at its centre, pixels (> 0).
  double angle = 0;            ///< Rotation on the screen, radians, counter-clockwise.
  double aspect = 1;           ///< Image width / height (> 0).

  /// The decal camera that projects the image as previewed, from \p view's eye.
  DecalCamera decal_camera(const Camera& view) const;
  /// Window positions of the image corners (u, v) = (0, 0), (1, 0), (1, 1), (0, 1); v = 0 is the
  /// image's bottom row (adaptex::DecalFrame).
  std::array<Vec2, 4> corners(const Camera& view) const;
  /// True if window pixel (x, y) is inside the previewed image.
  bool contains(const Camera& view, double x, double y) const;
};

/// A stencil for an image of \p aspect (width / height): centred in \p view, half its height.
Stencil fit_stencil(const Camera& view, double aspect);

/// Applies one cursor step of a right drag from (x0, y0) to (x1, y1): moves the centre by the
/// motion, scales by the ratio of the distances to the centre, or rotates by the change of the angle
/// around the centre (as Blender's stencil).
void edit_stencil(Stencil& s, StencilEdit edit, double x0, double y0, double x1, double y1);

}  // namespace adaptex::studio
