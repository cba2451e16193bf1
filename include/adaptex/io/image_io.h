#pragma once
/// \file image_io.h
/// PNG input/output through stb. Files store the top row first; ImageRGBA8 stores v = 0 first,
/// so both functions flip rows.
#include <filesystem>
#include <vector>

#include "adaptex/core/image.h"

namespace adaptex {

/// Reads any image stb can decode as RGBA8. \throw IoError unreadable or corrupt.
ImageRGBA8 read_image(const std::filesystem::path& path);
/// Writes a PNG. \throw IoError
void write_png(const std::filesystem::path& path, const ImageRGBA8& img);
/// Encodes a PNG into memory (for embedding in .glb). \throw IoError empty image
std::vector<unsigned char> encode_png(const ImageRGBA8& img);

}  // namespace adaptex
