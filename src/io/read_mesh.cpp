/// \file read_mesh.cpp
/// read_mesh() and read_mesh_from_memory(): the file checks (read_input_file()), then dispatch on the
/// format to the readers (obj_io.cpp: tinyobjloader; read_off.cpp, read_ply.cpp: strict readers of
/// adaptex; read_cgal.cpp: STL through CGAL's parsers; read_gltf.cpp: assimp after checks), then the
/// shared validation of mesh_validate.cpp. Both entry points run the same code after the file checks.
/// See docs/io.md for which library reads what and why.
#include <algorithm>

#include "adaptex/core/errors.h"
#include "mesh_soup.h"

namespace adaptex {

namespace {

using SoupReader = io_detail::PolygonSoup (*)(const std::string&, const io_detail::SoupSource&);

/// "obj" / ".OBJ" -> ".obj".
std::string normalized_format(const std::string& format) {
  std::string ext = format.empty() || format[0] == '.' ? format : "." + format;
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

/// The reader of \p ext (normalized_format()). \throw IoError unknown format
SoupReader reader_for(const std::string& ext, const std::string& name) {
  using namespace io_detail;
  if (ext == ".obj") return &read_obj_soup;
  if (ext == ".off") return &read_off_soup;
  if (ext == ".ply") return &read_ply_soup;
  if (ext == ".stl") return &read_stl_soup;
  if (ext == ".gltf" || ext == ".glb") return &read_gltf_soup;
  throw IoError(name + ": unknown mesh format '" + (ext.empty() ? std::string("(no extension)") : ext) +
                "' (supported: .obj .off .ply .stl .gltf .glb)");
}

}  // namespace

TriMesh read_mesh(const std::filesystem::path& path, const ReadOptions& options, ReadReport* report) {
  const std::string name = path.string();
  const std::string ext = normalized_format(path.extension().string());
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw IoError(name + ": cannot read: file does not exist");
  (void)reader_for(ext, name);  // an unknown format is reported before the file is read
  return read_mesh_from_memory(read_input_file(path), ext, path, options, report);
}

TriMesh read_mesh_from_memory(const std::string& bytes, const std::string& format, const std::filesystem::path& name,
                              const ReadOptions& options, ReadReport* report) {
  const std::string file = name.string();
  const SoupReader reader = reader_for(normalized_format(format), file);
  check_input_size(bytes.size(), file);
  return io_detail::soup_to_mesh(reader(bytes, {file, name.parent_path()}), file, options, report).mesh;
}

}  // namespace adaptex
