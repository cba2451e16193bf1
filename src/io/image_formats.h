#pragma once
/// \file image_formats.h
/// Internal to the io area: the structure checks that run on an image file's bytes before stb decodes
/// them (image_io.cpp). Each names the file and says what is wrong in one line. Not installed.
#include <string>

namespace adaptex::io_detail {

/// An image file's format and size, from its header.
struct ImageHeader {
  const char* format = "";  ///< "PNG", "JPEG" or "TGA".
  int width = 0, height = 0;
};

/// Recognises PNG (signature), JPEG (SOI marker) and TGA (a header stb reads as TGA) by content, walks
/// the file's structure and returns its size, checked against kMaxTextureSize and kMaxImagePixels.
/// \p name is the file in messages; its extension only picks the wording of "not a ... file".
/// \pre none. \throw IoError another format, truncated, forged (sizes that disagree with the bytes),
/// or larger than the caps.
ImageHeader check_image_file(const std::string& bytes, const std::string& name);

}  // namespace adaptex::io_detail
