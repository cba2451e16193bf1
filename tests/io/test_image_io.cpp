// Tests of io/image_io: PNG round trip, row order (row 0 = bottom = v 0), errors.
#include <gtest/gtest.h>

#include <stb_image.h>

#include <fstream>

#include "adaptex/core/errors.h"
#include "adaptex/io/image_io.h"
#include "test_support.h"

namespace adaptex {
namespace {

ImageRGBA8 gradient(int w, int h) {
  ImageRGBA8 img(w, h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      auto* t = img.texel(i, j);
      t[0] = static_cast<std::uint8_t>(i * 17);
      t[1] = static_cast<std::uint8_t>(j * 29);
      t[2] = static_cast<std::uint8_t>((i + j) * 7);
      t[3] = static_cast<std::uint8_t>(255 - j);
    }
  return img;
}

TEST(ImageIo, PngRoundTripIsExact) {
  test::TempDir dir;
  const auto img = gradient(13, 7);
  write_png(dir.path / "a.png", img);
  const auto back = read_image(dir.path / "a.png");
  ASSERT_EQ(back.width, 13);
  ASSERT_EQ(back.height, 7);
  EXPECT_EQ(back.data, img.data);
}

TEST(ImageIo, EncodeMatchesFileAndFlipsRows) {
  test::TempDir dir;
  // Bottom row (j = 0) red, everything else blue.
  ImageRGBA8 img(4, 3, {0, 0, 255, 255});
  for (int i = 0; i < 4; ++i) img.texel(i, 0)[0] = 255, img.texel(i, 0)[2] = 0;
  const auto png = encode_png(img);
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png[1], 'P');
  write_png(dir.path / "b.png", img);
  std::ifstream in(dir.path / "b.png", std::ios::binary);
  std::vector<unsigned char> file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(file, png);
  const auto back = read_image(dir.path / "b.png");
  EXPECT_EQ(back.texel(0, 0)[0], 255);  // still at the bottom after the round trip
  EXPECT_EQ(back.texel(0, 2)[2], 255);
}

TEST(ImageIo, FileRowOrderIsTopFirst) {
  // Decode our PNG with stb directly (no flip): the file's first row must be the top (j = H-1).
  ImageRGBA8 a(1, 2);
  a.texel(0, 0)[0] = 10;
  a.texel(0, 1)[0] = 200;
  const auto png = encode_png(a);
  int w = 0, h = 0, c = 0;
  unsigned char* px = stbi_load_from_memory(png.data(), static_cast<int>(png.size()), &w, &h, &c, 4);
  ASSERT_NE(px, nullptr);
  EXPECT_EQ(px[0], 200);
  EXPECT_EQ(px[4], 10);
  stbi_image_free(px);
}

TEST(ImageIo, Errors) {
  test::TempDir dir;
  EXPECT_THROW(read_image(dir.path / "missing.png"), IoError);
  {
    std::ofstream(dir.path / "bad.png") << "this is not a png";
  }
  try {
    read_image(dir.path / "bad.png");
    FAIL();
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.png"), std::string::npos);
  }
  // A JPEG whose Huffman table holds more than 256 codes: stb's table build writes past its 257
  // entries (UBSan, fuzz_jpeg); the heap it corrupts is the likely cause of fuzz_jpeg's SEGV.
  try {
    read_image(std::filesystem::path(ADAPTEX_SOURCE_DIR) / "tests/fuzz/seeds/jpeg/dht-too-many-codes.jpg");
    FAIL();
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("Huffman table (DHT)"), std::string::npos) << e.what();
  }
  EXPECT_THROW(encode_png(ImageRGBA8{}), InvalidInputError);  // an empty image is a bad argument
  EXPECT_THROW(write_png(dir.path / "no" / "dir" / "x.png", gradient(2, 2)), OutputError);
}

// rgb8x8.jpg with one more (unused) DC table, id 3, of 256 codes: 255 of 8 bits and one of \p last_bits.
std::string jpeg_with_256_code_table(int last_bits) {
  std::ifstream in(std::filesystem::path(ADAPTEX_SOURCE_DIR) / "tests/fuzz/seeds/jpeg/rgb8x8.jpg", std::ios::binary);
  const std::string jpeg((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t length = 2 + 17 + 256;
  std::string dht = {'\xFF', '\xC4', static_cast<char>(length >> 8), static_cast<char>(length & 0xFF), '\x03'};
  std::string counts(16, '\0');
  counts[7] = static_cast<char>(255);
  counts[last_bits - 1] = 1;
  dht += counts;
  for (int s = 0; s < 256; ++s) dht += static_cast<char>(s);
  return jpeg.substr(0, 2) + dht + jpeg.substr(2);
}

TEST(ImageIo, RefusesHuffmanTablesTheDecoderMisreads) {
  // stb_image marks "no code of at most 9 bits" with symbol index 255 in its lookup table: a 256th
  // code that short is decoded as another symbol (its assertion fired under fuzz_jpeg).
  try {
    read_image_from_memory(jpeg_with_256_code_table(9), "short.jpg");
    FAIL();
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("short.jpg: corrupt JPEG: a Huffman table (DHT)"), std::string::npos)
        << e.what();
  }
  // The same table with a 10-bit 256th code is read, and the image decodes as before.
  const auto ok = read_image_from_memory(jpeg_with_256_code_table(10), "long.jpg");
  const auto reference =
      read_image(std::filesystem::path(ADAPTEX_SOURCE_DIR) / "tests/fuzz/seeds/jpeg/rgb8x8.jpg");
  EXPECT_EQ(ok.width, 8);
  EXPECT_EQ(ok.data, reference.data);
}

}  // namespace
}  // namespace adaptex
