#pragma once
/// \file image_io.h
/// Image input (PNG, JPEG, TGA) and PNG output through stb. Files store the top row first; ImageRGBA8
/// stores v = 0 first, so both directions flip rows.
#include <filesystem>
#include <string>
#include <vector>

#include "adaptex/core/image.h"

namespace adaptex {

/// Reads a PNG, JPEG (baseline or progressive) or TGA (raw or RLE, true-colour, grey or colour-mapped)
/// as RGBA8; the format is recognised by content (a TGA, which has no signature, by its header). Regular
/// files only; at most kMaxTextureSize per side and kMaxImagePixels, checked from the header before
/// decoding; the file's structure is walked first, so a truncated or forged file is rejected.
/// \throw IoError unreadable, another format, larger than the caps, truncated or corrupt.
ImageRGBA8 read_image(const std::filesystem::path& path);
/// read_image() on the file's bytes already in memory (the same checks after the file ones: structure,
/// size caps from the header, PNG/JPEG/TGA only); \p name stands for the file in messages.
/// \pre none. \throw IoError empty, larger than kMaxInputFileBytes, another format, larger than the caps,
/// truncated or corrupt.
ImageRGBA8 read_image_from_memory(const std::string& bytes, const std::string& name);
/// Writes a PNG. \throw OutputError the file cannot be written
void write_png(const std::filesystem::path& path, const ImageRGBA8& img);
/// Encodes a PNG into memory (for embedding in .glb). \throw InvalidInputError empty image; OutputError encoding failed
std::vector<unsigned char> encode_png(const ImageRGBA8& img);

}  // namespace adaptex
