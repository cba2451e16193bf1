/// \file image_io.cpp
/// PNG/JPEG/... input and PNG output through stb_image / stb_image_write (the implementations live
/// in Debian's libstb.so). Files store the top row first, ImageRGBA8 stores v = 0 first: rows flip.
#include "adaptex/io/image_io.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

#include "adaptex/core/errors.h"

namespace adaptex {

namespace {

std::vector<unsigned char> read_file_bytes(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw IoError(path.string() + ": cannot read image: file does not exist");
  if (std::filesystem::is_directory(path, ec))
    throw IoError(path.string() + ": cannot read image: is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path.string() + ": cannot read image: cannot open file");
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw IoError(path.string() + ": cannot read image: read error");
  return bytes;
}

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
    throw IoError(what + ": cannot encode an empty image (" + std::to_string(img.width) + "x" +
                  std::to_string(img.height) + ")");
  if (img.data.size() != static_cast<size_t>(img.width) * img.height * 4)
    throw IoError(what + ": image data size " + std::to_string(img.data.size()) + " does not match " +
                  std::to_string(img.width) + "x" + std::to_string(img.height) + "x4");
}

}  // namespace

ImageRGBA8 read_image(const std::filesystem::path& path) {
  const auto bytes = read_file_bytes(path);
  if (bytes.empty()) throw IoError(path.string() + ": cannot read image: file is empty");
  if (bytes.size() > static_cast<size_t>(INT32_MAX))
    throw IoError(path.string() + ": cannot read image: file too large");
  int w = 0, h = 0, channels = 0;
  unsigned char* pixels =
      stbi_load_from_memory(bytes.data(), static_cast<int>(bytes.size()), &w, &h, &channels, 4);
  if (!pixels) {
    const char* reason = stbi_failure_reason();
    throw IoError(path.string() + ": cannot decode image: " + (reason ? reason : "unknown error"));
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
    throw IoError("PNG encoder: stb_image_write failed for a " + std::to_string(img.width) + "x" +
                  std::to_string(img.height) + " image");
  return out;
}

void write_png(const std::filesystem::path& path, const ImageRGBA8& img) {
  check_image(img, path.string());
  const auto png = encode_png(img);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw IoError(path.string() + ": cannot open for writing");
  out.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  out.close();
  if (!out) throw IoError(path.string() + ": write failed (disk full?)");
}

}  // namespace adaptex
