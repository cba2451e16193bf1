/// \file read_mesh.cpp
/// read_mesh(): dispatch on the file extension to the format readers (read_obj.cpp: tinyobjloader;
/// read_cgal.cpp: OFF/PLY/STL through CGAL's stream readers; read_gltf.cpp: assimp), then the shared
/// validation of mesh_validate.cpp. See docs/io.md for which library reads what and why.
#include <algorithm>

#include "adaptex/core/errors.h"
#include "mesh_soup.h"

namespace adaptex {

namespace {

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace

TriMesh read_mesh(const std::filesystem::path& path, const ReadOptions& options, ReadReport* report) {
  using namespace io_detail;
  const std::string name = path.string();
  const std::string ext = lower_extension(path);
  io_detail::PolygonSoup (*reader)(const std::filesystem::path&) = nullptr;
  if (ext == ".obj") reader = &read_obj_soup;
  else if (ext == ".off") reader = &read_off_soup;
  else if (ext == ".ply") reader = &read_ply_soup;
  else if (ext == ".stl") reader = &read_stl_soup;
  else if (ext == ".gltf" || ext == ".glb") reader = &read_gltf_soup;
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw IoError(name + ": cannot read: file does not exist");
  if (!reader)
    throw IoError(name + ": unknown mesh format '" + (ext.empty() ? std::string("(no extension)") : ext) +
                  "' (supported: .obj .off .ply .stl .gltf .glb)");
  return soup_to_mesh(reader(path), name, options, report).mesh;
}

}  // namespace adaptex
