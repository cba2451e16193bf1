/// \file read_gltf.cpp
/// glTF 2.0 (.gltf with its buffers, .glb) through assimp, without post-processing: every triangle
/// primitive of every node instance, placed by the node's world transform (applied in double; identity
/// transforms leave the float32 positions of the file bit-exact). Primitives split vertices (per
/// attribute set), so the soup is welded by identical position afterwards.
#include <assimp/Importer.hpp>
#include <assimp/scene.h>

#include <Eigen/Dense>

#include "adaptex/core/errors.h"
#include "mesh_soup.h"

namespace adaptex::io_detail {

namespace {

Eigen::Matrix4d to_eigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  out << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4;
  return out;
}

void collect(const aiScene* scene, const aiNode* node, const Eigen::Matrix4d& parent, PolygonSoup& soup,
             int& skipped_primitives) {
  const Eigen::Matrix4d world = parent * to_eigen(node->mTransformation);
  const bool identity = world.isIdentity(0.0);
  for (unsigned i = 0; i < node->mNumMeshes; ++i) {
    const aiMesh* mesh = scene->mMeshes[node->mMeshes[i]];
    const auto base = static_cast<std::int64_t>(soup.positions.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      Eigen::Vector4d q(p.x, p.y, p.z, 1.0);
      if (!identity) q = world * q;
      soup.positions.emplace_back(q.x(), q.y(), q.z());
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices < 3) {
        ++skipped_primitives;
        continue;
      }
      for (unsigned k = 0; k < face.mNumIndices; ++k) soup.indices.push_back(base + face.mIndices[k]);
      soup.end_polygon();
    }
  }
  for (unsigned c = 0; c < node->mNumChildren; ++c) collect(scene, node->mChildren[c], world, soup, skipped_primitives);
}

}  // namespace

PolygonSoup read_gltf_soup(const std::filesystem::path& path) {
  const std::string name = path.string();
  (void)read_file_text(path);  // existence, readability and emptiness, with our messages
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path.string(), 0);
  if (!scene || !scene->mRootNode) {
    std::string err = importer.GetErrorString();
    for (char& c : err)
      if (c == '\n' || c == '\r') c = ' ';
    throw IoError(name + ": corrupt glTF: " + (err.empty() ? std::string("assimp could not read it") : err));
  }
  PolygonSoup soup;
  soup.format = path.extension() == ".glb" || path.extension() == ".GLB" ? "glb" : "gltf";
  soup.weld = true;
  int skipped = 0;
  collect(scene, scene->mRootNode, Eigen::Matrix4d::Identity(), soup, skipped);
  if (skipped > 0)
    soup.warnings.push_back(name + ": ignored " + std::to_string(skipped) + " point/line primitives");
  return soup;
}

}  // namespace adaptex::io_detail
