/// \file brush.cpp
/// Screen- and world-space brush radius, interactive resize (see brush.h).
#include "brush.h"

#include <algorithm>
#include <cmath>

namespace adaptex::studio {

namespace {
double positive(double d) { return d > 0 ? d : 1.0; }
}  // namespace

double brush_world_radius(const BrushSettings& b, const Camera& view, const Vec3& at, double diagonal) {
  return b.screen_space ? b.pixel_radius * view.pixel_size_at(at) : b.radius * positive(diagonal);
}

double brush_screen_radius(const BrushSettings& b, const Camera& view, const Vec3& at, double diagonal) {
  return b.screen_space ? b.pixel_radius : b.radius * positive(diagonal) / view.pixel_size_at(at);
}

void set_brush_screen_radius(BrushSettings& b, double pixels, const Camera& view, const Vec3& at, double diagonal) {
  if (b.screen_space) {
    b.pixel_radius = std::clamp(pixels, kMinPixelRadius, kMaxPixelRadius);
  } else {
    b.radius = std::clamp(pixels * view.pixel_size_at(at) / positive(diagonal), kMinRadiusFraction, kMaxRadiusFraction);
  }
}

void scale_brush(BrushSettings& b, double factor) {
  if (b.screen_space)
    b.pixel_radius = std::clamp(b.pixel_radius * factor, kMinPixelRadius, kMaxPixelRadius);
  else
    b.radius = std::clamp(b.radius * factor, kMinRadiusFraction, kMaxRadiusFraction);
}

BrushResize begin_brush_resize(const BrushSettings& b, const Camera& view, const Vec3& at, double diagonal,
                               double x, double y) {
  BrushResize r;
  r.pixels = brush_screen_radius(b, view, at, diagonal);
  r.centre = Vec2(x - r.pixels, y);
  r.at = at;
  r.before = b;
  return r;
}

void update_brush_resize(BrushResize& r, BrushSettings& b, const Camera& view, double diagonal, double x, double y) {
  set_brush_screen_radius(b, std::hypot(x - r.centre.x(), y - r.centre.y()), view, r.at, diagonal);
  r.pixels = brush_screen_radius(b, view, r.at, diagonal);
}

}  // namespace adaptex::studio
