#pragma once
/// \file brush.h
/// The brush radius of adaptex-studio. Screen-space by default (BrushSettings::pixel_radius: the
/// brush keeps its size on the screen while zooming, as Blender's and Substance Painter's default),
/// world-space as an option (BrushSettings::radius, a fraction of the model's diagonal). A stroke
/// records one world radius (the stroke-file contract): a screen-space stroke takes it at the depth of
/// its first dab. Also Blender's interactive resize (F, move the mouse, click).
#include <optional>

#include "camera.h"
#include "settings.h"

namespace adaptex::studio {

/// A circle on the screen (window pixels, y down).
struct ScreenCircle {
  Vec2 centre = Vec2::Zero();
  double radius = 0;
};

/// Limits of the two radii.
inline constexpr double kMinPixelRadius = 1, kMaxPixelRadius = 1000;
inline constexpr double kMinRadiusFraction = 1e-4, kMaxRadiusFraction = 0.5;

/// World radius of \p b at surface point \p at of a model with bounding-box \p diagonal.
double brush_world_radius(const BrushSettings& b, const Camera& view, const Vec3& at, double diagonal);
/// On-screen radius (pixels) of \p b at \p at.
double brush_screen_radius(const BrushSettings& b, const Camera& view, const Vec3& at, double diagonal);
/// Sets the active radius of \p b so that it is \p pixels on the screen at \p at (clamped to the limits).
void set_brush_screen_radius(BrushSettings& b, double pixels, const Camera& view, const Vec3& at, double diagonal);
/// `[` / `]`: multiplies the active radius by \p factor (clamped to the limits).
void scale_brush(BrushSettings& b, double factor);

/// Blender's F resize: the circle stays where it was, its radius follows the cursor's distance.
struct BrushResize {
  Vec2 centre = Vec2::Zero();  ///< Window position of the circle's centre.
  Vec3 at = Vec3::Zero();      ///< The surface point whose depth converts pixels to world units.
  BrushSettings before;        ///< Restored when the resize is cancelled.
  double pixels = 0;           ///< The current on-screen radius.
};

/// Starts a resize with the cursor at (x, y) on the circle's right edge (the circle does not jump).
BrushResize begin_brush_resize(const BrushSettings& b, const Camera& view, const Vec3& at, double diagonal,
                               double x, double y);
/// The cursor moved to (x, y): the radius becomes its distance to the centre.
void update_brush_resize(BrushResize& r, BrushSettings& b, const Camera& view, double diagonal, double x, double y);

}  // namespace adaptex::studio
