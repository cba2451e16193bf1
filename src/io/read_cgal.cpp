/// \file read_cgal.cpp
/// STL (ascii and binary) through CGAL 5.5's STL parsers (header-only, Debian libcgal-dev). Binary vs
/// ascii is decided here, and a binary file's triangle count is checked against its size before CGAL
/// sees it. (OFF and PLY have strict readers of their own: read_off.cpp, read_ply.cpp.)
#include <CGAL/IO/STL/STL_reader.h>

#include <cstring>
#include <sstream>
#include <string>

#include "adaptex/core/errors.h"
#include "mesh_soup.h"

namespace adaptex::io_detail {

// ---------------------------------------------------------------------------------------------- STL
PolygonSoup read_stl_soup(const std::string& text, const SoupSource& source) {
  const std::string& name = source.name;
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
                  " (read " + count_str(static_cast<std::int64_t>(triangles.size()), "triangle", "triangles") + " before the error)");
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
