/// \file stencil.cpp
/// The decal stencil (see stencil.h).
#include "stencil.h"

#include <algorithm>
#include <cmath>

#include "adaptex/paint/decal.h"

namespace adaptex::studio {

DecalCamera Stencil::decal_camera(const Camera& view) const {
  const Ray r = view.pixel_ray(centre.x(), centre.y());
  DecalCamera d;
  d.eye = r.origin;
  d.target = r.origin + r.dir;
  // Screen y is down: a counter-clockwise turn on the screen turns the image's up towards screen-left.
  d.up = std::cos(angle) * view.up() - std::sin(angle) * view.right();
  const double tan_half = std::tan(view.fov_y_degrees * 3.14159265358979 / 360.0);
  const double h = std::clamp(height, 1.0, 1e6) / std::max(1, view.height);
  d.fov_y_degrees = std::clamp(2.0 * std::atan(h * tan_half) * 180.0 / 3.14159265358979, 1e-3, 179.0);
  d.aspect = aspect > 0 ? aspect : 1.0;
  return d;
}

std::array<Vec2, 4> Stencil::corners(const Camera& view) const {
  const DecalFrame f = decal_frame(decal_camera(view), "stencil");
  std::array<Vec2, 4> out;
  const double uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int k = 0; k < 4; ++k) {
    const Vec3 p = f.eye + f.forward + (2 * uv[k][0] - 1) * f.tan_half_x * f.right +
                   (2 * uv[k][1] - 1) * f.tan_half_y * f.up;
    const Vec3 s = view.project(p);
    out[size_t(k)] = Vec2(s.x(), s.y());
  }
  return out;
}

bool Stencil::contains(const Camera& view, double x, double y) const {
  const auto c = corners(view);
  // Inside a convex quad: the same side of all four edges.
  int sign = 0;
  for (int k = 0; k < 4; ++k) {
    const Vec2 a = c[size_t(k)], b = c[size_t((k + 1) % 4)];
    const double cross = (b.x() - a.x()) * (y - a.y()) - (b.y() - a.y()) * (x - a.x());
    const int s = cross > 0 ? 1 : cross < 0 ? -1 : 0;
    if (s != 0 && sign != 0 && s != sign) return false;
    if (s != 0) sign = s;
  }
  return true;
}

Stencil fit_stencil(const Camera& view, double aspect) {
  Stencil s;
  s.centre = Vec2(view.width * 0.5, view.height * 0.5);
  s.height = view.height * 0.5;
  s.aspect = aspect > 0 ? aspect : 1.0;
  return s;
}

void edit_stencil(Stencil& s, StencilEdit edit, double x0, double y0, double x1, double y1) {
  const Vec2 a(x0 - s.centre.x(), y0 - s.centre.y()), b(x1 - s.centre.x(), y1 - s.centre.y());
  switch (edit) {
    case StencilEdit::Move: s.centre += Vec2(x1 - x0, y1 - y0); break;
    case StencilEdit::Scale:
      if (a.norm() > 1 && b.norm() > 1) s.height = std::clamp(s.height * b.norm() / a.norm(), 8.0, 1e5);
      break;
    case StencilEdit::Rotate:
      // Window y is down: the screen angle of a vector is atan2(-y, x).
      if (a.norm() > 1 && b.norm() > 1) s.angle += std::atan2(-b.y(), b.x()) - std::atan2(-a.y(), a.x());
      break;
  }
}

}  // namespace adaptex::studio
