/// \file read_ply.cpp
/// PLY (ascii, binary little and big endian; `face`/`faces` with `vertex_indices`/`vertex_index` of any
/// integer type; `element tristrips`): a strict reader of its own. CGAL's PLY_reader, used before,
/// crashed on a property declared before any element and allocated whatever a list count claimed
/// (2^31 entries, or a negative count read as a huge size). Here every element count and
/// every list count is checked against the bytes left in the file before anything is allocated.
/// Ascii numbers are converted with std::from_chars (correctly rounded doubles, also for properties
/// declared `float`: the file's decimal text is kept), binary numbers bit-exactly.
#include <bit>
#include <cstring>
#include <string>

#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "mesh_soup.h"
#include "text_scanner.h"

namespace adaptex::io_detail {

namespace {

enum class PlyFormat { Ascii, BinaryLE, BinaryBE };

/// A scalar type: size in bytes, integer or not, signed or not.
struct PlyType {
  int size = 0;
  bool integer = true;
  bool is_signed = false;
};

bool ply_type(const std::string& t, PlyType& out) {
  struct Entry { const char* a; const char* b; PlyType type; };
  static const Entry table[] = {{"char", "int8", {1, true, true}},      {"uchar", "uint8", {1, true, false}},
                                {"short", "int16", {2, true, true}},    {"ushort", "uint16", {2, true, false}},
                                {"int", "int32", {4, true, true}},      {"uint", "uint32", {4, true, false}},
                                {"float", "float32", {4, false, true}}, {"double", "float64", {8, false, true}}};
  for (const Entry& e : table)
    if (t == e.a || t == e.b) {
      out = e.type;
      return true;
    }
  return false;
}

struct PlyProperty {
  std::string name;
  bool list = false;
  PlyType count_type;  ///< For lists.
  PlyType type;        ///< Scalar type, or the list's entry type.
};

struct PlyElement {
  std::string name;
  std::int64_t count = 0;
  std::vector<PlyProperty> properties;
  /// Fewest bytes one item can take (binary: scalars + list counts; ascii: 2 per property).
  std::int64_t min_item_bytes(PlyFormat f) const {
    std::int64_t n = 0;
    for (const auto& p : properties) n += f == PlyFormat::Ascii ? 2 : (p.list ? p.count_type.size : p.type.size);
    return n;
  }
  int find(const std::string& prop) const {
    for (std::size_t k = 0; k < properties.size(); ++k)
      if (properties[k].name == prop) return static_cast<int>(k);
    return -1;
  }
};

struct PlyHeader {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
  std::size_t data_start = 0;  ///< Offset of the first byte after the end_header line.
};

PlyHeader parse_ply_header(const std::string& name, const std::string& text) {
  const std::string corrupt = name + ": corrupt PLY header: ";
  PlyHeader h;
  std::size_t pos = 0;
  bool have_format = false;
  for (int line_no = 1;; ++line_no) {
    const std::size_t nl = text.find('\n', pos);
    if (nl == std::string::npos) throw IoError(corrupt + "no 'end_header' line");
    std::string line = text.substr(pos, nl - pos);
    pos = nl + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    TextScanner s{line, 0, false};
    const std::string key(s.token());
    const std::string where = "line " + std::to_string(line_no) + ": ";
    if (line_no == 1) {
      if (key != "ply") throw IoError(name + ": not a PLY file (it does not start with 'ply')");
    } else if (key == "end_header") {
      break;
    } else if (key == "format") {
      const std::string f(s.token());
      if (f == "ascii") h.format = PlyFormat::Ascii;
      else if (f == "binary_little_endian") h.format = PlyFormat::BinaryLE;
      else if (f == "binary_big_endian") h.format = PlyFormat::BinaryBE;
      else throw IoError(corrupt + where + "unknown format '" + f + "'");
      have_format = true;
    } else if (key == "element") {
      PlyElement e;
      e.name = std::string(s.token());
      if (e.name.empty() || !parse_int(s.token(), e.count) || e.count < 0)
        throw IoError(corrupt + where + "expected 'element NAME COUNT' with COUNT >= 0");
      h.elements.push_back(std::move(e));
    } else if (key == "property") {
      if (h.elements.empty()) throw IoError(corrupt + where + "a property is declared before any element");
      PlyProperty p;
      std::string t(s.token());
      if (t == "list") {
        p.list = true;
        const std::string ct(s.token());
        if (!ply_type(ct, p.count_type) || !p.count_type.integer)
          throw IoError(corrupt + where + "list count type '" + ct + "' is not an integer type");
        t = std::string(s.token());
      }
      if (!ply_type(t, p.type)) throw IoError(corrupt + where + "unknown property type '" + t + "'");
      p.name = std::string(s.token());
      if (p.name.empty()) throw IoError(corrupt + where + "property without a name");
      h.elements.back().properties.push_back(std::move(p));
    } else if (key != "comment" && key != "obj_info" && !key.empty()) {
      throw IoError(corrupt + where + "unknown keyword '" + key + "'");
    }
  }
  if (!have_format) throw IoError(corrupt + "no 'format' line");
  h.data_start = pos;
  return h;
}

/// Reads the values of a PLY body, binary or ascii, keeping track of the bytes left.
class PlyBody {
 public:
  PlyBody(const std::string& text, std::size_t start, PlyFormat f) : s_{text, start, false}, format_(f) {}

  bool read(const PlyType& t, double& out) {
    if (format_ == PlyFormat::Ascii) {
      const std::string_view tok = s_.token();
      if (!t.integer) return parse_double(tok, out);
      std::int64_t i = 0;
      if (!parse_int(tok, i)) return false;
      out = static_cast<double>(i);
      return true;
    }
    if (s_.bytes_left() < static_cast<std::size_t>(t.size)) return false;
    unsigned char b[8];
    std::memcpy(b, s_.text.data() + s_.pos, static_cast<std::size_t>(t.size));
    s_.pos += static_cast<std::size_t>(t.size);
    if ((format_ == PlyFormat::BinaryBE) == (std::endian::native == std::endian::little))
      for (int i = 0; i < t.size / 2; ++i) std::swap(b[i], b[t.size - 1 - i]);
    out = decode(t, b);
    return true;
  }
  std::size_t bytes_left() const { return s_.bytes_left(); }
  PlyFormat format() const { return format_; }

 private:
  static double decode(const PlyType& t, const unsigned char* b) {
    if (!t.integer) {
      if (t.size == 4) return static_cast<double>(load<float>(b));
      return load<double>(b);
    }
    switch (t.size) {
      case 1: return t.is_signed ? load<std::int8_t>(b) : load<std::uint8_t>(b);
      case 2: return t.is_signed ? load<std::int16_t>(b) : load<std::uint16_t>(b);
      default: return t.is_signed ? load<std::int32_t>(b) : static_cast<double>(load<std::uint32_t>(b));
    }
  }
  template <class T>
  static T load(const unsigned char* b) {
    T x;
    std::memcpy(&x, b, sizeof(T));
    return x;
  }
  TextScanner s_;
  PlyFormat format_;
};

/// Appends the triangles of a strip list (-1 restarts a strip; every odd triangle swaps its first two
/// corners so that all keep the strip's orientation; triangles with a repeated index are skipped).
void append_strips(const std::vector<std::int64_t>& list, PolygonSoup& soup) {
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

/// What one element contributes: positions (the first vertex element) or polygons (face / tristrips).
struct ElementRole {
  bool vertex = false, face = false, strip = false;
  int xyz[3] = {-1, -1, -1};
  int index = -1;  ///< The vertex_indices list.
};

ElementRole element_role(const std::string& name, const PlyElement& el, bool have_vertices) {
  ElementRole r;
  r.vertex = (el.name == "vertex" || el.name == "vertices") && !have_vertices;
  r.face = el.name == "face" || el.name == "faces";
  r.strip = el.name == "tristrips";
  if (r.vertex)
    for (int k = 0; k < 3; ++k) {
      const char* c = k == 0 ? "x" : k == 1 ? "y" : "z";
      r.xyz[k] = el.find(c);
      if (r.xyz[k] < 0 || el.properties[r.xyz[k]].list || el.properties[r.xyz[k]].type.integer)
        throw IoError(name + ": PLY vertex element has no float or double property '" + c + "'");
    }
  if (r.face || r.strip) {
    r.index = el.find("vertex_indices");
    if (r.index < 0) r.index = el.find("vertex_index");
    if (r.index < 0) throw IoError(name + ": PLY element '" + el.name + "' has no 'vertex_indices' list property");
    const PlyProperty& p = el.properties[r.index];
    if (!p.list || !p.type.integer)
      throw IoError(name + ": PLY element '" + el.name + "': '" + p.name + "' is not an integer list");
  }
  return r;
}

void read_element(const std::string& name, const PlyElement& el, const ElementRole& role, PlyBody& body,
                  PolygonSoup& soup) {
  std::vector<std::int64_t> list;
  const std::string n_str = std::to_string(el.count);
  for (std::int64_t j = 0; j < el.count; ++j) {
    Vec3 pos(0, 0, 0);
    for (std::size_t k = 0; k < el.properties.size(); ++k) {
      const PlyProperty& p = el.properties[k];
      // The message start, made only for an error (not once per item and property).
      const auto item = [&] {
        return name + ": PLY truncated or corrupt: element '" + el.name + "' item " + std::to_string(j) +
               " of " + n_str + " (property '" + p.name + "')";
      };
      double value = 0;
      if (!body.read(p.list ? p.count_type : p.type, value)) throw IoError(item() + " could not be read");
      if (!p.list) {
        for (int c = 0; c < 3; ++c)
          if (static_cast<int>(k) == role.xyz[c]) pos[c] = value;
        continue;
      }
      const int min_entry = body.format() == PlyFormat::Ascii ? 2 : p.type.size;
      if (value < 0 || value > static_cast<double>(body.bytes_left() / min_entry))
        throw IoError(item() + ": the list claims " + std::to_string(static_cast<std::int64_t>(value)) +
                      " entries, more than the " + std::to_string(body.bytes_left()) + " bytes left can hold");
      const auto count = static_cast<std::int64_t>(value);
      const bool keep = static_cast<int>(k) == role.index;
      if (keep) list.clear();
      for (std::int64_t e = 0; e < count; ++e) {
        if (!body.read(p.type, value)) throw IoError(item() + " could not be read");
        if (keep) list.push_back(static_cast<std::int64_t>(value));
      }
    }
    if (role.vertex) soup.positions.push_back(pos);
    if (role.face) {
      soup.indices.insert(soup.indices.end(), list.begin(), list.end());
      soup.end_polygon();
    }
    if (role.strip) append_strips(list, soup);
  }
}

}  // namespace

PolygonSoup read_ply_soup(const std::string& text, const SoupSource& source) {
  const std::string& name = source.name;
  if (text.rfind("ply", 0) != 0) throw IoError(name + ": not a PLY file (it does not start with 'ply')");
  const PlyHeader h = parse_ply_header(name, text);
  // Every element count against the bytes after the header, before anything is allocated.
  std::int64_t left = static_cast<std::int64_t>(text.size() - h.data_start);
  for (const PlyElement& el : h.elements) {
    const std::int64_t per = el.min_item_bytes(h.format);
    if (el.count > static_cast<std::int64_t>(kMaxMeshElements) || (per > 0 && el.count > left / per))
      throw IoError(name + ": the PLY header claims " + std::to_string(el.count) + " '" + el.name + "' items, more " +
                    "than the " + std::to_string(text.size() - h.data_start) + " bytes after the header can hold");
    left -= el.count * per;
  }
  PolygonSoup soup;
  soup.format = "ply";
  bool have_vertices = false, have_faces = false;
  PlyBody body(text, h.data_start, h.format);
  for (const PlyElement& el : h.elements) {
    const ElementRole role = element_role(name, el, have_vertices);
    if (role.vertex) soup.positions.reserve(static_cast<std::size_t>(el.count));
    have_vertices = have_vertices || role.vertex;
    have_faces = have_faces || role.face || role.strip;
    if (!el.properties.empty()) read_element(name, el, role, body, soup);
  }
  if (!have_vertices) throw IoError(name + ": PLY file has no 'vertex' element");
  if (!have_faces)
    throw InvalidInputError(name + ": no faces: the PLY file has no 'face' or 'tristrips' element (" +
                            std::to_string(soup.positions.size()) +
                            (soup.positions.size() == 1 ? " vertex)" : " vertices)"));
  return soup;
}

}  // namespace adaptex::io_detail
