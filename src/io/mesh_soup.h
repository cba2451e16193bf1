#pragma once
/// \file mesh_soup.h
/// Internal to the io area: the polygon soup every format reader produces, and the shared step that
/// turns it into a validated TriMesh (finite check, index check, fan triangulation, welding, then
/// validate_mesh()). Not installed.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "adaptex/core/mesh.h"
#include "adaptex/io/input_file.h"
#include "adaptex/io/mesh_io.h"

namespace adaptex::io_detail {

/// Polygons as read from a file, before any validation. Indices are 0-based but unchecked.
struct PolygonSoup {
  std::string format;               ///< "obj", "off", "ply", "stl", "gltf", "glb".
  std::vector<Vec3> positions;      ///< V positions in file order.
  std::vector<std::int64_t> offsets{0};  ///< P+1 offsets into indices.
  std::vector<std::int64_t> indices;     ///< Polygon corners (0-based, unchecked).
  std::vector<std::int64_t> tex_indices; ///< Optional: per-corner vt index (OBJ), -1 when absent.
  bool weld = false;                ///< The format splits vertices: weld identical positions.
  int welded_by_reader = 0;         ///< Corners the reader itself merged (CGAL's STL reader welds).
  int index_base = 0;               ///< Base used in the file (1 for OBJ), for messages only.
  std::string element = "face";     ///< What a polygon is called in messages ("face", "triangle").
  std::vector<std::string> warnings;  ///< Reader warnings (file name included), copied to the report.

  std::int64_t num_polygons() const { return static_cast<std::int64_t>(offsets.size()) - 1; }
  void end_polygon() { offsets.push_back(static_cast<std::int64_t>(indices.size())); }
};

/// Result of soup_to_mesh(): the mesh plus where every face and vertex came from (read_textured_obj
/// needs the per-corner vt of the source polygon).
struct SoupMesh {
  TriMesh mesh;
  std::vector<std::array<std::int64_t, 3>> face_corners;  ///< F: soup corner (index into indices).
  std::vector<int> vertex_source;  ///< V: the soup vertex (after welding: first occurrence) of each vertex.
};

/// validate_mesh() with provenance: \p face_source / \p vertex_source are updated in step with the
/// faces and vertices that are dropped, split or compacted (vertex_source of a split copy is the
/// source of the original). Both may be empty (then they are not tracked). \p face_flipped is set
/// to F flags (1 = corners 1 and 2 of the face were swapped to make the winding consistent), or
/// left empty when no face was flipped.
TriMesh validate_tracked(TriMesh mesh, const std::string& name, const ReadOptions& options,
                         ReadReport& report, std::vector<int>& face_source,
                         std::vector<int>& vertex_source, std::vector<char>& face_flipped);

/// Validates and triangulates \p soup (see read_mesh() for the rules). \p name is the file name.
SoupMesh soup_to_mesh(PolygonSoup soup, const std::string& name, const ReadOptions& options,
                      ReadReport* report);

/// Where the bytes given to a format reader came from.
struct SoupSource {
  std::string name;               ///< The file name (or the caller's stand-in), used in every message.
  std::filesystem::path base_dir; ///< Folder that resolves relative references (a glTF's external buffers).
};

/// Format readers (io/read_*.cpp), on the whole file already in memory (read_input_file() or a
/// read_mesh_from_memory() caller's bytes). Each throws IoError for corrupt or truncated input.
PolygonSoup read_obj_soup(const std::string& bytes, const SoupSource& source);
/// The soup of a plain OBJ file (read_obj_plain.cpp: `v x y z`, `vt`, `vn`, `f`, comments and
/// `o`/`g`/`s`/`mtllib`/`usemtl` lines), the same as tinyobjloader's path gives; nullopt for
/// anything else (read_obj_soup() then parses it with tinyobjloader).
std::optional<PolygonSoup> read_plain_obj_soup(const std::string& text);
PolygonSoup read_off_soup(const std::string& bytes, const SoupSource& source);
PolygonSoup read_ply_soup(const std::string& bytes, const SoupSource& source);
PolygonSoup read_stl_soup(const std::string& bytes, const SoupSource& source);
PolygonSoup read_gltf_soup(const std::string& bytes, const SoupSource& source);

/// A polygon soup with texture coordinates (OBJ `vt`, glTF TEXCOORD_0) and materials per corner.
struct TexturedSoup {
  PolygonSoup soup;                   ///< tex_indices set: per corner, an index into texcoords (or -1).
  std::vector<double> texcoords;      ///< 2 per texture coordinate.
  std::vector<int> corner_material;   ///< Per corner: the material of its polygon (-1: none); may be empty.
  int untextured_polygons = 0;        ///< Polygons of a glTF primitive without TEXCOORD_0 (UV (0, 0)).
};

/// Parses OBJ text with tinyobjloader (and re-converts the numbers, see obj_io.cpp). \p mtl_text is the
/// material text tinyobjloader sees at the first `mtllib` (empty: no materials, every corner -1).
TexturedSoup read_obj_data(const std::string& text, const std::string& name, const std::string& mtl_text);

/// The textured mesh of a soup: every corner must have a finite texture coordinate; validation as
/// soup_to_mesh(); wedges are the distinct (texture coordinate, vertex) pairs ordered by texture
/// coordinate index, charts the faces connected through wedges (read_textured_obj()). When
/// \p face_material is given it receives each face's material (from corner_material).
/// \throw IoError, InvalidInputError, TopologyError as read_textured_obj()
TexturedMesh textured_from_soup(TexturedSoup data, const std::string& name, const ReadOptions& options,
                                ReadReport* report, std::vector<int>* face_material);

/// "1 vertex" / "3 vertices": \p n with the singular or plural noun, for messages.
inline std::string count_str(std::int64_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

/// "x, y, z" with shortest round-trip digits, for messages.
std::string format_point(const Vec3& p);

}  // namespace adaptex::io_detail
