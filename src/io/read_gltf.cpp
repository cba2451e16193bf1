/// \file read_gltf.cpp
/// glTF 2.0 (.gltf with its buffers, .glb) through assimp, without post-processing: every triangle
/// primitive of every node instance, placed by the node's world transform (applied in double; identity
/// transforms leave the float32 positions of the file bit-exact). Primitives split vertices (per
/// attribute set), so the soup is welded by identical position afterwards.
///
/// assimp trusts the file: a forged GLB chunk length made it allocate 4 GB, and it guesses the format
/// from the content, so any file named .glb reached every assimp importer. So before assimp
/// sees a file, check_gltf() requires real glTF 2.0 (the GLB container, or a JSON object with
/// asset.version 2.x), checks every GLB chunk length, buffer, buffer view and accessor against the
/// bytes that exist, and requires external buffers to be regular files.
/// assimp then reads the checked bytes themselves (ReadFileFromMemory), not the file again; external
/// buffers are opened from the folder check_buffers() looked in (BaseDirIOSystem).
#include <assimp/DefaultIOSystem.h>
#include <assimp/Importer.hpp>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/scene.h>

#include <Eigen/Dense>
#include <algorithm>
#include <initializer_list>
#include <cstring>
#include <fstream>
#include <iterator>
#include <set>
#include <string_view>
#include <cstdio>
#include <map>

#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "gltf_check.h"

namespace adaptex::io_detail {

/// Standard base64 (RFC 4648) of a data: URI's payload; stops at the first character outside the
/// alphabet ('=' padding included). Written here because no dependency offers it to this layer:
/// Debian's libassimp 5.2.4 installs assimp/Base64.hpp but does not export its symbols, and
/// tinygltf's decoder is compiled only into the paint layer's exporter.
std::string decode_base64(const std::string& text, std::size_t from) {
  std::string out;
  std::uint32_t acc = 0;
  int bits = 0;
  for (std::size_t k = from; k < text.size(); ++k) {
    const char c = text[k];
    int v = c >= 'A' && c <= 'Z' ? c - 'A' : c >= 'a' && c <= 'z' ? c - 'a' + 26 : c >= '0' && c <= '9' ? c - '0' + 52
            : c == '+' ? 62 : c == '/' ? 63 : -1;
    if (v < 0) break;
    acc = (acc << 6) | static_cast<std::uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<char>((acc >> bits) & 0xFF));
    }
  }
  return out;
}

/// The bytes of buffer \p b (check_buffers() accepted it) other than the GLB's BIN chunk: a data: URI,
/// or a file next to the glTF.
std::string uri_buffer_bytes(const json& b, const std::filesystem::path& dir) {
  const std::string uri = b["uri"].get<std::string>();
  if (uri.rfind("data:", 0) == 0) return decode_base64(uri, uri.find(',') + 1);
  std::ifstream in(dir / uri, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

namespace {

Eigen::Matrix4d to_eigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  out << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4;
  return out;
}

/// What collect() gathers beyond positions and faces for read_gltf_textured_soup().
struct UvCollector {
  TexturedSoup* out = nullptr;
  std::map<std::pair<float, float>, std::int64_t> index;  ///< Identical UVs share one texture coordinate.
  std::vector<char> material_has_maps;                     ///< Per glTF material.
  const json* doc = nullptr;                               ///< The glTF, with every mesh named by mesh_marker().
  std::string name;

  /// The glTF material of \p mesh's primitive (-1: none). assimp's own material indices follow the
  /// order in which it loaded the materials, not the file's, so the primitive is found by the name
  /// assimp gives the mesh: the marker of its glTF mesh, then "-p" for primitive p when there are several.
  int material_of(const aiMesh* mesh) const {
    const std::string n = mesh->mName.C_Str();
    std::size_t m = 0, p = 0;
    if (std::sscanf(n.c_str(), "adaptex_mesh_%zu-%zu", &m, &p) < 1 || m >= (*doc)["meshes"].size())
      throw IoError(name + ": corrupt glTF: cannot tell which glTF mesh assimp's mesh '" + n + "' is");
    const json& prims = (*doc)["meshes"][m]["primitives"];
    if (p >= prims.size()) throw IoError(name + ": corrupt glTF: assimp's mesh '" + n + "' has no glTF primitive");
    const json& prim = prims[p];
    if (!prim.contains("material")) return -1;
    if (!prim["material"].is_number_unsigned() || prim["material"].get<std::size_t>() >= material_has_maps.size())
      throw IoError(name + ": corrupt glTF: mesh " + std::to_string(m) + " primitive " + std::to_string(p) +
                    " refers to a missing material");
    return prim["material"].get<int>();
  }
};

/// The texture coordinate indices of \p mesh's vertices (TEXCOORD_0; assimp has flipped v to OBJ's
/// convention, v = 0 at the bottom of the image). A primitive without TEXCOORD_0 whose material has
/// no map gets UV (0, 0) everywhere (counted in untextured_polygons).
std::vector<std::int64_t> collect_uvs(const aiMesh* mesh, int material, UvCollector& uvs) {
  const bool has_uvs = mesh->mTextureCoords[0] != nullptr;
  if (!has_uvs && material >= 0 && uvs.material_has_maps[static_cast<std::size_t>(material)])
    throw InvalidInputError(uvs.name + ": the mesh '" + std::string(mesh->mName.C_Str()) + "' has a primitive with material " +
                            std::to_string(material) + ", which has texture maps, but no texture coordinates (TEXCOORD_0)");
  std::vector<std::int64_t> out(mesh->mNumVertices);
  for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
    const aiVector3D t = has_uvs ? mesh->mTextureCoords[0][v] : aiVector3D(0, 0, 0);
    const auto [it, added] = uvs.index.emplace(std::make_pair(t.x, t.y), static_cast<std::int64_t>(uvs.index.size()));
    if (added) {
      uvs.out->texcoords.push_back(t.x);
      uvs.out->texcoords.push_back(t.y);
    }
    out[v] = it->second;
  }
  if (!has_uvs) uvs.out->untextured_polygons += static_cast<int>(mesh->mNumFaces);
  return out;
}

void collect(const aiScene* scene, const aiNode* node, const Eigen::Matrix4d& parent, PolygonSoup& soup,
             int& skipped_primitives, UvCollector* uvs) {
  const Eigen::Matrix4d world = parent * to_eigen(node->mTransformation);
  const bool identity = world.isIdentity(0.0);
  for (unsigned i = 0; i < node->mNumMeshes; ++i) {
    const aiMesh* mesh = scene->mMeshes[node->mMeshes[i]];
    const auto base = static_cast<std::int64_t>(soup.positions.size());
    const int material = uvs ? uvs->material_of(mesh) : -1;
    const std::vector<std::int64_t> tex = uvs ? collect_uvs(mesh, material, *uvs) : std::vector<std::int64_t>();
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
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        soup.indices.push_back(base + face.mIndices[k]);
        if (uvs) {
          soup.tex_indices.push_back(face.mIndices[k] < tex.size() ? tex[face.mIndices[k]] : -1);
          uvs->out->corner_material.push_back(material);
        }
      }
      soup.end_polygon();
    }
  }
  for (unsigned c = 0; c < node->mNumChildren; ++c)
    collect(scene, node->mChildren[c], world, soup, skipped_primitives, uvs);
}

std::string first_line_of(const std::string& msg) { return msg.substr(0, msg.find('\n')); }

std::uint32_t u32_at(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  std::memcpy(&v, bytes.data() + at, 4);  // GLB is little endian, as every platform adaptex builds on
  return v;
}

/// Splits a GLB container into its JSON text and the length (and, if asked, the offset) of its BIN
/// chunk (0 without one).
std::string split_glb(const std::string& name, const std::string& bytes, std::uint64_t& bin_length,
                      std::uint64_t* bin_offset = nullptr) {
  const std::string corrupt = name + ": corrupt glTF: ";
  if (bytes.size() < 20) throw IoError(corrupt + "a GLB file needs at least 20 bytes (has " + std::to_string(bytes.size()) + ")");
  if (u32_at(bytes, 4) != 2) throw IoError(corrupt + "GLB version " + std::to_string(u32_at(bytes, 4)) + " (only 2 is supported)");
  if (u32_at(bytes, 8) != bytes.size())
    throw IoError(corrupt + "the GLB header says " + std::to_string(u32_at(bytes, 8)) + " bytes but the file has " +
                  std::to_string(bytes.size()));
  std::string json_text;
  bin_length = 0;
  for (std::size_t at = 12, chunk = 0; at < bytes.size(); ++chunk) {
    if (bytes.size() - at < 8) throw IoError(corrupt + "GLB chunk " + std::to_string(chunk) + " header is truncated");
    const std::uint64_t length = u32_at(bytes, at), type = u32_at(bytes, at + 4);
    if (length > bytes.size() - at - 8)
      throw IoError(corrupt + "GLB chunk " + std::to_string(chunk) + " claims " + std::to_string(length) +
                    " bytes, more than the " + std::to_string(bytes.size() - at - 8) + " left in the file");
    if (chunk == 0 && type != 0x4E4F534Au) throw IoError(corrupt + "the first GLB chunk is not JSON");
    if (chunk == 0) json_text = bytes.substr(at + 8, length);
    if (chunk == 1 && type == 0x004E4942u) {
      bin_length = length;
      if (bin_offset) *bin_offset = at + 8;
    }
    at += 8 + length;
  }
  return json_text;
}

std::uint64_t get_size(const json& obj, const char* key, std::uint64_t fallback, const std::string& what) {
  const auto it = obj.find(key);
  if (it == obj.end()) return fallback;
  if (!it->is_number_unsigned()) throw IoError(what + ": '" + key + "' is not a non-negative integer");
  return it->get<std::uint64_t>();
}

/// Byte length of each buffer, checked against the bytes that exist (GLB BIN chunk, data: URI, file).
std::vector<std::uint64_t> check_buffers(const std::string& corrupt, const json& doc, const std::filesystem::path& dir,
                                         std::uint64_t bin_length) {
  std::vector<std::uint64_t> sizes;
  if (!doc.contains("buffers")) return sizes;
  if (!doc["buffers"].is_array()) throw IoError(corrupt + "'buffers' is not an array");
  for (const json& b : doc["buffers"]) {
    const std::string what = corrupt + "buffer " + std::to_string(sizes.size());
    if (!b.is_object()) throw IoError(what + " is not an object");
    const std::uint64_t length = get_size(b, "byteLength", 0, what);
    std::uint64_t available = bin_length;
    if (b.contains("uri")) {
      if (!b["uri"].is_string()) throw IoError(what + ": 'uri' is not a string");
      const std::string uri = b["uri"].get<std::string>();
      if (uri.rfind("data:", 0) == 0) {
        available = (uri.size() - std::min(uri.size(), uri.find(',') + 1)) / 4 * 3;
      } else {
        // assimp's in-memory reader answers this name with the glTF itself, not a file.
        if (uri.rfind(AI_MEMORYIO_MAGIC_FILENAME, 0) == 0) throw IoError(what + ": '" + uri + "' is a reserved name");
        const std::filesystem::path file = dir / uri;
        std::error_code ec;
        if (!std::filesystem::is_regular_file(file, ec))
          throw IoError(what + ": '" + uri + "' is not a regular file");
        available = std::filesystem::file_size(file, ec);
        if (ec) throw IoError(what + ": cannot get the size of '" + uri + "'");
        if (available > kMaxInputFileBytes)  // the cap of every input file (core/limits.h)
          throw IoError(what + ": '" + uri + "' is larger than the input file limit of " +
                        std::to_string(kMaxInputFileBytes) + " bytes");
      }
    }
    if (length > available)
      throw IoError(what + " claims " + std::to_string(length) + " bytes but only " + std::to_string(available) +
                    " exist");
    sizes.push_back(length);
  }
  return sizes;
}

/// Bytes of one accessor item (component size x components); 1 when the accessor does not say.
std::uint64_t accessor_item_bytes(const json& a) {
  std::uint64_t component = 1, components = 1;
  if (const auto it = a.find("componentType"); it != a.end() && it->is_number_unsigned()) {
    const auto t = it->get<std::uint64_t>();
    component = t == 5122 || t == 5123 ? 2 : t == 5125 || t == 5126 ? 4 : 1;
  }
  if (const auto it = a.find("type"); it != a.end() && it->is_string()) {
    const std::string t = it->get<std::string>();
    components = t == "VEC2" ? 2 : t == "VEC3" ? 3 : t == "VEC4" || t == "MAT2" ? 4 : t == "MAT3" ? 9 : t == "MAT4" ? 16 : 1;
  }
  return component * components;
}

/// Every buffer view inside its buffer, every accessor inside its buffer view (or, without one, no
/// more than kMaxMeshElements items).
void check_views_and_accessors(const std::string& corrupt, const json& doc, const std::vector<std::uint64_t>& buffers) {
  std::vector<std::uint64_t> views;
  if (doc.contains("bufferViews")) {
    if (!doc["bufferViews"].is_array()) throw IoError(corrupt + "'bufferViews' is not an array");
    for (const json& v : doc["bufferViews"]) {
      const std::string what = corrupt + "bufferView " + std::to_string(views.size());
      if (!v.is_object()) throw IoError(what + " is not an object");
      const std::uint64_t buffer = get_size(v, "buffer", buffers.size(), what);
      const std::uint64_t offset = get_size(v, "byteOffset", 0, what), length = get_size(v, "byteLength", 0, what);
      if (buffer >= buffers.size() || offset > buffers[buffer] || length > buffers[buffer] - offset)
        throw IoError(what + " lies outside its buffer");
      views.push_back(length);
    }
  }
  if (!doc.contains("accessors")) return;
  if (!doc["accessors"].is_array()) throw IoError(corrupt + "'accessors' is not an array");
  std::size_t index = 0;
  for (const json& a : doc["accessors"]) {
    const std::string what = corrupt + "accessor " + std::to_string(index++);
    if (!a.is_object()) throw IoError(what + " is not an object");
    const std::uint64_t count = get_size(a, "count", 0, what);
    const std::uint64_t ctype = get_size(a, "componentType", 0, what);
    if (ctype < 5120 || ctype > 5126 || ctype == 5124) throw IoError(what + ": unknown componentType " + std::to_string(ctype));
    static const std::set<std::string> types = {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"};
    if (!a.contains("type") || !a["type"].is_string() || !types.count(a["type"].get<std::string>()))
      throw IoError(what + ": unknown or missing type");
    if (count > kMaxMeshElements) throw IoError(what + " claims " + std::to_string(count) + " items");
    if (a.contains("sparse")) throw IoError(what + ": sparse accessors are not supported");
    if (!a.contains("bufferView")) continue;
    const std::uint64_t view = get_size(a, "bufferView", 0, what), offset = get_size(a, "byteOffset", 0, what);
    const std::uint64_t item = accessor_item_bytes(a);
    if (view >= views.size() || offset > views[view] || count > (views[view] - offset) / item)
      throw IoError(what + " (" + std::to_string(count) + " items) lies outside its buffer view");
  }
}

/// An optional array member; IoError when present and not an array.
const json* array_of(const std::string& corrupt, const json& obj, const char* key) {
  const auto it = obj.find(key);
  if (it == obj.end()) return nullptr;
  if (!it->is_array()) throw IoError(corrupt + "'" + key + "' is not an array");
  return &*it;
}

/// \p j must be an index below \p n.
void check_index(const json& j, std::size_t n, const std::string& what) {
  if (!j.is_number_unsigned() || j.get<std::uint64_t>() >= n)
    throw IoError(what + " refers to a missing item (" + j.dump() + ", there are " + std::to_string(n) + ")");
}

/// The accessor \p index (in range) must be of \p type with one of the \p components types (glTF 2.0
/// spec: POSITION is a float VEC3, indices an unsigned integer SCALAR). Found by fuzz_gltf: indices
/// read from a float VEC3 accessor by a line-loop primitive made assimp read address 0.
void check_accessor_kind(const json& accessors, const json& index, const char* type,
                         std::initializer_list<std::uint64_t> components, const std::string& what) {
  const json& a = accessors[index.get<std::size_t>()];
  const bool kind_ok = a.is_object() && a.contains("type") && a["type"] == type && a.contains("componentType") &&
                       a["componentType"].is_number_unsigned() &&
                       std::find(components.begin(), components.end(), a["componentType"].get<std::uint64_t>()) !=
                           components.end();
  if (!kind_ok) throw IoError(what + " must be a " + type + " accessor of the componentType the glTF 2.0 spec allows");
}

/// A primitive's vertex count (its indices' count, else its POSITION count) must make whole
/// primitives of its mode: a multiple of 3 for triangles, of 2 for lines, at least 3 for strips and
/// fans, at least 2 for line strips and loops (glTF 2.0 spec, 3.7.2.1). Found by fuzz_gltf (session
/// 11): a triangle strip with 1 index made assimp allocate count − 2 = 2^64 − 1 faces.
/// \pre the accessors referenced by \p p exist (check_index())
void check_vertex_count(const json& accessors, const json& p, const std::string& what) {
  const json& counted = accessors[(p.contains("indices") ? p["indices"] : p["attributes"]["POSITION"]).get<std::size_t>()];
  const json* count = counted.is_object() && counted.contains("count") ? &counted["count"] : nullptr;
  const std::uint64_t n = count && count->is_number_unsigned() ? count->get<std::uint64_t>() : 0;
  const std::uint64_t mode = p.contains("mode") ? p["mode"].get<std::uint64_t>() : 4;
  const bool ok = mode == 0 || (mode == 4 && n % 3 == 0) || (mode == 1 && n % 2 == 0) || ((mode == 2 || mode == 3) && n >= 2) ||
                  ((mode == 5 || mode == 6) && n >= 3);
  if (!ok)
    throw IoError(what + ": " + std::to_string(n) + " vertices do not make whole primitives of mode " + std::to_string(mode));
}

/// Every image's mimeType is a string with a '/': assimp's importer takes the text after
/// strchr(mimeType, '/') unchecked, so "image$png" made it strcmp() address 1 (found by fuzz_gltf).
void check_images(const std::string& corrupt, const json& doc) {
  const json* images = array_of(corrupt, doc, "images");
  for (std::size_t i = 0; images && i < images->size(); ++i) {
    const json& img = (*images)[i];
    if (!img.is_object()) throw IoError(corrupt + "image " + std::to_string(i) + " is not an object");
    if (const auto m = img.find("mimeType"); m != img.end())
      if (!m->is_string() || m->get<std::string>().find('/') == std::string::npos) {
        std::string shown = m->dump();
        if (shown.size() > 40) shown = shown.substr(0, 36) + "...";
        throw IoError(corrupt + "image " + std::to_string(i) + ": mimeType " + shown +
                      " is not a MIME type (such as \"image/png\")");
      }
  }
}

/// Every reference assimp follows without checking (a primitive without POSITION crashed it): meshes'
/// attributes and indices, primitive modes, nodes' meshes and children (no cycles: a node has at
/// most one parent and is not its own ancestor), scenes' nodes.
void check_references(const std::string& corrupt, const json& doc) {
  const json* accessors = array_of(corrupt, doc, "accessors");
  const std::size_t na = accessors ? accessors->size() : 0;
  const json* meshes = array_of(corrupt, doc, "meshes");
  const std::size_t nm = meshes ? meshes->size() : 0;
  for (std::size_t m = 0; m < nm; ++m) {
    const std::string what = corrupt + "mesh " + std::to_string(m);
    const json& mesh = (*meshes)[m];
    const json* prims = mesh.is_object() ? array_of(corrupt, mesh, "primitives") : nullptr;
    if (!prims || prims->empty()) throw IoError(what + " has no primitives");
    for (const json& p : *prims) {
      if (!p.is_object() || !p.contains("attributes") || !p["attributes"].is_object() ||
          !p["attributes"].contains("POSITION"))
        throw IoError(what + ": a primitive has no POSITION attribute");
      for (const auto& [name, a] : p["attributes"].items()) check_index(a, na, what + " attribute " + name);
      check_accessor_kind(*accessors, p["attributes"]["POSITION"], "VEC3", {5126}, what + ": POSITION");
      if (p.contains("indices")) {
        check_index(p["indices"], na, what + " indices");
        check_accessor_kind(*accessors, p["indices"], "SCALAR", {5121, 5123, 5125}, what + ": indices");
      }
      if (p.contains("mode") && (!p["mode"].is_number_unsigned() || p["mode"].get<std::uint64_t>() > 6))
        throw IoError(what + ": primitive mode must be 0..6");
      check_vertex_count(*accessors, p, what);
      if (p.contains("targets")) throw IoError(what + ": morph targets are not supported");
    }
  }
  const json* nodes = array_of(corrupt, doc, "nodes");
  const std::size_t nn = nodes ? nodes->size() : 0;
  std::vector<std::int64_t> parent(nn, -1);
  for (std::size_t n = 0; n < nn; ++n) {
    const std::string what = corrupt + "node " + std::to_string(n);
    const json& node = (*nodes)[n];
    if (!node.is_object()) throw IoError(what + " is not an object");
    if (node.contains("mesh")) check_index(node["mesh"], nm, what + " mesh");
    if (const json* children = array_of(corrupt, node, "children"))
      for (const json& c : *children) {
        check_index(c, nn, what + " child");
        auto& p = parent[c.get<std::size_t>()];
        if (p >= 0 || c.get<std::size_t>() == n) throw IoError(what + ": node " + c.dump() + " has two parents");
        p = static_cast<std::int64_t>(n);
      }
  }
  for (std::size_t n = 0; n < nn; ++n) {  // no cycles: walking up from any node ends at a root
    std::size_t steps = 0;
    for (std::int64_t x = parent[n]; x >= 0; x = parent[static_cast<std::size_t>(x)])
      if (++steps > nn) throw IoError(corrupt + "the node hierarchy has a cycle");
  }
  if (const json* scenes = array_of(corrupt, doc, "scenes"))
    for (const json& sc : *scenes) {
      const json* roots = sc.is_object() ? array_of(corrupt, sc, "nodes") : nullptr;
      if (roots)
        for (const json& r : *roots) check_index(r, nn, corrupt + "scene node");
    }
  if (doc.contains("scene")) check_index(doc["scene"], doc.contains("scenes") ? doc["scenes"].size() : 0, corrupt + "scene");
}

/// Every index of every primitive names a vertex of its POSITION accessor. assimp follows index values
/// without checking them for some primitive modes: found by fuzz_gltf, a line loop whose
/// indices (a valid unsigned-short SCALAR accessor) were read from the positions' bytes made assimp
/// read address 0. Runs after check_views_and_accessors() and check_references(), so every accessor
/// and view read here lies inside its buffer.
void check_index_values(const std::string& corrupt, const json& doc, const std::string& bytes, std::uint64_t bin_offset,
                        std::uint64_t bin_length, const std::filesystem::path& dir) {
  const json* meshes = array_of(corrupt, doc, "meshes");
  if (!meshes) return;
  // Buffers' bytes, read on first use; the BIN chunk is read where it lies in the file's bytes.
  std::vector<std::string> loaded;
  std::vector<char> have;
  for (std::size_t m = 0; m < meshes->size(); ++m)
    for (const json& p : (*meshes)[m].at("primitives")) {
      if (!p.contains("indices")) continue;
      const std::string what = corrupt + "mesh " + std::to_string(m) + " indices";
      // Types and ranges were checked before (get_size(), check_index()); missing counts and offsets
      // are 0, as there.
      const json& accessors = doc.at("accessors");
      const json& acc = accessors.at(p.at("indices").get<std::size_t>());
      const std::uint64_t vertices =
          accessors.at(p.at("attributes").at("POSITION").get<std::size_t>()).value("count", std::uint64_t{0});
      if (!acc.contains("bufferView")) {  // all zero: valid when there is a vertex
        if (acc.value("count", std::uint64_t{0}) > 0 && vertices == 0) throw IoError(what + ": index 0 but the primitive has no vertices");
        continue;
      }
      const json& view = doc.at("bufferViews").at(acc.at("bufferView").get<std::size_t>());
      if (view.contains("byteStride")) throw IoError(what + ": an index buffer view must not have a byteStride");
      const std::size_t buffer = view.at("buffer").get<std::size_t>();
      const json& buffers = doc.at("buffers");
      if (have.empty()) have.assign(buffers.size(), 0), loaded.resize(buffers.size());
      const json& b = buffers.at(buffer);
      if (b.contains("uri") && !have[buffer]) loaded[buffer] = uri_buffer_bytes(b, dir), have[buffer] = 1;
      const std::string_view data = b.contains("uri") ? std::string_view(loaded[buffer])
                                                      : std::string_view(bytes).substr(static_cast<std::size_t>(bin_offset),
                                                                                       static_cast<std::size_t>(bin_length));
      const std::uint64_t size = accessor_item_bytes(acc), count = acc.value("count", std::uint64_t{0});
      const std::uint64_t start = view.value("byteOffset", std::uint64_t{0}) + acc.value("byteOffset", std::uint64_t{0});
      if (start + count * size > data.size()) throw IoError(what + " lie outside the buffer's data");
      for (std::uint64_t k = 0; k < count; ++k) {
        std::uint32_t v = 0;
        std::memcpy(&v, data.data() + start + k * size, static_cast<std::size_t>(size));  // little endian
        if (v >= vertices)
          throw IoError(what + ": index " + std::to_string(v) + " but the primitive has " + std::to_string(vertices) +
                        " vertices");
      }
    }
}

}  // namespace

CheckedGltf check_gltf(const std::string& name, const std::filesystem::path& base_dir, const std::string& bytes) {
  const std::string corrupt = name + ": corrupt glTF: ";
  std::uint64_t bin_length = 0;
  const bool glb = bytes.rfind("glTF", 0) == 0;
  std::size_t first = bytes.find_first_not_of(" \t\r\n");
  if (!glb && (first == std::string::npos || bytes[first] != '{'))
    throw IoError(corrupt + "neither a binary glTF (it does not start with 'glTF') nor a glTF JSON object");
  json doc;
  std::uint64_t bin_offset = 0;
  try {
    doc = json::parse(glb ? split_glb(name, bytes, bin_length, &bin_offset) : bytes);
  } catch (const json::exception& e) {
    throw IoError(corrupt + "the JSON does not parse (" + first_line_of(e.what()) + ")");
  }
  if (!doc.is_object() || !doc.contains("asset") || !doc["asset"].is_object() || !doc["asset"].contains("version") ||
      !doc["asset"]["version"].is_string() || doc["asset"]["version"].get<std::string>().rfind("2.", 0) != 0)
    throw IoError(corrupt + "not glTF 2.0 (no \"asset\": {\"version\": \"2.x\"})");
  check_views_and_accessors(corrupt, doc, check_buffers(corrupt, doc, base_dir, bin_length));
  check_references(corrupt, doc);
  check_images(corrupt, doc);
  try {
    check_index_values(corrupt, doc, bytes, bin_offset, bin_length, base_dir);
  } catch (const json::exception& e) {  // a member the checks above let pass but this one cannot read
    throw IoError(corrupt + "cannot read the index data (" + first_line_of(e.what()) + ")");
  }
  return {std::move(doc), glb, bin_offset, bin_length};
}

namespace {

/// assimp's file system seen from the glTF's folder: relative names (external buffers) resolve there,
/// as check_buffers() resolved them, and only regular files open.
class BaseDirIOSystem : public Assimp::DefaultIOSystem {
 public:
  explicit BaseDirIOSystem(std::filesystem::path base_dir) : base_dir_(std::move(base_dir)) {}
  bool Exists(const char* file) const override {
    std::error_code ec;
    return std::filesystem::is_regular_file(resolve(file), ec);
  }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    return Exists(file) ? DefaultIOSystem::Open(resolve(file).string().c_str(), mode) : nullptr;
  }

 private:
  std::filesystem::path resolve(const char* file) const { return base_dir_ / file; }  // absolute names stay
  std::filesystem::path base_dir_;
};

}  // namespace

namespace {

/// The soup of a checked glTF through assimp; with \p uvs, its texture coordinates and materials too.
PolygonSoup soup_of_checked(const std::string& bytes, const SoupSource& source, bool glb, UvCollector* uvs) {
  const std::string& name = source.name;
  Assimp::Importer importer;
  importer.SetIOHandler(new BaseDirIOSystem(source.base_dir));  // the importer owns it
  // The format hint is the container check_gltf() accepted, so only the glTF 2.0 importer reads it.
  const aiScene* scene = importer.ReadFileFromMemory(bytes.data(), bytes.size(), 0, glb ? "glb" : "gltf");
  if (!scene || !scene->mRootNode) {
    std::string err = importer.GetErrorString();
    for (char& c : err)
      if (c == '\n' || c == '\r') c = ' ';
    throw IoError(name + ": corrupt glTF: " + (err.empty() ? std::string("assimp could not read it") : err));
  }
  PolygonSoup soup;
  soup.format = glb ? "glb" : "gltf";
  soup.weld = true;
  int skipped = 0;
  collect(scene, scene->mRootNode, Eigen::Matrix4d::Identity(), soup, skipped, uvs);
  if (skipped > 0)
    soup.warnings.push_back(name + ": ignored " + std::to_string(skipped) + " point/line primitives");
  return soup;
}

}  // namespace

PolygonSoup read_gltf_soup(const std::string& bytes, const SoupSource& source) {
  const CheckedGltf checked = check_gltf(source.name, source.base_dir, bytes);
  return soup_of_checked(bytes, source, checked.glb, nullptr);
}

namespace {

/// \p bytes with the JSON replaced by \p doc (a GLB keeps its other chunks, after a JSON chunk padded
/// with spaces to 4 bytes).
std::string with_json(const std::string& bytes, const CheckedGltf& checked, const json& doc) {
  std::string text = doc.dump(-1, ' ', false, json::error_handler_t::replace);  // never throws
  if (!checked.glb) return text;
  while (text.size() % 4) text += ' ';
  const std::size_t rest = 12 + 8 + u32_at(bytes, 12);  // after the first (JSON) chunk
  std::string out = bytes.substr(0, 12);
  const auto put32 = [&](std::size_t at, std::uint32_t v) { std::memcpy(out.data() + at, &v, 4); };
  out += std::string(8, '\0');
  put32(12, static_cast<std::uint32_t>(text.size()));
  put32(16, 0x4E4F534Au);
  out += text;
  out += bytes.substr(rest);
  put32(8, static_cast<std::uint32_t>(out.size()));
  return out;
}

}  // namespace

TexturedSoup read_gltf_textured_soup(const std::string& bytes, const SoupSource& source, const CheckedGltf& checked) {
  TexturedSoup out;
  UvCollector uvs;
  uvs.out = &out;
  uvs.name = source.name;
  json doc = checked.doc;
  if (const auto materials = doc.find("materials"); materials != doc.end() && materials->is_array())
    for (const json& m : *materials) {
      const auto has = [](const json& o, const char* key) { return o.is_object() && o.contains(key); };
      const bool maps = has(m, "normalTexture") || has(m, "occlusionTexture") || has(m, "emissiveTexture") ||
                        (has(m, "pbrMetallicRoughness") && (has(m["pbrMetallicRoughness"], "baseColorTexture") ||
                                                            has(m["pbrMetallicRoughness"], "metallicRoughnessTexture")));
      uvs.material_has_maps.push_back(maps ? 1 : 0);
    }
  if (const auto meshes = doc.find("meshes"); meshes != doc.end())  // an array of objects (check_references())
    for (std::size_t m = 0; m < meshes->size(); ++m) (*meshes)[m]["name"] = "adaptex_mesh_" + std::to_string(m);
  uvs.doc = &doc;
  out.soup = soup_of_checked(with_json(bytes, checked, doc), source, checked.glb, &uvs);
  return out;
}

}  // namespace adaptex::io_detail
