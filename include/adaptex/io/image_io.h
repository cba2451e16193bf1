#pragma once
/// \file image_io.h
/// PNG input/output through stb. Files store the top row first; ImageRGBA8 stores v = 0 first,
/// so both functions flip rows.
#include <filesystem>
#include <string>
#include <vector>

#include "adaptex/core/image.h"

namespace adaptex {

/// Reads a PNG as RGBA8 (only PNG; regular files only; at most kMaxTextureSize per side and
/// kMaxImagePixels, checked from the header before decoding).
/// \throw IoError unreadable, not a PNG, larger than the caps, or corrupt.
ImageRGBA8 read_image(const std::filesystem::path& path);
/// read_image() on the file's bytes already in memory (the same checks after the file ones: size caps
/// from the header, PNG only); \p name stands for the file in messages.
/// \pre none. \throw IoError empty, larger than kMaxInputFileBytes, not a PNG, larger than the caps, or corrupt.
ImageRGBA8 read_image_from_memory(const std::string& bytes, const std::string& name);
/// Writes a PNG. \throw OutputError the file cannot be written
void write_png(const std::filesystem::path& path, const ImageRGBA8& img);
/// Encodes a PNG into memory (for embedding in .glb). \throw InvalidInputError empty image; OutputError encoding failed
std::vector<unsigned char> encode_png(const ImageRGBA8& img);

}  // namespace adaptex
