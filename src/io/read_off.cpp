/// \file read_off.cpp
/// OFF (incl. COFF/NOFF/STOFF/4OFF/nOFF with n = 3, CRLF line ends, '#' comments): a strict reader of
/// its own. CGAL's File_scanner_OFF, used before, crashed on an out-of-range colour-map index and read
/// negative counts and indices as huge unsigned numbers; this reader checks every count
/// against the bytes left in the file before allocating. Like CGAL's scanner, a vertex is its
/// coordinates followed by anything up to the line end (normals, colours, texture coordinates: skipped),
/// and a face is its corner count, the corner indices, then anything up to the line end (a colour).
/// Numbers are converted with std::from_chars: correctly rounded, so positions are the file's values.
#include <cmath>
#include <string>

#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "mesh_soup.h"
#include "text_scanner.h"

namespace adaptex::io_detail {

namespace {

/// What the header keyword ([ST][C][N][4][n]OFF) says.
struct OffHeader {
  bool texture = false;      ///< 'ST': s t at the end of each vertex line.
  bool color = false;        ///< 'C': a colour per vertex.
  bool normal = false;       ///< 'N': nx ny nz after the coordinates.
  bool homogeneous = false;  ///< '4': x y z w per vertex.
  bool dimension = false;    ///< 'n': a dimension number follows the keyword.
};

bool parse_keyword(std::string_view k, OffHeader& h) {
  for (bool* flag : {&h.texture, &h.color, &h.normal}) {
    const std::string_view prefix = flag == &h.texture ? "ST" : flag == &h.color ? "C" : "N";
    *flag = k.substr(0, prefix.size()) == prefix;
    if (*flag) k.remove_prefix(prefix.size());
  }
  if (!k.empty() && k.front() == '4') {
    h.homogeneous = true;
    k.remove_prefix(1);
  }
  if (!k.empty() && k.front() == 'n') {
    h.dimension = true;
    k.remove_prefix(1);
  }
  return k == "OFF";
}

/// Reads the keyword and the vertex / face / edge counts; checks them against the bytes left.
void read_off_header(const std::string& name, TextScanner& s, OffHeader& h, std::int64_t& nv, std::int64_t& nf) {
  const std::string bad = name + ": not a valid OFF file: bad header (expected [C][N]OFF followed by the vertex, face "
                                 "and edge counts)";
  if (!parse_keyword(s.token(), h)) throw IoError(bad);
  const std::size_t after_keyword = s.pos;
  if (s.token() == "BINARY") throw IoError(name + ": binary OFF is not supported (only the text form)");
  s.pos = after_keyword;
  if (h.dimension) {
    std::int64_t dim = 0;
    if (!parse_int(s.token(), dim)) throw IoError(bad);
    if (dim != 3) throw IoError(name + ": OFF of dimension " + std::to_string(dim) + " (only 3 is supported)");
  }
  std::int64_t ne = 0;
  if (!parse_int(s.token(), nv) || !parse_int(s.token(), nf)) throw IoError(bad);
  const std::size_t after_counts = s.pos;
  if (!parse_int(s.token(), ne)) s.pos = after_counts;  // the edge count is optional and ignored
  if (nv < 0 || nf < 0)
    throw IoError(name + ": not a valid OFF file: negative count in the header (" + std::to_string(nv) +
                  " vertices, " + std::to_string(nf) + " faces)");
  // A vertex takes at least 6 bytes ("0 0 0\n"), a face at least 2 ("0\n").
  const auto left = static_cast<std::int64_t>(s.bytes_left());
  const int per_vertex = h.homogeneous ? 8 : 6;
  if (nv > left / per_vertex || nf > (left - nv * per_vertex) / 2)
    throw IoError(name + ": the OFF header claims " + count_str(nv, "vertex", "vertices") + " and " +
                  count_str(nf, "face", "faces") + ", more than the " + std::to_string(left) +
                  " bytes left in the file can hold (file truncated or corrupt)");
}

/// Checks a colour: 3 or 4 numbers, or one colour-map index in [0, 255] (Geomview's map has 256
/// entries; CGAL's scanner, used before, indexed its map with any value and crashed). \p tokens may
/// be empty (no colour given).
void check_color(const std::vector<std::string_view>& tokens, const std::string& what) {
  double x = 0;
  for (std::string_view t : tokens)
    if (!parse_double(t, x) || !std::isfinite(x)) throw IoError(what + " has a colour value that is not a finite number");
  std::int64_t index = 0;
  if (tokens.size() == 1 && (!parse_int(tokens[0], index) || index < 0 || index > 255))
    throw IoError(what + ": colour index " + std::string(tokens[0]) + " is out of range (a colour-map index is 0..255)");
}

/// The colour tokens of a vertex line's rest (after the coordinates): normals first, texture
/// coordinates last.
std::vector<std::string_view> vertex_color(std::vector<std::string_view> rest, const OffHeader& h) {
  if (!h.color) return {};
  const std::size_t normals = h.normal ? std::min<std::size_t>(3, rest.size()) : 0;
  rest.erase(rest.begin(), rest.begin() + static_cast<std::ptrdiff_t>(normals));
  if (h.texture) rest.resize(rest.size() >= 2 ? rest.size() - 2 : 0);
  return rest;
}

}  // namespace

PolygonSoup read_off_soup(const std::string& text, const SoupSource& source) {
  const std::string& name = source.name;
  TextScanner s{text, 0, true};
  OffHeader h;
  std::int64_t nv = 0, nf = 0;
  read_off_header(name, s, h, nv, nf);
  const std::string counts =
      " (the header says " + count_str(nv, "vertex", "vertices") + ", " + count_str(nf, "face", "faces") + ")";
  PolygonSoup soup;
  soup.format = "off";
  soup.positions.reserve(static_cast<std::size_t>(nv));
  soup.offsets.reserve(static_cast<std::size_t>(nf) + 1);
  for (std::int64_t v = 0; v < nv; ++v) {
    double c[4] = {0, 0, 0, 1};
    for (int k = 0; k < (h.homogeneous ? 4 : 3); ++k)
      if (!parse_double(s.token(), c[k]))
        throw IoError(name + ": vertex " + std::to_string(v) + " is missing or not numeric: file truncated, or " +
                      "fewer vertex lines than the header says" + counts);
    check_color(vertex_color(s.rest_of_line(), h), name + ": vertex " + std::to_string(v));
    soup.positions.emplace_back(c[0] / c[3], c[1] / c[3], c[2] / c[3]);
  }
  for (std::int64_t f = 0; f < nf; ++f) {
    std::int64_t n = 0;
    if (!parse_int(s.token(), n) || n < 0)
      throw IoError(name + ": face " + std::to_string(f) + " is missing or unreadable: file truncated, or fewer " +
                    "vertex or face lines than the header says" + counts);
    if (n > static_cast<std::int64_t>(s.bytes_left() / 2))
      throw IoError(name + ": face " + std::to_string(f) + " claims " + std::to_string(n) + " corners, more than the " +
                    std::to_string(s.bytes_left()) + " bytes left in the file can hold");
    for (std::int64_t j = 0; j < n; ++j) {
      std::int64_t idx = 0;
      const std::string_view t = s.token();
      if (t.empty())
        throw IoError(name + ": face " + std::to_string(f) + " lists fewer vertex indices than its count " +
                      std::to_string(n) + " (file truncated or corrupt)");
      if (!parse_int(t, idx) || idx < 0 || idx >= nv)
        throw InvalidInputError(name + ": face " + std::to_string(f) + " refers to a vertex index out of range " +
                                "(the file has " + count_str(nv, "vertex", "vertices") + ", numbered from 0)");
      soup.indices.push_back(idx);
    }
    check_color(s.rest_of_line(), name + ": face " + std::to_string(f));
    soup.end_polygon();
  }
  return soup;
}

}  // namespace adaptex::io_detail
