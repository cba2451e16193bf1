/// \file image_io.cpp
/// PNG input and output through stb_image / stb_image_write (the implementations live in Debian's
/// libstb.so). Files store the top row first, ImageRGBA8 stores v = 0 first: rows flip.
/// Only PNG is read (stb would decode PSD, GIF, HDR, ... too: a 52-byte PSD header made it allocate
/// 1 GB; issue 11): the signature and the IHDR size are checked before stb decodes anything, and the
/// size must be within kMaxTextureSize per side and kMaxImagePixels in all.
#include "adaptex/io/image_io.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <string_view>
#include <string>

#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "adaptex/io/input_file.h"

namespace adaptex {

namespace {

// Copies \p src (rows of \p row_bytes) into \p dst in reverse row order.
void copy_flipped(const unsigned char* src, unsigned char* dst, int rows, size_t row_bytes) {
  for (int j = 0; j < rows; ++j)
    std::memcpy(dst + static_cast<size_t>(rows - 1 - j) * row_bytes, src + static_cast<size_t>(j) * row_bytes,
                row_bytes);
}

void append_bytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<unsigned char>*>(context);
  const auto* p = static_cast<const unsigned char*>(data);
  out->insert(out->end(), p, p + size);
}

void check_image(const ImageRGBA8& img, const std::string& what) {
  if (img.width <= 0 || img.height <= 0)
    throw InvalidInputError(what + ": cannot encode an empty image (" + std::to_string(img.width) + "x" +
                  std::to_string(img.height) + ")");
  if (img.data.size() != static_cast<size_t>(img.width) * img.height * 4)
    throw InvalidInputError(what + ": image data size " + std::to_string(img.data.size()) + " does not match " +
                  std::to_string(img.width) + "x" + std::to_string(img.height) + "x4");
}

/// Checks the PNG signature and the IHDR chunk's size against the caps, before decoding.
void check_png_header(const std::string& bytes, const std::string& name) {
  static constexpr std::string_view signature("\x89PNG\r\n\x1a\n", 8);
  if (bytes.size() < 8 || std::string_view(bytes).substr(0, 8) != signature)
    throw IoError(name + ": not a PNG file (only PNG images are read)");
  if (bytes.size() < 33 || bytes.compare(12, 4, "IHDR") != 0)
    throw IoError(name + ": corrupt PNG: no IHDR chunk after the signature");
  const auto be32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (int k = 0; k < 4; ++k) v = v << 8 | static_cast<unsigned char>(bytes[at + k]);
    return v;
  };
  const std::uint64_t w = be32(16), h = be32(20);
  if (w == 0 || h == 0) throw IoError(name + ": corrupt PNG: the header says " + std::to_string(w) + "x" + std::to_string(h));
  if (w > static_cast<std::uint64_t>(kMaxTextureSize) || h > static_cast<std::uint64_t>(kMaxTextureSize) ||
      w * h > kMaxImagePixels)
    throw IoError(name + ": PNG of " + std::to_string(w) + "x" + std::to_string(h) + " pixels is larger than the " +
                  std::to_string(kMaxTextureSize) + "x" + std::to_string(kMaxTextureSize) + " limit");
  // Every chunk up to IEND must fit in the bytes left: stb grows its IDAT buffer to a chunk's claimed
  // length before reading it (the fuzz smoke found a 2x2 PNG whose chunk claimed ~1 GB: a 2 GB
  // allocation).
  for (std::size_t at = 8; at + 8 <= bytes.size();) {
    const std::uint64_t length = be32(at);
    std::string type = bytes.substr(at + 4, 4);
    for (char& c : type)  // a forged type may hold any byte: keep the message one printable line
      if (c < 0x20 || c > 0x7e) c = '?';
    if (length > bytes.size() - at - 8 || bytes.size() - at - 8 - length < 4)
      throw IoError(name + ": corrupt PNG: chunk \"" + type + "\" at byte " + std::to_string(at) + " claims " +
                    std::to_string(length) + " bytes, but only " + std::to_string(bytes.size() - at - 8) +
                    " are left");
    if (type == "IEND") break;
    at += 12 + length;
  }
}

}  // namespace

ImageRGBA8 read_image(const std::filesystem::path& path) {
  return read_image_from_memory(read_input_file(path), path.string());
}

ImageRGBA8 read_image_from_memory(const std::string& bytes, const std::string& name) {
  check_input_size(bytes.size(), name);
  check_png_header(bytes, name);
  if (bytes.size() > static_cast<size_t>(INT32_MAX)) throw IoError(name + ": cannot read image: file too large");
  int w = 0, h = 0, channels = 0;
  unsigned char* pixels =
      stbi_load_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()), static_cast<int>(bytes.size()), &w,
                            &h, &channels, 4);
  if (!pixels) {
    const char* reason = stbi_failure_reason();
    throw IoError(name + ": cannot decode image: " + (reason ? reason : "unknown error"));
  }
  ImageRGBA8 img;
  img.width = w;
  img.height = h;
  img.data.resize(static_cast<size_t>(w) * h * 4);
  copy_flipped(pixels, img.data.data(), h, static_cast<size_t>(w) * 4);
  stbi_image_free(pixels);
  return img;
}

std::vector<unsigned char> encode_png(const ImageRGBA8& img) {
  check_image(img, "PNG encoder");
  const size_t row_bytes = static_cast<size_t>(img.width) * 4;
  std::vector<unsigned char> flipped(img.data.size());
  copy_flipped(img.data.data(), flipped.data(), img.height, row_bytes);
  std::vector<unsigned char> out;
  if (!stbi_write_png_to_func(&append_bytes, &out, img.width, img.height, 4, flipped.data(),
                              static_cast<int>(row_bytes)))
    throw OutputError("PNG encoder: stb_image_write failed for a " + std::to_string(img.width) + "x" +
                  std::to_string(img.height) + " image");
  return out;
}

void write_png(const std::filesystem::path& path, const ImageRGBA8& img) {
  check_image(img, path.string());
  const auto png = encode_png(img);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw OutputError(path.string() + ": cannot open for writing");
  out.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  out.close();
  if (!out) throw OutputError(path.string() + ": write failed (disk full?)");
}

}  // namespace adaptex
