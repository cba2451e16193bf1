#pragma once
// Small writers of mesh files in every input format, for the io tests (test code only: the library
// itself never hand-parses or hand-writes these formats except OBJ output).
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "adaptex/core/mesh.h"

namespace adaptex::test {

inline std::string num17(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

inline void write_text(const std::filesystem::path& p, const std::string& s) {
  std::ofstream out(p, std::ios::binary);
  out << s;
}

/// OFF (or COFF with an RGBA colour per vertex), optionally with CRLF line endings.
inline void write_off(const std::filesystem::path& p, const TriMesh& m, bool coff = false, bool crlf = false) {
  const std::string nl = crlf ? "\r\n" : "\n";
  std::string s = std::string(coff ? "COFF" : "OFF") + nl + std::to_string(m.num_vertices()) + " " +
                  std::to_string(m.num_faces()) + " 0" + nl;
  for (const auto& v : m.positions)
    s += num17(v.x()) + " " + num17(v.y()) + " " + num17(v.z()) + (coff ? " 192 64 32 255" : "") + nl;
  for (const auto& f : m.faces)
    s += "3 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) + nl;
  write_text(p, s);
}

/// ASCII PLY with float (declared) or double properties, written with 17 digits.
inline void write_ply_ascii(const std::filesystem::path& p, const TriMesh& m, const char* type = "float") {
  std::string s = "ply\nformat ascii 1.0\ncomment adaptex test\nelement vertex " + std::to_string(m.num_vertices()) +
                  "\nproperty " + type + " x\nproperty " + type + " y\nproperty " + type +
                  " z\nelement face " + std::to_string(m.num_faces()) +
                  "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& v : m.positions) s += num17(v.x()) + " " + num17(v.y()) + " " + num17(v.z()) + "\n";
  for (const auto& f : m.faces)
    s += "3 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) + "\n";
  write_text(p, s);
}

template <class T>
void put(std::string& s, T x) {
  char b[sizeof(T)];
  std::memcpy(b, &x, sizeof(T));
  s.append(b, sizeof(T));
}

/// Binary little-endian PLY with double positions, and either a face list or a tristrips element.
inline void write_ply_binary(const std::filesystem::path& p, const TriMesh& m,
                             const std::vector<int>* strips = nullptr) {
  std::string s = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(m.num_vertices()) +
                  "\nproperty double x\nproperty double y\nproperty double z\n";
  if (strips)
    s += "element tristrips 1\nproperty list int int vertex_indices\nend_header\n";
  else
    s += "element face " + std::to_string(m.num_faces()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& v : m.positions) {
    put(s, v.x());
    put(s, v.y());
    put(s, v.z());
  }
  if (strips) {
    put(s, static_cast<std::int32_t>(strips->size()));
    for (int i : *strips) put(s, static_cast<std::int32_t>(i));
  } else {
    for (const auto& f : m.faces) {
      put(s, static_cast<std::uint8_t>(3));
      for (int v : f) put(s, static_cast<std::int32_t>(v));
    }
  }
  write_text(p, s);
}

/// Binary STL (float32, one record per triangle: every vertex is repeated per triangle).
inline void write_stl_binary(const std::filesystem::path& p, const TriMesh& m) {
  std::string s(80, ' ');
  put(s, static_cast<std::uint32_t>(m.num_faces()));
  for (const auto& f : m.faces) {
    for (int k = 0; k < 3; ++k) put(s, 0.0f);
    for (int v : f)
      for (int k = 0; k < 3; ++k) put(s, static_cast<float>(m.positions[v][k]));
    put(s, static_cast<std::uint16_t>(0));
  }
  write_text(p, s);
}

inline void write_stl_ascii(const std::filesystem::path& p, const TriMesh& m) {
  std::string s = "solid test\n";
  for (const auto& f : m.faces) {
    s += "  facet normal 0 0 0\n    outer loop\n";
    for (int v : f)
      s += "      vertex " + num17(m.positions[v].x()) + " " + num17(m.positions[v].y()) + " " +
           num17(m.positions[v].z()) + "\n";
    s += "    endloop\n  endfacet\n";
  }
  s += "endsolid test\n";
  write_text(p, s);
}

/// A GLB holding \p json as its JSON chunk, optionally with a BIN chunk; \p forged_bin_length replaces
/// the BIN chunk's length field.
inline std::string glb(std::string json, const std::string& bin, std::uint32_t forged_bin_length = 0) {
  while (json.size() % 4) json += ' ';
  std::string s = "glTF";
  put(s, std::uint32_t{2});
  put(s, static_cast<std::uint32_t>(12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size())));
  put(s, static_cast<std::uint32_t>(json.size()));
  put(s, std::uint32_t{0x4E4F534A});
  s += json;
  if (!bin.empty()) {
    put(s, forged_bin_length ? forged_bin_length : static_cast<std::uint32_t>(bin.size()));
    put(s, std::uint32_t{0x004E4942});
    s += bin;
  }
  return s;
}

/// The first 52 bytes of a PSD (Photoshop) file declaring 11,000,000 x 25 pixels.
inline std::string psd_header() {
  std::string s = "8BPS";
  s += std::string("\0\1", 2) + std::string(6, '\0') + std::string("\0\3", 2);
  auto be32 = [&](std::uint32_t v) {
    for (int k = 3; k >= 0; --k) s += static_cast<char>((v >> (8 * k)) & 0xFF);
  };
  be32(25);
  be32(11'000'000);
  s += std::string("\0\x08\0\3", 4);
  s.resize(52, '\0');
  return s;
}

/// A PNG signature and IHDR declaring \p w x \p h pixels, and nothing else.
inline std::string png_header(std::uint32_t w, std::uint32_t h) {
  std::string s("\x89PNG\r\n\x1a\n", 8);
  s += std::string("\0\0\0\x0d", 4) + "IHDR";
  for (std::uint32_t v : {w, h})
    for (int k = 3; k >= 0; --k) s += static_cast<char>((v >> (8 * k)) & 0xFF);
  s += std::string("\x08\x06\0\0\0", 5) + std::string(4, '\0');
  return s;
}

}  // namespace adaptex::test
