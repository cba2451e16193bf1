#pragma once
/// \file image.h
/// Images in texture-space order: texel (i, j) is column i, row j, and row j = 0 is v = 0 (the
/// *bottom* of the picture, OBJ convention). Texel (i, j) is centred at ((i+0.5)/W, (j+0.5)/H).
/// PNG files store the top row first: io/image_io flips on read and write.
#include <cstdint>
#include <vector>

#include "adaptex/core/types.h"

namespace adaptex {

/// 8-bit RGBA image, 4 bytes per texel, rows from v = 0 upwards.
struct ImageRGBA8 {
  int width = 0, height = 0;
  std::vector<std::uint8_t> data;  ///< width * height * 4 bytes.

  ImageRGBA8() = default;
  ImageRGBA8(int w, int h, std::array<std::uint8_t, 4> fill = {0, 0, 0, 0});
  std::uint8_t* texel(int i, int j) { return &data[(static_cast<size_t>(j) * width + i) * 4]; }
  const std::uint8_t* texel(int i, int j) const { return &data[(static_cast<size_t>(j) * width + i) * 4]; }
  bool empty() const { return width == 0 || height == 0; }
};

/// Single-channel float image (importance, stretch and weight maps), same texel order.
struct ImageF {
  int width = 0, height = 0;
  std::vector<float> data;  ///< width * height values.

  ImageF() = default;
  ImageF(int w, int h, float fill = 0.0f);
  float& at(int i, int j) { return data[static_cast<size_t>(j) * width + i]; }
  float at(int i, int j) const { return data[static_cast<size_t>(j) * width + i]; }
};

/// One axis of sample_bilinear()'s clamp-to-edge footprint (texel centres at (i + 0.5) / size): the
/// coordinate u lies between texels i0 and i1 (equal at the edges) with weight f on i1. A lookup at
/// many points of a regular grid can compute the taps once per row and column and get the same values
/// as sample_bilinear() there.
struct BilinearTap {
  int i0 = 0, i1 = 0;
  double f = 0;
};
/// \pre size >= 1
BilinearTap bilinear_tap(int size, double u);

/// Bilinear sample of the RGB channels at (u, v) with clamp-to-edge, in [0,1] per channel,
/// exactly as the stroke-file contract defines reconstruction.
Vec3 sample_bilinear(const ImageRGBA8& img, double u, double v);
/// Bilinear sample of a float image at (u, v), clamp-to-edge.
double sample_bilinear(const ImageF& img, double u, double v);

}  // namespace adaptex
