/// \file read_obj_plain.cpp
/// A fast reader for the plain OBJ files that scans and exporters write (`v x y z`, `vt`, `vn`, `f`
/// with `v`, `v/vt`, `v//vn`, `v/vt/vn` and negative indices, `#` comment lines, and `o`, `g`, `s`,
/// `mtllib`, `usemtl` lines, which do not change the soup). Anything else (or anything it cannot
/// parse) makes it give up, and read_obj_soup() parses the file with tinyobjloader as before: it
/// yields the same soup as that path (numbers by std::from_chars, as refine_numbers() gives them)
/// in one pass (the read of the 1.09M-face scan of docs/bench_unwrap.md: 5.1 -> 3.6 s).
#include <charconv>
#include <cstring>
#include <system_error>

#include "mesh_soup.h"

namespace adaptex::io_detail {

namespace {

bool blank(char c) { return c == ' ' || c == '\t'; }

/// One line of the text, [p, end), parsed in place.
struct ObjLine {
  const char* p;
  const char* end;

  void skip_blanks() {
    while (p < end && blank(*p)) ++p;
  }
  /// A number up to the next blank (or the line end), optional leading '+'.
  bool number(double& out) {
    skip_blanks();
    if (p < end && *p == '+') ++p;
    const auto res = std::from_chars(p, end, out);
    if (res.ec != std::errc() || (res.ptr < end && !blank(*res.ptr))) return false;
    p = res.ptr;
    return true;
  }
  /// An index of a face corner: a nonzero integer; \p count resolves a negative one (tinyobjloader:
  /// -1 is the last one so far). Stops at '/', a blank or the line end.
  bool index(std::int64_t count, std::int64_t& out) {
    std::int64_t i = 0;
    const auto res = std::from_chars(p, end, i);
    if (res.ec != std::errc() || i == 0 || (res.ptr < end && !blank(*res.ptr) && *res.ptr != '/'))
      return false;
    p = res.ptr;
    out = i > 0 ? i - 1 : count + i;
    return out >= 0;
  }
  bool at_end() {
    skip_blanks();
    return p == end;
  }
};

/// The corners of an `f` statement into \p soup (3 or more; vt index or -1 each).
bool face(ObjLine& line, std::int64_t nv, std::int64_t nvt, PolygonSoup& soup) {
  int corners = 0;
  while (!line.at_end()) {
    std::int64_t v = 0, vt = -1, vn = 0;
    if (!line.index(nv, v)) return false;
    if (line.p < line.end && *line.p == '/') {
      ++line.p;
      if (line.p < line.end && *line.p != '/' && !line.index(nvt, vt)) return false;
      if (line.p < line.end && *line.p == '/') {
        ++line.p;
        if (!line.index(1, vn)) return false;  // the normal's index is not kept
      }
    }
    if (line.p < line.end && !blank(*line.p)) return false;
    soup.indices.push_back(v);
    soup.tex_indices.push_back(vt);
    ++corners;
  }
  if (corners < 3) return false;
  soup.end_polygon();
  return true;
}

/// Whether \p line starts with \p key followed by a blank.
bool keyword(const ObjLine& line, const char* key) {
  const std::size_t n = std::strlen(key);
  return static_cast<std::size_t>(line.end - line.p) > n && std::memcmp(line.p, key, n) == 0 &&
         blank(line.p[n]);
}

}  // namespace

std::optional<PolygonSoup> read_plain_obj_soup(const std::string& text) {
  PolygonSoup soup;
  soup.format = "obj";
  soup.index_base = 1;
  soup.weld = true;
  std::int64_t nvt = 0;
  const char* p = text.data();
  const char* const stop = p + text.size();
  while (p < stop) {
    const char* nl = static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(stop - p)));
    const char* end = nl ? nl : stop;
    ObjLine line{p, end > p && end[-1] == '\r' ? end - 1 : end};
    p = nl ? nl + 1 : stop;
    if (std::memchr(line.p, '\r', static_cast<std::size_t>(line.end - line.p)) ||
        std::memchr(line.p, '\\', static_cast<std::size_t>(line.end - line.p)))
      return std::nullopt;  // a lone carriage return or a line continuation: tinyobjloader decides
    line.skip_blanks();
    if (line.p == line.end || *line.p == '#') continue;
    const auto nv = static_cast<std::int64_t>(soup.positions.size());
    if (keyword(line, "v")) {
      line.p += 1;
      Vec3 x;
      if (!line.number(x[0]) || !line.number(x[1]) || !line.number(x[2]) || !line.at_end())
        return std::nullopt;
      soup.positions.push_back(x);
    } else if (keyword(line, "f")) {
      line.p += 1;
      if (!face(line, nv, nvt, soup)) return std::nullopt;
    } else if (keyword(line, "vt")) {
      ++nvt;
    } else if (!keyword(line, "vn") && !keyword(line, "o") && !keyword(line, "g") &&
               !keyword(line, "s") && !keyword(line, "mtllib") && !keyword(line, "usemtl")) {
      return std::nullopt;
    }
  }
  return soup;
}

}  // namespace adaptex::io_detail
