/// \file read_cgal.cpp
/// OFF (incl. COFF/NOFF/STOFF, CRLF), PLY (ascii and binary; `face` and `tristrips` elements) and STL
/// (ascii and binary) through CGAL 5.5's stream readers (header-only, Debian libcgal-dev).
/// Why CGAL and not assimp: assimp 5.2 on Debian is built with float ai_real (and its ascii number
/// parser is not correctly rounded), and it does not read `element tristrips`; CGAL's readers parse
/// ascii numbers with the C++ stream (correctly rounded doubles) and binary numbers bit-exactly.
/// For ascii PLY the header's float properties are read as double so that the file's decimal text,
/// not its float32 rounding, is kept (see docs/io.md, "Precision").
#include <CGAL/IO/OFF/File_scanner_OFF.h>
#include <CGAL/IO/PLY/PLY_reader.h>
#include <CGAL/IO/STL/STL_reader.h>

#include <cstring>
#include <sstream>

#include "adaptex/core/errors.h"
#include "mesh_soup.h"

namespace adaptex::io_detail {

namespace {

std::string count_str(std::size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

}  // namespace

// ---------------------------------------------------------------------------------------------- OFF
PolygonSoup read_off_soup(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::istringstream in(read_file_text(path));
  PolygonSoup soup;
  soup.format = "off";
  CGAL::File_scanner_OFF scanner(in, false);
  if (in.fail())
    throw IoError(name + ": not a valid OFF file: bad header (expected [C][N]OFF followed by the vertex, face "
                         "and edge counts)");
  const std::size_t nv = scanner.size_of_vertices(), nf = scanner.size_of_facets();
  const std::size_t size_hint = in.str().size();
  soup.positions.reserve(std::min(nv, size_hint));
  soup.offsets.reserve(std::min(nf, size_hint) + 1);
  const std::string counts = " (the header says " + count_str(nv, "vertex", "vertices") + ", " +
                             count_str(nf, "face", "faces") + ")";
  for (std::size_t v = 0; v < nv; ++v) {
    double x = 0, y = 0, z = 0, w = 1;
    scanner.scan_vertex(x, y, z, w);
    if (scanner.has_normals()) {
      double nx, ny, nz;
      scanner.scan_normal(nx, ny, nz);
    }
    if (scanner.has_vcolors()) {
      unsigned char r, g, b;
      scanner.scan_color(r, g, b);
    }
    if (scanner.has_textures()) {
      double tu, tv;
      scanner.scan_texture(tu, tv);
    }
    scanner.skip_to_next_vertex(v);
    if (in.fail())
      throw IoError(name + ": vertex " + std::to_string(v) + " is missing or not numeric (NaN/inf are not " +
                    "accepted): file truncated, or fewer vertex lines than the header says" + counts);
    soup.positions.emplace_back(x / w, y / w, z / w);
  }
  for (std::size_t f = 0; f < nf; ++f) {
    std::size_t no = static_cast<std::size_t>(-1);
    scanner.scan_facet(no, f);
    if (in.fail() || no == static_cast<std::size_t>(-1) || (in.eof() && no == 0))
      throw IoError(name + ": face " + std::to_string(f) + " is missing or unreadable: file truncated, or fewer " +
                    "vertex or face lines than the header says" + counts);
    for (std::size_t j = 0; j < no; ++j) {
      std::size_t idx = 0;
      scanner.scan_facet_vertex_index(idx, j + 1, f);
      if (in.bad())
        throw IoError(name + ": face " + std::to_string(f) + " lists fewer vertex indices than its count " +
                      std::to_string(no) + " (file truncated or corrupt)");
      if (in.fail())
        throw InvalidInputError(name + ": face " + std::to_string(f) + " refers to a vertex index out of range " +
                                "(the file has " + count_str(nv, "vertex", "vertices") + ", numbered from 0)");
      soup.indices.push_back(static_cast<std::int64_t>(idx));
    }
    if (scanner.has_fcolors()) {
      unsigned char r, g, b;
      scanner.scan_color(r, g, b);
    }
    scanner.skip_to_next_facet(f);
    soup.end_polygon();
  }
  return soup;
}

// ---------------------------------------------------------------------------------------------- PLY
namespace {

/// In an ascii PLY header, declares float properties as double so that CGAL's reader keeps the
/// decimal text at double precision instead of rounding it to float32 first.
void promote_ascii_floats(std::string& text) {
  const auto end = text.find("end_header");
  if (end == std::string::npos) return;
  std::istringstream header(text.substr(0, end));
  std::string line, out;
  bool ascii = false;
  while (std::getline(header, line)) {
    if (line.rfind("format ascii", 0) == 0) ascii = true;
    if (line.rfind("property", 0) == 0) {
      std::istringstream tokens(line);
      std::string tok, rebuilt;
      while (tokens >> tok) {
        if (tok == "float" || tok == "float32") tok = "double";
        rebuilt += rebuilt.empty() ? tok : " " + tok;
      }
      line = rebuilt;
    }
    out += line + "\n";
  }
  if (ascii) text = out + text.substr(end);
}

template <class T>
bool take_list(CGAL::IO::internal::PLY_element& el, const char* tag, std::vector<std::int64_t>& out) {
  if (!el.has_property<std::vector<T>>(tag)) return false;
  std::vector<T> buf;
  el.assign(buf, tag);
  out.assign(buf.begin(), buf.end());
  return true;
}

/// Reads an integer list property of any PLY index type.
bool take_index_list(CGAL::IO::internal::PLY_element& el, const char* tag, std::vector<std::int64_t>& out) {
  return take_list<std::int32_t>(el, tag, out) || take_list<std::uint32_t>(el, tag, out) ||
         take_list<std::int16_t>(el, tag, out) || take_list<std::uint16_t>(el, tag, out) ||
         take_list<std::int8_t>(el, tag, out) || take_list<std::uint8_t>(el, tag, out);
}

bool has_any_property(CGAL::IO::internal::PLY_element& el, const char* tag) {
  for (std::size_t k = 0; k < el.number_of_properties(); ++k)
    if (el.property(k)->name() == tag) return true;
  return false;
}

}  // namespace

PolygonSoup read_ply_soup(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::string text = read_file_text(path);
  if (text.rfind("ply", 0) != 0) throw IoError(name + ": not a PLY file (it does not start with 'ply')");
  if (text.find("end_header") == std::string::npos)
    throw IoError(name + ": corrupt PLY header: no 'end_header' line");
  promote_ascii_floats(text);
  const std::size_t size_hint = text.size();
  std::istringstream in(std::move(text));
  CGAL::IO::internal::PLY_reader reader(false);
  if (!reader.init(in)) throw IoError(name + ": corrupt PLY header (unknown format, element or property type)");
  PolygonSoup soup;
  soup.format = "ply";
  bool have_vertices = false, have_faces = false;
  std::vector<std::int64_t> list;
  for (std::size_t e = 0; e < reader.number_of_elements(); ++e) {
    auto& el = reader.element(e);
    const std::string& ename = el.name();
    const std::size_t n = el.number_of_items();
    const bool is_vertex = (ename == "vertex" || ename == "vertices") && !have_vertices;
    const bool is_face = ename == "face" || ename == "faces";
    const bool is_strip = ename == "tristrips";
    const char* index_tag = nullptr;
    if (is_vertex) {
      for (const char* c : {"x", "y", "z"})
        if (!el.has_property<double>(c))
          throw IoError(name + ": PLY vertex element has no float or double property '" + c + "'");
      soup.positions.reserve(std::min(n, size_hint));
      have_vertices = true;
    }
    if (is_face || is_strip) {
      index_tag = has_any_property(el, "vertex_indices") ? "vertex_indices"
                  : has_any_property(el, "vertex_index") ? "vertex_index"
                                                         : nullptr;
      if (!index_tag)
        throw IoError(name + ": PLY element '" + ename + "' has no 'vertex_indices' list property");
      have_faces = true;
    }
    for (std::size_t j = 0; j < n; ++j) {
      for (std::size_t k = 0; k < el.number_of_properties(); ++k) {
        el.property(k)->get(in);
        if (in.fail())
          throw IoError(name + ": PLY truncated or corrupt: element '" + ename + "' item " + std::to_string(j) +
                        " of " + std::to_string(n) + " (property '" + el.property(k)->name() +
                        "') could not be read");
      }
      if (is_vertex) {
        double x, y, z;
        el.assign(x, "x");
        el.assign(y, "y");
        el.assign(z, "z");
        soup.positions.emplace_back(x, y, z);
      } else if (index_tag) {
        if (!take_index_list(el, index_tag, list))
          throw IoError(name + ": PLY element '" + ename + "': '" + index_tag + "' is not an integer list");
        if (is_face) {
          soup.indices.insert(soup.indices.end(), list.begin(), list.end());
          soup.end_polygon();
        } else {
          // Triangle strips, -1 restarts a strip; every odd triangle swaps its first two corners so that
          // all triangles keep the strip's orientation. Repeated indices (strip "turns") are skipped.
          std::size_t start = 0;
          for (std::size_t i = 0; i <= list.size(); ++i) {
            if (i < list.size() && list[i] >= 0) continue;
            for (std::size_t k = start; k + 2 < i; ++k) {
              std::int64_t a = list[k], b = list[k + 1], c = list[k + 2];
              if (a == b || b == c || a == c) continue;
              if ((k - start) % 2 == 1) std::swap(a, b);
              soup.indices.insert(soup.indices.end(), {a, b, c});
              soup.end_polygon();
            }
            start = i + 1;
          }
        }
      }
    }
  }
  if (!have_vertices) throw IoError(name + ": PLY file has no 'vertex' element");
  if (!have_faces)
    throw InvalidInputError(name + ": no faces: the PLY file has no 'face' or 'tristrips' element (" +
                            count_str(soup.positions.size(), "vertex", "vertices") + ")");
  return soup;
}

// ---------------------------------------------------------------------------------------------- STL
PolygonSoup read_stl_soup(const std::filesystem::path& path) {
  const std::string name = path.string();
  const std::string text = read_file_text(path);
  std::size_t first = 0;
  while (first < text.size() && std::isspace(static_cast<unsigned char>(text[first]))) ++first;
  const bool solid = text.compare(first, 5, "solid") == 0;
  std::uint32_t declared = 0;
  if (text.size() >= 84) std::memcpy(&declared, text.data() + 80, 4);
  const bool exact_binary_size = text.size() >= 84 && text.size() == 84 + 50ull * declared;
  const bool binary = exact_binary_size || !solid;
  if (binary) {
    if (text.size() < 84)
      throw IoError(name + ": binary STL shorter than its 84-byte header (" + std::to_string(text.size()) +
                    " bytes)");
    if (text.size() < 84 + 50ull * declared)
      throw IoError(name + ": binary STL truncated: the header says " + std::to_string(declared) +
                    " triangles (" + std::to_string(84 + 50ull * declared) + " bytes) but the file has " +
                    std::to_string(text.size()) + " bytes (" + std::to_string((text.size() - 84) / 50) +
                    " complete triangles)");
  }
  // Note: CGAL's STL reader already welds corners with identical coordinates.
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<int, 3>> triangles;
  std::istringstream in(binary ? text.substr(0, 84 + 50ull * declared) : text);
  // The format is decided above; CGAL's read_STL() would fall back from one to the other on errors.
  const bool ok = binary ? CGAL::IO::internal::parse_binary_STL(in, points, triangles, false)
                         : CGAL::IO::internal::parse_ASCII_STL(in, points, triangles, false);
  if (!ok)
    throw IoError(name + ": corrupt " + (binary ? std::string("binary") : std::string("ASCII")) +
                  " STL: could not parse " + (binary ? "the triangle records" : "the facet/vertex lines") +
                  " (read " + count_str(triangles.size(), "triangle", "triangles") + " before the error)");
  PolygonSoup soup;
  soup.format = "stl";
  soup.element = "triangle";
  soup.positions.reserve(points.size());
  for (const auto& p : points) soup.positions.emplace_back(p[0], p[1], p[2]);
  for (const auto& t : triangles) {
    soup.indices.insert(soup.indices.end(), {t[0], t[1], t[2]});
    soup.end_polygon();
  }
  soup.welded_by_reader = static_cast<int>(3 * triangles.size() - points.size());
  return soup;
}

}  // namespace adaptex::io_detail
