#pragma once
// Writers of small PNG, JPEG and TGA files for the io tests, through stb_image_write (test code only).
#include <stb_image_write.h>

#include <string>
#include <vector>

#include "adaptex/core/image.h"
#include "adaptex/io/image_io.h"

namespace adaptex::test {

inline void append_to_string(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
}

/// \p img's rows in file order (top row first), as stb_image_write expects them.
inline std::vector<unsigned char> top_first(const ImageRGBA8& img) {
  std::vector<unsigned char> rows(img.data.size());
  const std::size_t row = static_cast<std::size_t>(img.width) * 4;
  for (int j = 0; j < img.height; ++j)
    std::copy_n(img.data.begin() + static_cast<std::ptrdiff_t>(j * row), row,
                rows.begin() + static_cast<std::ptrdiff_t>((img.height - 1 - j) * row));
  return rows;
}

inline std::string png_bytes(const ImageRGBA8& img) {
  const auto v = encode_png(img);
  return std::string(v.begin(), v.end());
}

/// Baseline JPEG of the RGB channels (quality 0-100).
inline std::string jpeg_bytes(const ImageRGBA8& img, int quality = 95) {
  const auto rows = top_first(img);
  std::vector<unsigned char> rgb;
  for (std::size_t k = 0; k < rows.size(); k += 4) rgb.insert(rgb.end(), rows.begin() + k, rows.begin() + k + 3);
  std::string out;
  stbi_write_jpg_to_func(&append_to_string, &out, img.width, img.height, 3, rgb.data(), quality);
  return out;
}

/// TGA, RGBA, RLE-compressed (stb's default) or raw.
inline std::string tga_bytes(const ImageRGBA8& img, bool rle = true) {
  const auto rows = top_first(img);
  const int saved = stbi_write_tga_with_rle;
  stbi_write_tga_with_rle = rle ? 1 : 0;
  std::string out;
  stbi_write_tga_to_func(&append_to_string, &out, img.width, img.height, 4, rows.data());
  stbi_write_tga_with_rle = saved;
  return out;
}

/// A w x h image of one colour.
inline ImageRGBA8 solid(int w, int h, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  return ImageRGBA8(w, h, {r, g, b, 255});
}

}  // namespace adaptex::test
