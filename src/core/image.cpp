#include "adaptex/core/image.h"

#include <algorithm>
#include <cmath>

namespace adaptex {

ImageRGBA8::ImageRGBA8(int w, int h, std::array<std::uint8_t, 4> fill)
    : width(w), height(h), data(static_cast<size_t>(w) * h * 4) {
  for (size_t k = 0; k < data.size(); k += 4) std::copy(fill.begin(), fill.end(), data.begin() + k);
}

ImageF::ImageF(int w, int h, float fill) : width(w), height(h), data(static_cast<size_t>(w) * h, fill) {}

BilinearTap bilinear_tap(int size, double u) {
  const double x = u * size - 0.5;
  const double xf = std::floor(x);
  const int xi = static_cast<int>(std::clamp(xf, -1.0, static_cast<double>(size)));
  return BilinearTap{std::clamp(xi, 0, size - 1), std::clamp(xi + 1, 0, size - 1), x - xf};
}

namespace {
// Clamp-to-edge bilinear footprint: texel centres at (i+0.5)/W.
struct Footprint {
  int i0, i1, j0, j1;
  double fx, fy;
};
Footprint footprint(int w, int h, double u, double v) {
  const BilinearTap x = bilinear_tap(w, u), y = bilinear_tap(h, v);
  return Footprint{x.i0, x.i1, y.i0, y.i1, x.f, y.f};
}
}  // namespace

Vec3 sample_bilinear(const ImageRGBA8& img, double u, double v) {
  const Footprint fp = footprint(img.width, img.height, u, v);
  Vec3 out;
  for (int c = 0; c < 3; ++c) {
    const double a = img.texel(fp.i0, fp.j0)[c], b = img.texel(fp.i1, fp.j0)[c];
    const double d = img.texel(fp.i0, fp.j1)[c], e = img.texel(fp.i1, fp.j1)[c];
    const double bottom = a + (b - a) * fp.fx, top = d + (e - d) * fp.fx;
    out[c] = (bottom + (top - bottom) * fp.fy) / 255.0;
  }
  return out;
}

double sample_bilinear(const ImageF& img, double u, double v) {
  const Footprint fp = footprint(img.width, img.height, u, v);
  const double a = img.at(fp.i0, fp.j0), b = img.at(fp.i1, fp.j0);
  const double d = img.at(fp.i0, fp.j1), e = img.at(fp.i1, fp.j1);
  const double bottom = a + (b - a) * fp.fx, top = d + (e - d) * fp.fx;
  return bottom + (top - bottom) * fp.fy;
}

}  // namespace adaptex
