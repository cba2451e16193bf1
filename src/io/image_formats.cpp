/// \file image_formats.cpp
/// The structure walks of check_image_file(): everything stb would otherwise trust. stb sizes its
/// buffers from header fields and reads past a truncated file as zeros (a cut JPEG or TGA decodes
/// "successfully" with a grey or black bottom), so the checks here require every byte the header
/// promises to exist:
/// - PNG: the IHDR size, and every chunk up to IEND inside the file (stb grows its IDAT buffer to a
///   chunk's claimed length before reading it).
/// - JPEG: the marker segments from SOI, each inside the file, a frame header (SOF) before the first
///   scan, and the end-of-image marker (EOI) after the last scan; at least one byte of coded data per
///   64 luma blocks (a Huffman code is at least one bit per block), so a few bytes cannot claim 8192².
/// - TGA: the header fields stb accepts, then the palette and the pixel data (raw, or RLE packets
///   walked one by one) inside the file.
#include "image_formats.h"

#include <cstdint>
#include <string_view>

#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"

namespace adaptex::io_detail {

namespace {

std::uint32_t be16(const std::string& b, std::size_t at) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(b[at])) << 8 | static_cast<unsigned char>(b[at + 1]);
}
std::uint32_t le16(const std::string& b, std::size_t at) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 1])) << 8 | static_cast<unsigned char>(b[at]);
}
std::uint32_t be32(const std::string& b, std::size_t at) { return be16(b, at) << 16 | be16(b, at + 2); }
unsigned byte(const std::string& b, std::size_t at) { return static_cast<unsigned char>(b[at]); }

/// \p format's size \p w x \p h, checked against the caps (core/limits.h).
ImageHeader checked_size(const char* format, std::uint64_t w, std::uint64_t h, const std::string& name) {
  if (w == 0 || h == 0)
    throw IoError(name + ": corrupt " + format + ": the header says " + std::to_string(w) + "x" + std::to_string(h));
  if (w > static_cast<std::uint64_t>(kMaxTextureSize) || h > static_cast<std::uint64_t>(kMaxTextureSize) ||
      w * h > kMaxImagePixels)
    throw IoError(name + ": " + format + " of " + std::to_string(w) + "x" + std::to_string(h) +
                  " pixels is larger than the " + std::to_string(kMaxTextureSize) + "x" +
                  std::to_string(kMaxTextureSize) + " limit");
  return {format, static_cast<int>(w), static_cast<int>(h)};
}

ImageHeader check_png(const std::string& bytes, const std::string& name) {
  if (bytes.size() < 33 || bytes.compare(12, 4, "IHDR") != 0)
    throw IoError(name + ": corrupt PNG: no IHDR chunk after the signature");
  const ImageHeader header = checked_size("PNG", be32(bytes, 16), be32(bytes, 20), name);
  for (std::size_t at = 8; at + 8 <= bytes.size();) {
    const std::uint64_t length = be32(bytes, at);
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
  return header;
}

/// Skips a JPEG scan's entropy-coded data from \p at: returns the position of the next marker (an 0xFF
/// followed by neither 0x00 (stuffing) nor a restart marker RST0-7), or npos at the end of the bytes.
std::size_t skip_scan_data(const std::string& bytes, std::size_t at) {
  for (std::size_t k = bytes.find('\xFF', at); k != std::string::npos; k = bytes.find('\xFF', k + 1)) {
    if (k + 1 >= bytes.size()) return std::string::npos;
    const unsigned m = byte(bytes, k + 1);
    if (m != 0x00 && m != 0xFF && !(m >= 0xD0 && m <= 0xD7)) return k;
  }
  return std::string::npos;
}


/// The Huffman tables of a DHT segment [begin, end): each a class/id byte, 16 code counts and as many
/// symbols as the counts sum to, at most 256 (stb_image builds its code table in 257 entries: a larger
/// sum writes past it, found by fuzz_jpeg under UBSan). A 256th code of at most 9 bits is refused too:
/// stb's 9-bit lookup table marks "no short code" with index 255, so it would decode that code as
/// another symbol of another length (its assertion fired under fuzz_jpeg). Real tables hold at most
/// 162 symbols.
/// Marks each table it holds in \p defined[class][id].
void check_huffman_tables(const std::string& bytes, std::size_t begin, std::size_t end, const std::string& corrupt,
                          bool (&defined)[2][4]) {
  constexpr int kStbFastBits = 9;
  std::size_t p = begin;
  while (p < end) {
    if (p + 17 > end) throw IoError(corrupt + "truncated Huffman table (DHT) at byte " + std::to_string(p));
    const unsigned table_class = byte(bytes, p) >> 4, id = byte(bytes, p) & 15;
    if (table_class > 1 || id > 3)
      throw IoError(corrupt + "a Huffman table (DHT) at byte " + std::to_string(p) + " of class " +
                    std::to_string(table_class) + " and id " + std::to_string(id) + " (class 0-1, id 0-3)");
    defined[table_class][id] = true;
    std::size_t codes = 0;
    int longest = 0;
    for (int k = 1; k <= 16; ++k) {
      const unsigned count = static_cast<unsigned char>(bytes[p + k]);
      codes += count;
      if (count > 0) longest = k;
    }
    if (codes > 256)
      throw IoError(corrupt + "a Huffman table (DHT) at byte " + std::to_string(p) + " with " + std::to_string(codes) +
                    " codes (at most 256)");
    if (codes == 256 && longest <= kStbFastBits)
      throw IoError(corrupt + "a Huffman table (DHT) at byte " + std::to_string(p) +
                    " whose 256th code has only " + std::to_string(longest) + " bits (the decoder needs more than " +
                    std::to_string(kStbFastBits) + ")");
    p += 17 + codes;
  }
  if (p != end) throw IoError(corrupt + "a Huffman table (DHT) runs past its segment");
}

/// The scan header (SOS) whose segment starts at \p at: every Huffman table its decoding reads must be
/// defined before it (stb_image does not check: it would decode with uninitialized tables, which
/// fuzz_jpeg found as wild reads). A progressive DC scan reads DC tables only on its first pass, an
/// AC scan AC tables only; a sequential scan reads both.
void check_scan_tables(const std::string& bytes, std::size_t at, std::size_t length, bool progressive,
                       const bool (&defined)[2][4], const std::string& corrupt) {
  const unsigned components = length >= 3 ? byte(bytes, at + 4) : 0;
  if (components < 1 || components > 4 || length != 6 + 2 * components)
    throw IoError(corrupt + "a scan header (SOS) at byte " + std::to_string(at) + " of " + std::to_string(length) +
                  " bytes for " + std::to_string(components) + " components");
  const std::size_t tail = at + 5 + 2 * components;
  const unsigned ss = byte(bytes, tail), ah = byte(bytes, tail + 2) >> 4;
  const bool dc = !progressive || (ss == 0 && ah == 0), ac = !progressive || ss != 0;
  for (unsigned c = 0; c < components; ++c) {
    const unsigned tables = byte(bytes, at + 6 + 2 * c), td = tables >> 4, ta = tables & 15;
    if ((dc && (td > 3 || !defined[0][td])) || (ac && (ta > 3 || !defined[1][ta])))
      throw IoError(corrupt + "the scan at byte " + std::to_string(at) + " uses a Huffman table that no DHT defined (" +
                    (dc ? "DC " + std::to_string(td) : std::string()) + (dc && ac ? ", " : "") +
                    (ac ? "AC " + std::to_string(ta) : std::string()) + ")");
  }
}

ImageHeader check_jpeg(const std::string& bytes, const std::string& name) {
  const std::string corrupt = name + ": corrupt JPEG: ";
  ImageHeader header{"JPEG", 0, 0};
  bool frame = false, scan = false, progressive = false;
  bool huffman[2][4] = {};  // DC / AC tables defined so far
  std::uint64_t coded = 0;  // bytes of entropy-coded data
  std::size_t at = 2;
  while (true) {
    while (at < bytes.size() && byte(bytes, at) == 0xFF && at + 1 < bytes.size() && byte(bytes, at + 1) == 0xFF) ++at;
    if (at + 2 > bytes.size())
      throw IoError(corrupt + "truncated: the file ends at byte " + std::to_string(bytes.size()) +
                    " before the end-of-image marker");
    if (byte(bytes, at) != 0xFF)
      throw IoError(corrupt + "expected a marker at byte " + std::to_string(at));
    const unsigned m = byte(bytes, at + 1);
    if (m == 0xD9) break;  // EOI
    if (m == 0xD8) throw IoError(corrupt + "a second start-of-image marker at byte " + std::to_string(at));
    if (m == 0x01 || (m >= 0xD0 && m <= 0xD7)) {  // standalone markers
      at += 2;
      continue;
    }
    if (at + 4 > bytes.size()) throw IoError(corrupt + "truncated inside the segment at byte " + std::to_string(at));
    const std::size_t length = be16(bytes, at + 2);
    if (length < 2 || length > bytes.size() - at - 2)
      throw IoError(corrupt + "truncated: the segment at byte " + std::to_string(at) + " claims " +
                    std::to_string(length) + " bytes, but only " + std::to_string(bytes.size() - at - 2) + " are left");
    const bool sof = m >= 0xC0 && m <= 0xCF && m != 0xC4 && m != 0xC8 && m != 0xCC;
    if (sof) {
      if (length < 8) throw IoError(corrupt + "frame header of " + std::to_string(length) + " bytes");
      if (frame) throw IoError(corrupt + "more than one frame header (SOF)");
      frame = true;
      progressive = m == 0xC2 || m == 0xC6 || m == 0xCA || m == 0xCE;
      if (be16(bytes, at + 5) == 0) throw IoError(corrupt + "height 0 (a DNL marker) is not supported");
      header = checked_size("JPEG", be16(bytes, at + 7), be16(bytes, at + 5), name);
    }
    if (m == 0xC4) check_huffman_tables(bytes, at + 4, at + 2 + length, corrupt, huffman);
    if (m == 0xDA && frame) check_scan_tables(bytes, at, length, progressive, huffman, corrupt);
    at += 2 + length;
    if (m == 0xDA) {  // SOS: entropy-coded data follows
      if (!frame) throw IoError(corrupt + "a scan before the frame header (SOF)");
      scan = true;
      const std::size_t next = skip_scan_data(bytes, at);
      if (next == std::string::npos)
        throw IoError(corrupt + "truncated: the scan data runs to the end of the file (byte " +
                      std::to_string(bytes.size()) + ") without an end-of-image marker");
      coded += next - at;
      at = next;
    }
  }
  if (!frame || !scan) throw IoError(corrupt + (frame ? "no scan (SOS) before the end-of-image marker" : "no frame header (SOF)"));
  const std::uint64_t blocks = (static_cast<std::uint64_t>(header.width) + 7) / 8 * ((static_cast<std::uint64_t>(header.height) + 7) / 8);
  if (coded * 64 < blocks)
    throw IoError(corrupt + "forged size: " + std::to_string(header.width) + "x" + std::to_string(header.height) +
                  " pixels cannot be coded in " + std::to_string(coded) + " bytes of scan data");
  return header;
}

/// Bytes per stored TGA pixel (or palette index / entry) of \p bits, 0 when stb does not read it.
std::size_t tga_bytes(unsigned bits) { return bits == 8 ? 1 : bits == 15 || bits == 16 ? 2 : bits == 24 ? 3 : bits == 32 ? 4 : 0; }

/// True when \p bytes start with a header stb reads as TGA (stbi__tga_test: colour-map type 0 or 1 and
/// an image type that fits it). No other format stb reads has 0 or 1 as its second byte.
bool looks_like_tga(const std::string& bytes) {
  if (bytes.size() < 18 || byte(bytes, 1) > 1) return false;
  const unsigned type = byte(bytes, 2);
  return byte(bytes, 1) == 1 ? type == 1 || type == 9 : type == 2 || type == 3 || type == 10 || type == 11;
}

ImageHeader check_tga(const std::string& bytes, const std::string& name) {
  const std::string corrupt = name + ": corrupt TGA: ";
  if (!looks_like_tga(bytes)) throw IoError(corrupt + "the 18-byte header is missing or names an unknown image type");
  const bool indexed = byte(bytes, 1) == 1, rle = byte(bytes, 2) >= 8;
  const unsigned palette_bits = byte(bytes, 7), bits = byte(bytes, 16);
  const ImageHeader header = checked_size("TGA", le16(bytes, 12), le16(bytes, 14), name);
  if (indexed ? (bits != 8 && bits != 16) || tga_bytes(palette_bits) == 0 : tga_bytes(bits) == 0)
    throw IoError(corrupt + std::to_string(bits) + " bits per pixel" +
                  (indexed ? " with " + std::to_string(palette_bits) + "-bit palette entries" : std::string()) +
                  " is not a TGA pixel format");
  // What stb reads before the pixels: the ID field, then (indexed) palette_start bytes it skips and
  // the palette itself.
  std::uint64_t at = 18 + std::uint64_t{byte(bytes, 0)};
  if (indexed) {
    const std::uint64_t entries = le16(bytes, 5);
    if (entries == 0) throw IoError(corrupt + "a colour-mapped image with an empty palette");
    at += le16(bytes, 3) + entries * tga_bytes(palette_bits);
  }
  const std::uint64_t pixel = tga_bytes(bits), pixels = static_cast<std::uint64_t>(header.width) * header.height;
  const auto truncated = [&](std::uint64_t need) {
    return IoError(corrupt + "truncated: the pixel data needs " + std::to_string(need) + " bytes but the file has " +
                   std::to_string(bytes.size()));
  };
  if (!rle) {
    if (at + pixels * pixel > bytes.size()) throw truncated(at + pixels * pixel);
    return header;
  }
  for (std::uint64_t done = 0; done < pixels;) {  // RLE packets: a count byte, then 1 or n pixels
    if (at >= bytes.size()) throw truncated(at + 1);
    const unsigned packet = byte(bytes, at);
    const std::uint64_t n = (packet & 127u) + 1;
    at += 1 + ((packet & 128u) ? pixel : n * pixel);
    done += n;
  }
  if (at > bytes.size()) throw truncated(at);
  return header;
}

std::string lower_extension(const std::string& name) {
  const std::size_t dot = name.find_last_of('.'), slash = name.find_last_of("/\\");
  std::string ext = dot == std::string::npos || (slash != std::string::npos && slash > dot) ? "" : name.substr(dot + 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace

ImageHeader check_image_file(const std::string& bytes, const std::string& name) {
  static constexpr std::string_view png_signature("\x89PNG\r\n\x1a\n", 8);
  ImageHeader header;
  if (bytes.size() >= 8 && std::string_view(bytes).substr(0, 8) == png_signature) {
    header = check_png(bytes, name);
  } else if (bytes.size() >= 3 && byte(bytes, 0) == 0xFF && byte(bytes, 1) == 0xD8 && byte(bytes, 2) == 0xFF) {
    header = check_jpeg(bytes, name);
  } else if (looks_like_tga(bytes) || lower_extension(name) == "tga") {
    header = check_tga(bytes, name);
  } else {
    const std::string ext = lower_extension(name);
    const std::string claimed = ext == "png" ? "a PNG file" : ext == "jpg" || ext == "jpeg" ? "a JPEG file" : "an image";
    throw IoError(name + ": not " + claimed + ": the content is not a PNG, JPEG or TGA image (the formats read)");
  }
  return header;
}

}  // namespace adaptex::io_detail
