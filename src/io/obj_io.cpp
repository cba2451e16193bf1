/// \file obj_io.cpp
/// Wavefront OBJ: reading through tinyobjloader (double build), reading with texture coordinates into
/// a Parameterization, and writing `v`/`vt`/`f v/vt` at full (shortest round-trip) precision.
///
/// Precision: tinyobjloader's own number parser is not correctly rounded (measured on the shared
/// meshes: 68,690 of armadillo.obj's 129,729 coordinates differ from strtod by 1-2 ulp), and it reads
/// "nan"/"inf" as 0. tinyobjloader still parses the file; the numbers of its `v` and `vt` statements are
/// then converted once more with std::from_chars (correctly rounded, accepts nan/inf so that they are
/// reported), and checked against tinyobjloader's values. See docs/io.md.
#ifndef TINYOBJLOADER_USE_DOUBLE
#define TINYOBJLOADER_USE_DOUBLE
#endif
#include <tiny_obj_loader.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <tuple>

#include "adaptex/core/errors.h"
#include "adaptex/core/union_find.h"
#include "mesh_soup.h"
#include "text_scanner.h"

namespace adaptex {
namespace io_detail {

namespace {

/// First line of a (possibly multi-line) library message, without trailing whitespace.
std::string first_line(const std::string& msg) {
  std::string line = msg.substr(0, msg.find('\n'));
  while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
  return line;
}


/// Re-converts the numbers of every \p key statement ("v" or "vt") of \p text with std::from_chars
/// into \p values (stride \p stride, at most \p per numbers each). Returns false (values untouched)
/// when the statements do not line up with tinyobjloader's; throws IoError on a non-numeric token.
bool refine_numbers(const std::string& name, const std::string& text, const std::string& key, int per,
                    int stride, std::vector<double>& values) {
  std::vector<double> refined(values.size());
  std::size_t count = 0, pos = 0;
  int line_no = 0;
  while (pos < text.size()) {
    ++line_no;
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::size_t p = pos;
    pos = end + 1;
    while (p < end && io_detail::is_line_blank(text[p])) ++p;
    if (text.compare(p, key.size(), key) != 0 || p + key.size() >= end || !io_detail::is_line_blank(text[p + key.size()])) continue;
    p += key.size();
    if ((count + 1) * stride > values.size()) return false;
    for (int k = 0; k < per; ++k) {
      while (p < end && io_detail::is_line_blank(text[p])) ++p;
      if (p >= end || text[p] == '#') break;
      if (text[p] == '+') ++p;
      double d = 0;
      const auto res = std::from_chars(text.data() + p, text.data() + end, d);
      if (res.ec == std::errc::invalid_argument || (res.ptr < text.data() + end && !io_detail::is_line_blank(*res.ptr)))
        throw IoError(name + ": line " + std::to_string(line_no) + ": '" + key + "' statement " +
                      std::to_string(count + 1) + " has a non-numeric coordinate");
      if (res.ec == std::errc::result_out_of_range)
        d = std::strtod(std::string(text.data() + p, res.ptr).c_str(), nullptr);  // overflow -> inf, reported later
      p = static_cast<std::size_t>(res.ptr - text.data());
      const double lib = values[count * stride + k];
      if (std::isfinite(d) && std::abs(d - lib) > 1e-9 * std::max(1.0, std::abs(d))) return false;
      refined[count * stride + k] = d;
    }
    for (int k = per; k < stride; ++k) refined[count * stride + k] = values[count * stride + k];
    ++count;
  }
  if (count * stride != values.size()) return false;
  values = std::move(refined);
  return true;
}

}  // namespace

TexturedSoup read_obj_data(const std::string& text, const std::string& name, const std::string& mtl_text) {
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  // From the text already read: tinyobjloader never opens a `mtllib` file (a material path may name
  // anything, e.g. /dev/zero). The material text, when given, is read_textured_asset()'s list of the
  // material names; tinyobjloader only maps `usemtl` to them.
  if (!reader.ParseFromString(text, mtl_text, config))
    throw IoError(name + ": corrupt OBJ: " + first_line(reader.Error().empty() ? "tinyobjloader failed" : reader.Error()));
  TexturedSoup data;
  PolygonSoup& soup = data.soup;
  soup.format = "obj";
  soup.index_base = 1;
  soup.weld = true;
  const auto& attrib = reader.GetAttrib();
  std::vector<double> xyz(attrib.vertices.begin(), attrib.vertices.end());
  if (!refine_numbers(name, text, "v", 3, 3, xyz))
    soup.warnings.push_back(name + ": could not match the 'v' lines to tinyobjloader's vertices; positions "
                                   "keep tinyobjloader's rounding (within 2 ulp)");
  soup.positions.reserve(xyz.size() / 3);
  for (std::size_t i = 0; i + 2 < xyz.size(); i += 3) soup.positions.emplace_back(xyz[i], xyz[i + 1], xyz[i + 2]);
  data.texcoords.assign(attrib.texcoords.begin(), attrib.texcoords.end());
  if (!data.texcoords.empty() && !refine_numbers(name, text, "vt", 2, 2, data.texcoords))
    soup.warnings.push_back(name + ": could not match the 'vt' lines to tinyobjloader's texture coordinates; "
                                   "they keep tinyobjloader's rounding");
  for (const auto& shape : reader.GetShapes()) {
    std::size_t c = 0;
    for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      const unsigned n = shape.mesh.num_face_vertices[f];
      const int material = f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1;
      for (unsigned k = 0; k < n; ++k, ++c) {
        soup.indices.push_back(shape.mesh.indices[c].vertex_index);
        soup.tex_indices.push_back(shape.mesh.indices[c].texcoord_index);
        data.corner_material.push_back(material);
      }
      soup.end_polygon();
    }
  }
  return data;
}

PolygonSoup read_obj_soup(const std::string& bytes, const SoupSource& source) {
  if (std::optional<PolygonSoup> plain = read_plain_obj_soup(bytes)) return std::move(*plain);
  return read_obj_data(bytes, source.name, std::string()).soup;
}

TexturedMesh textured_from_soup(TexturedSoup data, const std::string& name, const ReadOptions& options,
                                ReadReport* report, std::vector<int>* face_material) {
  const PolygonSoup& soup = data.soup;
  const auto nt = static_cast<std::int64_t>(data.texcoords.size() / 2);
  for (std::int64_t p = 0; p < soup.num_polygons(); ++p)
    for (std::int64_t c = soup.offsets[p]; c < soup.offsets[p + 1]; ++c) {
      const std::int64_t t = soup.tex_indices[c];
      if (t < 0)
        throw InvalidInputError(name + ": face " + std::to_string(p + 1) +
                                " has no texture coordinates (expected 'f v/vt ...'; the file has " +
                                std::to_string(nt) + " vt)");
      if (t >= nt)
        throw InvalidInputError(name + ": face " + std::to_string(p + 1) + " refers to vt " + std::to_string(t + 1) +
                                ", out of range (the file has " + std::to_string(nt) + " vt)");
    }
  for (std::int64_t t = 0; t < nt; ++t)
    if (!std::isfinite(data.texcoords[2 * t]) || !std::isfinite(data.texcoords[2 * t + 1]))
      throw InvalidInputError(name + (soup.format == "obj" ? ": vt " : ": texture coordinate ") + std::to_string(t + 1) +
                              " is not finite (" +
                              std::to_string(data.texcoords[2 * t]) + ", " +
                              std::to_string(data.texcoords[2 * t + 1]) + ")");
  const std::vector<std::int64_t> tex = soup.tex_indices;
  SoupMesh sm = soup_to_mesh(std::move(data.soup), name, options, report);

  TexturedMesh out;
  out.mesh = std::move(sm.mesh);
  const int nf = out.mesh.num_faces();
  if (face_material) {
    face_material->resize(nf);
    for (int f = 0; f < nf; ++f)
      (*face_material)[f] = data.corner_material.empty() ? -1 : data.corner_material[sm.face_corners[f][0]];
  }
  // Wedges: distinct (vt, vertex) pairs ordered by vt, then by first use.
  Parameterization& param = out.param;
  std::map<std::pair<std::int64_t, int>, int> wedge_of;
  {
    std::map<std::pair<std::int64_t, int>, int> first_corner;
    for (int f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k)
        first_corner.emplace(std::make_pair(tex[sm.face_corners[f][k]], out.mesh.faces[f][k]), 3 * f + k);
    std::vector<std::tuple<std::int64_t, int, int>> keys;  // (vt, first corner, vertex)
    keys.reserve(first_corner.size());
    for (const auto& [key, corner] : first_corner) keys.emplace_back(key.first, corner, key.second);
    std::sort(keys.begin(), keys.end());
    param.uv.reserve(keys.size());
    for (const auto& [t, corner, v] : keys) {
      wedge_of[{t, v}] = param.num_wedges();
      param.uv.emplace_back(data.texcoords[2 * t], data.texcoords[2 * t + 1]);
      param.wedge_vertex.push_back(v);
    }
  }
  param.uv_faces.resize(nf);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k)
      param.uv_faces[f][k] = wedge_of.at({tex[sm.face_corners[f][k]], out.mesh.faces[f][k]});
  // Charts: faces connected through shared wedges.
  UnionFind wedges(param.num_wedges());
  for (const Face& t : param.uv_faces) {
    wedges.unite(t[0], t[1]);
    wedges.unite(t[0], t[2]);
  }
  std::vector<int> chart_of_root(param.num_wedges(), -1);
  param.face_chart.resize(nf);
  for (int f = 0; f < nf; ++f) {
    int& c = chart_of_root[wedges.find(param.uv_faces[f][0])];
    if (c < 0) c = param.num_charts++;
    param.face_chart[f] = c;
  }
  return out;
}

}  // namespace io_detail

TexturedMesh read_textured_obj(const std::filesystem::path& path, const ReadOptions& options, ReadReport* report) {
  using namespace io_detail;
  const std::string name = path.string();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw IoError(name + ": cannot read: file does not exist");
  return textured_from_soup(read_obj_data(read_input_file(path), name, std::string()), name, options, report, nullptr);
}

namespace {

void append_number(std::string& out, double x) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, x);
  out.append(buf, res.ptr);
}

void append_int(std::string& out, long x) {
  char buf[24];
  const auto res = std::to_chars(buf, buf + sizeof buf, x);
  out.append(buf, res.ptr);
}

/// Writes the lines of items [0, n) to \p file, formatted by \p line(i, text) in blocks of
/// kWriteBlock items: kWriteBatch blocks at a time in parallel (TBB), written in order. The same
/// bytes as one loop, with at most one batch of text in memory (not the whole file).
constexpr std::size_t kWriteBlock = 1 << 15;
constexpr std::size_t kWriteBatch = 16;
template <class Line>
void write_lines(std::ofstream& file, std::size_t n, std::size_t bytes_per_item, const Line& line) {
  std::vector<std::string> blocks(kWriteBatch);
  for (std::size_t first = 0; first < n; first += kWriteBlock * kWriteBatch) {
    const std::size_t count = std::min(kWriteBatch, (n - first + kWriteBlock - 1) / kWriteBlock);
    tbb::parallel_for(std::size_t{0}, count, [&](std::size_t b) {
      std::string& text = blocks[b];
      const std::size_t begin = first + b * kWriteBlock, end = std::min(n, begin + kWriteBlock);
      text.clear();
      text.reserve((end - begin) * bytes_per_item);
      for (std::size_t i = begin; i < end; ++i) line(i, text);
    });
    for (std::size_t b = 0; b < count; ++b) file.write(blocks[b].data(), static_cast<std::streamsize>(blocks[b].size()));
  }
}

/// write_obj() of both forms: face f uses materials[face_material[f]] (all materials[0] when
/// face_material is empty); a `usemtl` starts every run of faces of one material.
void write_obj_materials(const std::filesystem::path& path, const TriMesh& mesh, const Parameterization* param,
                         const std::optional<std::string>& mtllib, const std::vector<std::string>& materials,
                         const std::vector<int>& face_material) {
  const std::string name = path.string();
  if (param && param->uv_faces.size() != mesh.faces.size())
    throw InvalidInputError(name + ": write_obj: the parameterization has " + std::to_string(param->uv_faces.size()) +
                            " UV faces but the mesh has " + std::to_string(mesh.faces.size()) + " faces");
  if (!face_material.empty() && face_material.size() != mesh.faces.size())
    throw InvalidInputError(name + ": write_obj: " + std::to_string(face_material.size()) + " face materials for " +
                            std::to_string(mesh.faces.size()) + " faces");
  const auto material_of = [&](std::size_t f) { return face_material.empty() ? 0 : face_material[f]; };
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    if (material_of(f) < 0 || material_of(f) >= static_cast<int>(materials.size()))
      throw InvalidInputError(name + ": write_obj: face " + std::to_string(f) + " has no material");
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!file) throw OutputError(name + ": cannot open for writing");
  std::string head = "# written by adaptex: v = input positions (shortest round-trip digits)";
  head += param ? ", vt = UV layout, f v/vt\n" : "\n";
  if (mtllib) head += "mtllib " + *mtllib + "\n";
  file.write(head.data(), static_cast<std::streamsize>(head.size()));
  write_lines(file, mesh.positions.size(), 64, [&](std::size_t i, std::string& text) {
    const Vec3& p = mesh.positions[i];
    text += "v ";
    append_number(text, p.x());
    text += ' ';
    append_number(text, p.y());
    text += ' ';
    append_number(text, p.z());
    text += '\n';
  });
  if (param)
    write_lines(file, param->uv.size(), 40, [&](std::size_t i, std::string& text) {
      const Vec2& t = param->uv[i];
      text += "vt ";
      append_number(text, t.x());
      text += ' ';
      append_number(text, t.y());
      text += '\n';
    });
  write_lines(file, mesh.faces.size(), 40, [&](std::size_t f, std::string& text) {
    const int m = material_of(f);
    if (mtllib && (f == 0 || m != material_of(f - 1))) text += "usemtl " + materials[m] + "\n";
    text += 'f';
    for (int k = 0; k < 3; ++k) {
      text += ' ';
      append_int(text, mesh.faces[f][k] + 1L);
      if (param) {
        text += '/';
        append_int(text, param->uv_faces[f][k] + 1L);
      }
    }
    text += '\n';
  });
  file.close();
  if (!file) throw OutputError(name + ": write failed (disk full?)");
}

}  // namespace

void write_obj(const std::filesystem::path& path, const TriMesh& mesh, const Parameterization* param,
               const std::optional<std::string>& mtllib, const std::string& material) {
  write_obj_materials(path, mesh, param, mtllib, {material}, {});
}

void write_obj(const std::filesystem::path& path, const TriMesh& mesh, const Parameterization& param,
               const std::string& mtllib, const std::vector<std::string>& materials,
               const std::vector<int>& face_material) {
  write_obj_materials(path, mesh, &param, mtllib, materials, face_material);
}

}  // namespace adaptex
