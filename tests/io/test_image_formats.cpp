// Tests of io/image_io's JPEG and TGA input: decoding, row order, format by content, and the
// structure checks (truncated, forged and oversized files) that run before stb decodes anything.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "adaptex/core/errors.h"
#include "adaptex/io/image_io.h"
#include "image_test_files.h"
#include "io_test_files.h"
#include "test_support.h"

namespace adaptex {
namespace {

/// Bottom half (v < 0.5) blue, top half red, a green column at i = 0.
ImageRGBA8 two_halves(int w, int h) {
  ImageRGBA8 img(w, h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      auto* t = img.texel(i, j);
      t[0] = j >= h / 2 ? 255 : 0;
      t[1] = i == 0 ? 255 : 0;
      t[2] = j < h / 2 ? 255 : 0;
      t[3] = 255;
    }
  return img;
}

std::string error_of(const std::string& bytes, const std::string& name) {
  try {
    (void)read_image_from_memory(bytes, name);
  } catch (const IoError& e) {
    return e.what();
  }
  return "(no error)";
}

/// The read is rejected with one line that names the file and contains \p what.
void expect_rejects(const std::string& bytes, const std::string& name, const std::string& what) {
  const std::string msg = error_of(bytes, name);
  EXPECT_EQ(msg.rfind(name + ": ", 0), 0u) << msg;
  EXPECT_NE(msg.find(what), std::string::npos) << "expected '" << what << "' in: " << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

TEST(ImageFormats, TgaRleAndRawRoundTripExactlyWithV0AtTheBottom) {
  const ImageRGBA8 img = two_halves(17, 10);
  for (bool rle : {true, false}) {
    const ImageRGBA8 back = read_image_from_memory(test::tga_bytes(img, rle), "a.tga");
    ASSERT_EQ(back.width, 17);
    ASSERT_EQ(back.height, 10);
    EXPECT_EQ(back.data, img.data) << (rle ? "RLE" : "raw");
    EXPECT_EQ(back.texel(3, 0)[2], 255);  // v = 0 row is blue
  }
}

TEST(ImageFormats, ColourMappedTgaReadsThroughItsPalette) {
  // 2x1, 8-bit indices into a 2-entry 24-bit palette (BGR), bottom-left origin.
  std::string tga = {0, 1, 1, 0, 0, 2, 0, 24, 0, 0, 0, 0, 2, 0, 1, 0, 8, 0};
  tga += std::string("\x00\x00\xff", 3) + std::string("\xff\x00\x00", 3);  // entry 0 red, entry 1 blue
  tga += std::string("\x01\x00", 2);
  const ImageRGBA8 img = read_image_from_memory(tga, "p.tga");
  ASSERT_EQ(img.width, 2);
  EXPECT_EQ(img.texel(0, 0)[2], 255);  // blue
  EXPECT_EQ(img.texel(1, 0)[0], 255);  // red
}

TEST(ImageFormats, JpegDecodesCloseToTheOriginalWithV0AtTheBottom) {
  const ImageRGBA8 img = two_halves(32, 16);
  const ImageRGBA8 back = read_image_from_memory(test::jpeg_bytes(img, 100), "a.jpg");
  ASSERT_EQ(back.width, 32);
  ASSERT_EQ(back.height, 16);
  EXPECT_GT(back.texel(20, 2)[2], 200);   // bottom: blue
  EXPECT_LT(back.texel(20, 2)[0], 60);
  EXPECT_GT(back.texel(20, 13)[0], 200);  // top: red
  EXPECT_LT(back.texel(20, 13)[2], 60);
  EXPECT_EQ(back.texel(20, 13)[3], 255);
}

TEST(ImageFormats, FormatIsTakenFromTheContentNotTheName) {
  const ImageRGBA8 img = two_halves(8, 8);
  EXPECT_EQ(read_image_from_memory(test::tga_bytes(img), "really_a_tga.png").data, img.data);
  EXPECT_EQ(read_image_from_memory(test::png_bytes(img), "really_a_png.jpg").data, img.data);
  EXPECT_EQ(read_image_from_memory(test::jpeg_bytes(img), "really_a_jpeg.tga").width, 8);
  expect_rejects("GIF89a" + std::string(40, '\0'), "anim.gif", "not an image: the content is not a PNG, JPEG or TGA");
  expect_rejects("8BPS" + std::string(40, '\1'), "x.jpg", "not a JPEG file");
}

TEST(ImageFormats, TruncatedJpegIsRejectedAtEveryCut) {
  const std::string jpeg = test::jpeg_bytes(two_halves(64, 48));
  ASSERT_GT(jpeg.size(), 600u);
  // Cut inside the headers, inside the scan, and just before the end-of-image marker.
  for (std::size_t cut : {std::size_t{3}, std::size_t{20}, std::size_t{200}, jpeg.size() / 2, jpeg.size() - 2})
    expect_rejects(jpeg.substr(0, cut), "cut.jpg", "corrupt JPEG: truncated");
}

TEST(ImageFormats, TruncatedTgaIsRejected) {
  const ImageRGBA8 img = two_halves(40, 30);
  const std::string raw = test::tga_bytes(img, false), rle = test::tga_bytes(img, true);
  expect_rejects(raw.substr(0, raw.size() - 50), "raw.tga", "corrupt TGA: truncated");
  expect_rejects(rle.substr(0, rle.size() / 2), "rle.tga", "corrupt TGA: truncated");
  expect_rejects(raw.substr(0, 12), "short.tga", "corrupt TGA: the 18-byte header is missing");
}

/// A baseline JPEG header claiming \p w x \p h, with a few bytes of scan data and an EOI; with
/// \p tables, one-code DC 0 and AC 0 Huffman tables before the scan.
std::string forged_jpeg(int w, int h, bool tables = true) {
  std::string j = "\xFF\xD8";
  for (const char table : {'\x00', '\x10'})
    if (tables) j += std::string("\xFF\xC4\x00\x14", 4) + table + '\x01' + std::string(15, '\0') + '\x00';
  j += std::string("\xFF\xC0\x00\x0B\x08", 5);
  j += static_cast<char>(h >> 8);
  j += static_cast<char>(h & 255);
  j += static_cast<char>(w >> 8);
  j += static_cast<char>(w & 255);
  j += std::string("\x01\x01\x11\x00", 4);                           // 1 component
  j += std::string("\xFF\xDA\x00\x08\x01\x01\x00\x00\x3F\x00", 10);  // SOS
  j += std::string(16, '\x55');
  j += "\xFF\xD9";
  return j;
}

TEST(ImageFormats, ForgedAndOversizedHeadersAreRejectedBeforeDecoding) {
  expect_rejects(forged_jpeg(8000, 8000), "forged.jpg",
                 "corrupt JPEG: forged size: 8000x8000 pixels cannot be coded in 16 bytes of scan data");
  expect_rejects(forged_jpeg(9000, 100), "huge.jpg", "JPEG of 9000x100 pixels is larger than the 8192x8192 limit");
  expect_rejects(forged_jpeg(0, 0) , "zero.jpg", "height 0");
  // A scan whose Huffman tables were never defined (stb_image would decode with uninitialized ones).
  expect_rejects(forged_jpeg(8, 8, false), "undefined.jpg",
                 "corrupt JPEG: the scan at byte 15 uses a Huffman table that no DHT defined (DC 0, AC 0)");
  std::string tga = test::tga_bytes(two_halves(4, 4), false);
  tga[12] = static_cast<char>(0x40), tga[13] = static_cast<char>(0x1F);  // width 8000
  tga[14] = static_cast<char>(0x40), tga[15] = static_cast<char>(0x1F);  // height 8000
  expect_rejects(tga, "forged.tga", "corrupt TGA: truncated: the pixel data needs 256000018 bytes");
  tga[12] = static_cast<char>(0xFF), tga[13] = static_cast<char>(0xFF);  // width 65535
  expect_rejects(tga, "huge.tga", "TGA of 65535x8000 pixels is larger than the 8192x8192 limit");
  std::string bits = test::tga_bytes(two_halves(4, 4), false);
  bits[16] = 7;
  expect_rejects(bits, "bits.tga", "7 bits per pixel is not a TGA pixel format");
}

TEST(ImageFormats, ReadImageOpensJpegAndTgaFiles) {
  test::TempDir dir;
  const ImageRGBA8 img = two_halves(12, 6);
  test::write_text(dir.path / "a.tga", test::tga_bytes(img));
  test::write_text(dir.path / "a.jpeg", test::jpeg_bytes(img));
  EXPECT_EQ(read_image(dir.path / "a.tga").data, img.data);
  EXPECT_EQ(read_image(dir.path / "a.jpeg").height, 6);
}

}  // namespace
}  // namespace adaptex
