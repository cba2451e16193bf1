/// \file image_io.cpp
/// PNG, JPEG and TGA input and PNG output through stb_image / stb_image_write (the implementations
/// live in Debian's libstb.so). Files store the top row first, ImageRGBA8 stores v = 0 first: rows flip.
/// Only these three formats are read (stb would decode PSD, GIF, HDR, ... too: a 52-byte PSD header
/// made it allocate 1 GB). Before stb decodes anything, adaptex walks the file's structure itself
/// (PNG chunks, JPEG segments up to the end-of-image marker, TGA header, palette and RLE packets), so
/// a truncated or forged file is one clear error, and the size from the header must be within
/// kMaxTextureSize per side and kMaxImagePixels in all (stbi_info_from_memory must agree).
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
#include "image_formats.h"

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

}  // namespace

ImageRGBA8 read_image(const std::filesystem::path& path) {
  return read_image_from_memory(read_input_file(path), path.string());
}

ImageRGBA8 read_image_from_memory(const std::string& bytes, const std::string& name) {
  check_input_size(bytes.size(), name);
  const io_detail::ImageHeader header = io_detail::check_image_file(bytes, name);
  if (bytes.size() > static_cast<size_t>(INT32_MAX)) throw IoError(name + ": cannot read image: file too large");
  int w = 0, h = 0, channels = 0;
  // stb's own reading of the header must agree with adaptex's (the same decoder will then run).
  if (!stbi_info_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()), static_cast<int>(bytes.size()), &w,
                             &h, &channels) ||
      w != header.width || h != header.height)
    throw IoError(name + ": corrupt " + header.format + ": the decoder reads a different header (" + std::to_string(w) +
                  "x" + std::to_string(h) + ", expected " + std::to_string(header.width) + "x" +
                  std::to_string(header.height) + ")");
  unsigned char* pixels =
      stbi_load_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()), static_cast<int>(bytes.size()), &w,
                            &h, &channels, 4);
  if (!pixels) {
    const char* reason = stbi_failure_reason();
    throw IoError(name + ": corrupt " + header.format + ": cannot decode: " + (reason ? reason : "unknown error"));
  }
  if (w != header.width || h != header.height) {
    stbi_image_free(pixels);
    throw IoError(name + ": corrupt " + header.format + ": decoded to another size than its header's");
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
