/// \file layout_image.cpp
/// UV layout picture coloured by per-face stretch (thesis Figure 3.8).
#include "adaptex/param/layout_image.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"

namespace adaptex {

namespace {

using Rgb = std::array<double, 3>;

/// Blue -> cyan -> green -> yellow -> red for t in [0, 1].
Rgb ramp(double t) {
  static const Rgb stops[] = {{0.15, 0.25, 0.85}, {0.1, 0.75, 0.9}, {0.2, 0.8, 0.3},
                              {0.95, 0.85, 0.2},  {0.85, 0.15, 0.1}};
  t = std::clamp(t, 0.0, 1.0) * 4.0;
  const int i = std::min(3, static_cast<int>(t));
  const double s = t - i;
  Rgb c;
  for (int k = 0; k < 3; ++k) c[k] = (1 - s) * stops[i][k] + s * stops[i + 1][k];
  return c;
}

void put(ImageRGBA8& img, int i, int j, const Rgb& c) {
  std::uint8_t* p = img.texel(i, j);
  for (int k = 0; k < 3; ++k) p[k] = static_cast<std::uint8_t>(std::lround(255 * std::clamp(c[k], 0.0, 1.0)));
  p[3] = 255;
}

void darken(ImageRGBA8& img, int i, int j) {
  std::uint8_t* p = img.texel(i, j);
  for (int k = 0; k < 3; ++k) p[k] = static_cast<std::uint8_t>(p[k] * 0.45);
}

}  // namespace

ImageRGBA8 render_layout(const Parameterization& param, const std::vector<double>& face_value,
                         const LayoutImageOptions& options) {
  const int n = options.size;
  if (n < 1 || n > kMaxTextureSize)
    throw InvalidInputError("render_layout: image size " + std::to_string(n) + " is outside [1, " +
                            std::to_string(kMaxTextureSize) + "]");
  const size_t nf = param.uv_faces.size();
  if (face_value.size() != nf)
    throw InvalidInputError("render_layout: " + std::to_string(face_value.size()) +
                            " face values for " + std::to_string(nf) + " faces");
  double lo = options.low, hi = options.high;
  if (hi <= lo) {
    std::vector<double> finite;
    finite.reserve(nf);
    for (double v : face_value)
      if (std::isfinite(v)) finite.push_back(v);
    lo = 0;
    hi = 1;
    if (!finite.empty()) {
      auto pct = [&](size_t p) {
        const size_t k = std::min(finite.size() - 1, finite.size() * p / 100);
        std::nth_element(finite.begin(), finite.begin() + static_cast<long>(k), finite.end());
        return finite[k];
      };
      lo = pct(1);
      hi = std::max(pct(99), lo + 1e-6);
    }
  }
  ImageRGBA8 img(n, n, {255, 255, 255, 255});
  double uv_area = 0;
  auto px = [&](const Vec2& t) { return Vec2(t.x() * n, t.y() * n); };
  for (size_t f = 0; f < nf; ++f) {
    const Vec2 a = px(param.uv[param.uv_faces[f][0]]), b = px(param.uv[param.uv_faces[f][1]]),
               c = px(param.uv[param.uv_faces[f][2]]);
    const double area2 = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    uv_area += std::abs(area2) / 2;
    const double v = face_value[f];
    const Rgb col = std::isfinite(v) ? ramp((v - lo) / (hi - lo)) : Rgb{1.0, 0.0, 1.0};
    if (area2 == 0) continue;
    const int i0 = std::max(0, static_cast<int>(std::floor(std::min({a.x(), b.x(), c.x()}))));
    const int i1 = std::min(n - 1, static_cast<int>(std::ceil(std::max({a.x(), b.x(), c.x()}))));
    const int j0 = std::max(0, static_cast<int>(std::floor(std::min({a.y(), b.y(), c.y()}))));
    const int j1 = std::min(n - 1, static_cast<int>(std::ceil(std::max({a.y(), b.y(), c.y()}))));
    const double sgn = area2 > 0 ? 1.0 : -1.0;
    auto edge = [](const Vec2& p, const Vec2& q, double x, double y) {
      return (q.x() - p.x()) * (y - p.y()) - (q.y() - p.y()) * (x - p.x());
    };
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const double x = i + 0.5, y = j + 0.5;
        if (sgn * edge(a, b, x, y) >= 0 && sgn * edge(b, c, x, y) >= 0 && sgn * edge(c, a, x, y) >= 0)
          put(img, i, j, col);
      }
  }
  if (options.wireframe && nf > 0 && uv_area / static_cast<double>(nf) >= 6.0) {
    // Mark the edge pixels first so that shared edges and vertices are darkened only once.
    std::vector<char> mask(static_cast<size_t>(n) * n, 0);
    for (size_t f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) {
        const Vec2 p = px(param.uv[param.uv_faces[f][k]]);
        const Vec2 q = px(param.uv[param.uv_faces[f][(k + 1) % 3]]);
        const int steps = std::max(1, static_cast<int>(std::ceil((q - p).cwiseAbs().maxCoeff())));
        for (int s = 0; s <= steps; ++s) {
          const Vec2 r = p + (q - p) * (static_cast<double>(s) / steps);
          const int i = std::clamp(static_cast<int>(r.x()), 0, n - 1);
          const int j = std::clamp(static_cast<int>(r.y()), 0, n - 1);
          mask[static_cast<size_t>(j) * n + i] = 1;
        }
      }
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        if (mask[static_cast<size_t>(j) * n + i]) darken(img, i, j);
  }
  return img;
}

}  // namespace adaptex
