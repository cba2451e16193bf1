/// \file export.cpp
/// OBJ/MTL/PNG and glTF 2.0 binary export of a painted mesh (docs/export.md).
#include "adaptex/paint/export.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "adaptex/core/errors.h"
#include "adaptex/io/image_io.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/paint/tangent_frame.h"

namespace adaptex {

namespace fs = std::filesystem;

namespace {

bool bad_name_char(char c) {
  return c == '/' || c == '\\' || std::isspace(static_cast<unsigned char>(c)) || c == '\0' ||
         std::iscntrl(static_cast<unsigned char>(c));
}

void check_layout(const TriMesh& mesh, const Parameterization& param) {
  if (mesh.faces.empty()) throw InvalidInputError("export: the mesh has no faces");
  if (param.uv_faces.size() != mesh.faces.size())
    throw InvalidInputError("export: the parameterization has " + std::to_string(param.uv_faces.size()) +
                            " faces, the mesh " + std::to_string(mesh.faces.size()));
  for (const Face& f : param.uv_faces)
    for (int w : f)
      if (w < 0 || w >= param.num_wedges())
        throw InvalidInputError("export: a UV face refers to wedge " + std::to_string(w) + " of " +
                                std::to_string(param.num_wedges()));
  for (size_t f = 0; f < mesh.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.faces[f][k];
      if (v < 0 || v >= mesh.num_vertices())
        throw InvalidInputError("export: face " + std::to_string(f) + " refers to vertex " +
                                std::to_string(v) + " of " + std::to_string(mesh.num_vertices()));
    }
}

void check_inputs(const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& texture) {
  check_layout(mesh, param);
  if (texture.empty() ||
      texture.data.size() != static_cast<size_t>(texture.width) * texture.height * 4)
    throw InvalidInputError("export: the texture is empty or its size is inconsistent");
}

/// Appends \p bytes to \p buf (padded to 4 bytes first) and returns the bufferView index.
int add_buffer_view(tinygltf::Model& model, std::vector<unsigned char>& buf, const void* bytes,
                    size_t size, int target) {
  while (buf.size() % 4) buf.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buf.size();
  view.byteLength = size;
  if (target) view.target = target;
  const auto* p = static_cast<const unsigned char*>(bytes);
  buf.insert(buf.end(), p, p + size);
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size()) - 1;
}

int add_accessor(tinygltf::Model& model, int view, int component, int type, size_t count,
                 std::vector<double> min = {}, std::vector<double> max = {}) {
  tinygltf::Accessor acc;
  acc.bufferView = view;
  acc.byteOffset = 0;
  acc.componentType = component;
  acc.type = type;
  acc.count = count;
  acc.minValues = std::move(min);
  acc.maxValues = std::move(max);
  model.accessors.push_back(acc);
  return static_cast<int>(model.accessors.size()) - 1;
}

}  // namespace

void check_export_name(const std::string& name) {
  if (name.empty()) throw InvalidInputError("output name is empty");
  if (name == "." || name == "..")
    throw InvalidInputError("output name '" + name + "' is not a file name");
  for (char c : name)
    if (bad_name_char(c))
      throw InvalidInputError("output name '" + name +
                              "' must not contain whitespace, control characters or path separators");
}

std::string sanitize_export_name(const std::string& stem) {
  std::string s = stem;
  for (char& c : s)
    if (bad_name_char(c)) c = '_';
  if (s.empty() || s == "." || s == "..") s = "mesh";
  return s;
}

namespace {

/// A .glb under construction: one buffer, shared vertex attributes, one sampler, images and materials.
struct GlbBuilder {
  tinygltf::Model model;
  std::vector<unsigned char> buf;
  std::map<std::string, int> attributes;  // POSITION, NORMAL, TEXCOORD_0: shared by every primitive

  /// One glTF vertex per wedge: POSITION (with min/max), NORMAL (when \p normals), TANGENT (when \p normals
  /// and \p tangents: MikkTSpace, w = handedness; the frame normal maps are baked in), TEXCOORD_0 = (u, 1 - v).
  void geometry(const TriMesh& mesh, const Parameterization& param, bool normals, bool tangents) {
    const int nw = param.num_wedges();
    std::vector<float> pos(3 * static_cast<size_t>(nw)), uv(2 * static_cast<size_t>(nw));
    std::vector<double> pmin(3, std::numeric_limits<double>::infinity()),
        pmax(3, -std::numeric_limits<double>::infinity());
    // Wedge -> 3-D vertex through the faces (authoritative); wedge_vertex only for unused wedges.
    std::vector<int> wv(nw, -1);
    for (size_t f = 0; f < mesh.faces.size(); ++f)
      for (int k = 0; k < 3; ++k) wv[param.uv_faces[f][k]] = mesh.faces[f][k];
    for (int w = 0; w < nw; ++w)
      if (wv[w] < 0) {
        const bool known = w < static_cast<int>(param.wedge_vertex.size()) && param.wedge_vertex[w] >= 0 &&
                           param.wedge_vertex[w] < mesh.num_vertices();
        wv[w] = known ? param.wedge_vertex[w] : 0;
      }
    for (int w = 0; w < nw; ++w) {
      const int v = wv[w];
      for (int k = 0; k < 3; ++k) {
        const float x = static_cast<float>(mesh.positions[v][k]);
        pos[3 * w + k] = x;
        pmin[k] = std::min(pmin[k], static_cast<double>(x));
        pmax[k] = std::max(pmax[k], static_cast<double>(x));
      }
      uv[2 * w] = static_cast<float>(param.uv[w].x());
      uv[2 * w + 1] = static_cast<float>(1.0 - param.uv[w].y());  // glTF: v = 0 is the image's top
    }
    const int v_pos = add_buffer_view(model, buf, pos.data(), pos.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
    attributes["POSITION"] =
        add_accessor(model, v_pos, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, nw, pmin, pmax);
    if (normals) {
      const std::vector<Vec3> vn = vertex_normals(mesh);
      std::vector<float> nrm(3 * static_cast<size_t>(nw));
      for (int w = 0; w < nw; ++w)
        for (int k = 0; k < 3; ++k) nrm[3 * w + k] = static_cast<float>(vn[wv[w]][k]);
      const int v_nrm =
          add_buffer_view(model, buf, nrm.data(), nrm.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
      attributes["NORMAL"] = add_accessor(model, v_nrm, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, nw);
      if (tangents) {
        const std::vector<Eigen::Vector4d> wt = wedge_tangents(mesh, param, vn);
        std::vector<float> tan(4 * static_cast<size_t>(nw));
        for (int w = 0; w < nw; ++w) {
          const Eigen::Vector3f t = wt[w].head<3>().cast<float>().normalized();  // unit in float too
          for (int k = 0; k < 3; ++k) tan[4 * w + k] = t[k];
          tan[4 * w + 3] = static_cast<float>(wt[w].w());
        }
        const int v_tan =
            add_buffer_view(model, buf, tan.data(), tan.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
        attributes["TANGENT"] = add_accessor(model, v_tan, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, nw);
      }
    }
    const int v_uv = add_buffer_view(model, buf, uv.data(), uv.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
    attributes["TEXCOORD_0"] = add_accessor(model, v_uv, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, nw);
  }

  /// A triangle primitive of the faces \p faces of \p param (all when null), with material \p material.
  tinygltf::Primitive primitive(const Parameterization& param, const std::vector<int>* faces, int material) {
    std::vector<std::uint32_t> idx;
    const size_t n = faces ? faces->size() : param.uv_faces.size();
    idx.reserve(3 * n);
    for (size_t i = 0; i < n; ++i)
      for (int w : param.uv_faces[faces ? (*faces)[i] : i]) idx.push_back(static_cast<std::uint32_t>(w));
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.attributes = attributes;
    const int v_idx = add_buffer_view(model, buf, idx.data(), idx.size() * sizeof(std::uint32_t),
                                      TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    prim.indices =
        add_accessor(model, v_idx, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, idx.size());
    prim.material = material;
    return prim;
  }

  /// Sampler 0: linear magnification, trilinear minification, wrap mode \p address.
  void sampler(TextureAddress address) {
    tinygltf::Sampler sampler;
    sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
    sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
    const int wrap =
        address == TextureAddress::Repeat ? TINYGLTF_TEXTURE_WRAP_REPEAT : TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
    sampler.wrapS = wrap;
    sampler.wrapT = wrap;
    model.samplers.push_back(sampler);
  }

  /// An embedded PNG and its texture (sampler 0); returns the texture index.
  int texture(const std::string& name, const std::vector<unsigned char>& png) {
    tinygltf::Image image;
    image.name = name;
    image.mimeType = "image/png";
    image.bufferView = add_buffer_view(model, buf, png.data(), png.size(), 0);
    model.images.push_back(image);
    tinygltf::Texture t;
    t.source = static_cast<int>(model.images.size()) - 1;
    t.sampler = 0;
    model.textures.push_back(t);
    return static_cast<int>(model.textures.size()) - 1;
  }

  /// One mesh of \p prims in one node of the scene; the encoded .glb.
  std::vector<unsigned char> finish(const std::string& name, std::vector<tinygltf::Primitive> prims) {
    model.asset.version = "2.0";
    model.asset.generator = "adaptex";
    tinygltf::Mesh gmesh;
    gmesh.name = name;
    gmesh.primitives = std::move(prims);
    model.meshes.push_back(gmesh);
    tinygltf::Node node;
    node.mesh = 0;
    node.name = name;
    model.nodes.push_back(node);
    tinygltf::Scene scene;
    scene.nodes.push_back(0);
    model.scenes.push_back(scene);
    model.defaultScene = 0;
    while (buf.size() % 4) buf.push_back(0);
    tinygltf::Buffer buffer;
    buffer.data = std::move(buf);
    model.buffers.push_back(std::move(buffer));
    tinygltf::TinyGLTF writer;
    std::ostringstream os;
    if (!writer.WriteGltfSceneToStream(&model, os, false, true))
      throw OutputError("glTF encoder: tinygltf could not write the model");
    const std::string s = os.str();
    return std::vector<unsigned char>(s.begin(), s.end());
  }
};

/// Sets the texture of map \p slot of \p mat (glTF has no statement for roughness, metallic, bump,
/// specular alone: those are left out of the .glb).
void set_glb_map(tinygltf::Material& mat, const std::string& slot, int index) {
  if (slot == "base_color") mat.pbrMetallicRoughness.baseColorTexture.index = index;
  if (slot == "normal") mat.normalTexture.index = index;
  if (slot == "metallic_roughness") mat.pbrMetallicRoughness.metallicRoughnessTexture.index = index;
  if (slot == "occlusion") mat.occlusionTexture.index = index;
  if (slot == "emissive") {
    mat.emissiveTexture.index = index;
    mat.emissiveFactor = {1.0, 1.0, 1.0};
  }
}

/// encode_glb() with the texture already encoded as \p png (shared with NAME.png by the exporter),
/// and options.maps encoded as \p extra_png (parallel).
std::vector<unsigned char> encode_glb_png(const TriMesh& mesh, const Parameterization& param,
                                          const std::vector<unsigned char>& png,
                                          const ExportOptions& options,
                                          const std::vector<std::vector<unsigned char>>& extra_png) {
  GlbBuilder b;
  const bool normal_map = std::any_of(options.maps.begin(), options.maps.end(),
                                      [](const ExportMap& m) { return m.slot == "normal"; });
  b.geometry(mesh, param, options.normals, normal_map);
  tinygltf::Primitive prim = b.primitive(param, nullptr, 0);
  b.sampler(options.wrap);
  b.texture(options.material + "_texture", png);
  tinygltf::Material mat;
  // More maps: one image and texture each, with the same sampler.
  for (size_t m = 0; m < extra_png.size(); ++m)
    set_glb_map(mat, options.maps[m].slot, b.texture(options.material + "_" + options.maps[m].slot, extra_png[m]));
  mat.name = options.material;
  mat.pbrMetallicRoughness.baseColorTexture.index = 0;
  mat.pbrMetallicRoughness.baseColorFactor = {1.0, 1.0, 1.0, 1.0};
  const bool has_mr = mat.pbrMetallicRoughness.metallicRoughnessTexture.index >= 0;
  mat.pbrMetallicRoughness.metallicFactor = has_mr ? 1.0 : 0.0;
  mat.pbrMetallicRoughness.roughnessFactor = 1.0;
  // Input meshes may be wound either way: double-sided so no viewer culls the painted side.
  mat.doubleSided = true;
  b.model.materials.push_back(mat);
  return b.finish(options.material, {prim});
}

void write_bytes(AtomicOutput& out, const fs::path& path, const std::vector<unsigned char>& bytes) {
  const fs::path tmp = out.add(path);
  std::ofstream f(tmp, std::ios::binary);
  if (!f) throw OutputError(path.string() + ": cannot open for writing");
  f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  f.close();
  if (!f) throw OutputError(path.string() + ": write error");
}

}  // namespace

std::vector<unsigned char> encode_glb(const TriMesh& mesh, const Parameterization& param,
                                      const ImageRGBA8& texture, const ExportOptions& options) {
  check_inputs(mesh, param, texture);
  std::vector<std::vector<unsigned char>> extra;
  for (const ExportMap& m : options.maps) extra.push_back(encode_png(m.image));
  return encode_glb_png(mesh, param, encode_png(texture), options, extra);
}

namespace {

/// The MTL statement of a map of \p slot (a comment for a slot MTL has no statement for).
std::string mtl_map_line(const std::string& slot, const std::string& opt, const std::string& file) {
  static const std::map<std::string, std::string> statement{{"base_color", "map_Kd"}, {"normal", "norm"},
                                                            {"emissive", "map_Ke"},   {"roughness", "map_Pr"},
                                                            {"metallic", "map_Pm"},   {"bump", "bump"},
                                                            {"specular", "map_Ks"}};
  const auto it = statement.find(slot);
  return it == statement.end() ? "# " + slot + ": " + file + "\n" : it->second + " " + opt + file + "\n";
}

}  // namespace

void write_mtl(const fs::path& path, const std::string& material, const std::string& texture_file, bool clamp,
               const std::vector<std::pair<std::string, std::string>>& maps) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw OutputError(path.string() + ": cannot open for writing");
  const std::string opt = clamp ? "-clamp on " : "";
  out << "# adaptex painted material\n"
      << "newmtl " << material << "\n"
      << "Ka 0 0 0\n"
      << "Kd 1 1 1\n"
      << "Ks 0 0 0\n"
      << "d 1\n"
      << "illum 1\n"
      << "map_Kd " << opt << texture_file << "\n";
  for (const auto& [slot, file] : maps) out << mtl_map_line(slot, opt, file);
  out.close();
  if (!out) throw OutputError(path.string() + ": write error");
}

void write_mtl(const fs::path& path, const std::string& material, const std::string& texture_file, bool clamp) {
  write_mtl(path, material, texture_file, clamp, {});
}

ExportedFiles export_textured_mesh(AtomicOutput& out, const fs::path& dir, const std::string& name,
                                   const TriMesh& mesh, const Parameterization& param,
                                   const ImageRGBA8& texture, const ExportOptions& options) {
  check_export_name(name);
  check_export_name(options.material);
  check_inputs(mesh, param, texture);
  ExportedFiles files;
  if (options.obj) {
    files.obj = dir / (name + ".obj");
    files.mtl = dir / (name + ".mtl");
    files.png = dir / (name + ".png");
    std::vector<std::pair<std::string, std::string>> maps;
    for (const ExportMap& m : options.maps) {
      check_export_name(m.slot);
      maps.emplace_back(m.slot, name + "_" + m.slot + ".png");
    }
    write_obj(out.add(files.obj), mesh, &param, name + ".mtl", options.material);
    write_mtl(out.add(files.mtl), options.material, name + ".png", options.mtl_clamp, maps);
  }
  // Every texture is PNG-encoded once, for the PNG files and the .glb alike (same bytes).
  const std::vector<unsigned char> png = encode_png(texture);
  std::vector<std::vector<unsigned char>> extra;
  for (const ExportMap& m : options.maps) {
    if (m.image.empty()) throw InvalidInputError("export: map '" + m.slot + "' is empty");
    extra.push_back(encode_png(m.image));
  }
  if (options.obj) {
    write_bytes(out, files.png, png);
    for (size_t m = 0; m < extra.size(); ++m)
      write_bytes(out, dir / (name + "_" + options.maps[m].slot + ".png"), extra[m]);
  }
  if (options.glb) {
    files.glb = dir / (name + ".glb");
    write_bytes(out, files.glb, encode_glb_png(mesh, param, png, options, extra));
  }
  return files;
}

namespace {

std::string number(double x) {
  std::ostringstream os;
  os << x;
  return os.str();
}

void check_materials(const TriMesh& mesh, const Parameterization& param, const ExportMaterials& set) {
  if (set.face_material.size() != mesh.faces.size())
    throw InvalidInputError("export: " + std::to_string(set.face_material.size()) + " face materials for " +
                            std::to_string(mesh.faces.size()) + " faces");
  for (int m : set.face_material)
    if (m < 0 || m >= static_cast<int>(set.materials.size()))
      throw InvalidInputError("export: a face has material " + std::to_string(m) + " of " +
                              std::to_string(set.materials.size()));
  for (const ExportImage& im : set.images) {
    check_export_name(im.file);
    if (im.image.empty()) throw InvalidInputError("export: image '" + im.file + "' is empty");
  }
  for (const ExportMaterial& mat : set.materials) {
    check_export_name(mat.name);
    for (const ExportMaterialMap& m : mat.maps)
      if (m.image < 0 || m.image >= static_cast<int>(set.images.size()))
        throw InvalidInputError("export: material '" + mat.name + "' refers to image " + std::to_string(m.image));
  }
  check_layout(mesh, param);
}

/// The MTL of every material: factors, then every map (`-clamp on` when \p clamp).
void write_materials_mtl(const fs::path& path, const ExportMaterials& set, bool clamp) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw OutputError(path.string() + ": cannot open for writing");
  const std::string opt = clamp ? "-clamp on " : "";
  out << "# adaptex materials\n";
  for (const ExportMaterial& m : set.materials) {
    const auto& c = m.base_color;
    out << "\nnewmtl " << m.name << "\nKa 0 0 0\nKd " << number(c[0]) << " " << number(c[1]) << " "
        << number(c[2]) << "\nKs 0 0 0\nd " << number(c[3]) << "\nillum 1\n";
    if (m.emissive != std::array<double, 3>{0, 0, 0})
      out << "Ke " << number(m.emissive[0]) << " " << number(m.emissive[1]) << " " << number(m.emissive[2]) << "\n";
    if (m.roughness) out << "Pr " << number(*m.roughness) << "\n";
    if (m.metallic) out << "Pm " << number(*m.metallic) << "\n";
    for (const ExportMaterialMap& map : m.maps) out << mtl_map_line(map.slot, opt, set.images[map.image].file);
  }
  out.close();
  if (!out) throw OutputError(path.string() + ": write error");
}

/// The .glb of export_textured_materials(): images embedded once, one primitive per used material.
std::vector<unsigned char> encode_glb_materials(const TriMesh& mesh, const Parameterization& param,
                                                const ExportMaterials& set,
                                                const std::vector<std::vector<unsigned char>>& png,
                                                const ExportOptions& options) {
  GlbBuilder b;
  bool normal_map = false;
  for (const ExportMaterial& m : set.materials)
    for (const ExportMaterialMap& map : m.maps) normal_map = normal_map || map.slot == "normal";
  b.geometry(mesh, param, options.normals, normal_map);
  std::vector<std::vector<int>> faces(set.materials.size());
  for (size_t f = 0; f < mesh.faces.size(); ++f) faces[set.face_material[f]].push_back(static_cast<int>(f));
  std::vector<tinygltf::Primitive> prims;
  for (size_t m = 0; m < set.materials.size(); ++m)
    if (!faces[m].empty()) prims.push_back(b.primitive(param, &faces[m], static_cast<int>(m)));
  b.sampler(options.wrap);
  for (size_t i = 0; i < png.size(); ++i) b.texture(fs::path(set.images[i].file).stem().string(), png[i]);
  for (const ExportMaterial& m : set.materials) {
    tinygltf::Material mat;
    mat.name = m.name;
    bool metallic_map = false;
    for (const ExportMaterialMap& map : m.maps) {
      set_glb_map(mat, map.slot, map.image);
      metallic_map = metallic_map || map.slot == "metallic_roughness";
    }
    mat.pbrMetallicRoughness.baseColorFactor = {m.base_color.begin(), m.base_color.end()};
    mat.pbrMetallicRoughness.metallicFactor = m.metallic.value_or(metallic_map ? 1.0 : 0.0);
    mat.pbrMetallicRoughness.roughnessFactor = m.roughness.value_or(1.0);
    if (m.emissive != std::array<double, 3>{0, 0, 0}) mat.emissiveFactor = {m.emissive.begin(), m.emissive.end()};
    mat.doubleSided = true;  // as export_textured_mesh(): input meshes may be wound either way
    b.model.materials.push_back(mat);
  }
  return b.finish("adaptex_materials", std::move(prims));
}

}  // namespace

ExportedFiles export_textured_materials(AtomicOutput& out, const fs::path& dir, const std::string& name,
                                        const TriMesh& mesh, const Parameterization& param,
                                        const ExportMaterials& set, const ExportOptions& options) {
  check_export_name(name);
  check_materials(mesh, param, set);
  ExportedFiles files;
  std::vector<std::vector<unsigned char>> png;
  for (const ExportImage& im : set.images) png.push_back(encode_png(im.image));
  if (options.obj) {
    files.obj = dir / (name + ".obj");
    files.mtl = dir / (name + ".mtl");
    std::vector<std::string> names;
    for (const ExportMaterial& m : set.materials) names.push_back(m.name);
    write_obj(out.add(files.obj), mesh, param, name + ".mtl", names, set.face_material);
    write_materials_mtl(out.add(files.mtl), set, options.mtl_clamp);
    for (size_t i = 0; i < png.size(); ++i) write_bytes(out, dir / set.images[i].file, png[i]);
    if (!set.images.empty()) files.png = dir / set.images[0].file;
  }
  if (options.glb) {
    files.glb = dir / (name + ".glb");
    write_bytes(out, files.glb, encode_glb_materials(mesh, param, set, png, options));
  }
  return files;
}

ImageRGBA8 draw_uv_layout(const Parameterization& param, const ImageRGBA8* texture, int size) {
  if (size <= 0) throw InvalidInputError("layout picture: size must be > 0");
  ImageRGBA8 img(size, size, {255, 255, 255, 255});
  if (texture && !texture->empty())
    for (int j = 0; j < size; ++j)
      for (int i = 0; i < size; ++i) {
        const int ti = std::min(texture->width - 1, static_cast<int>((i + 0.5) / size * texture->width));
        const int tj = std::min(texture->height - 1, static_cast<int>((j + 0.5) / size * texture->height));
        std::memcpy(img.texel(i, j), texture->texel(ti, tj), 4);
        img.texel(i, j)[3] = 255;
      }
  // Edges go into a mask first so that every edge pixel is blended exactly once.
  std::vector<char> edge(static_cast<size_t>(size) * size, 0);
  auto plot = [&](double x, double y) {
    const int i = static_cast<int>(std::floor(x)), j = static_cast<int>(std::floor(y));
    if (i >= 0 && j >= 0 && i < size && j < size) edge[static_cast<size_t>(j) * size + i] = 1;
  };
  for (const Face& f : param.uv_faces)
    for (int k = 0; k < 3; ++k) {
      if (f[k] < 0 || f[k] >= param.num_wedges() || f[(k + 1) % 3] < 0 ||
          f[(k + 1) % 3] >= param.num_wedges())
        continue;
      const Vec2 a = param.uv[f[k]] * size, b = param.uv[f[(k + 1) % 3]] * size;
      const int steps = std::max(1, static_cast<int>(std::ceil((b - a).lpNorm<Eigen::Infinity>())));
      for (int s = 0; s <= steps; ++s) {
        const Vec2 p = a + (b - a) * (static_cast<double>(s) / steps);
        plot(p.x(), p.y());
      }
    }
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i)
      if (edge[static_cast<size_t>(j) * size + i]) {
        std::uint8_t* t = img.texel(i, j);
        for (int c = 0; c < 3; ++c) t[c] = static_cast<std::uint8_t>((3 * t[c] + 2 * 40) / 5);  // 40% dark grey
      }
  return img;
}

ExportOptions material_export_options(const MaterialTextures& tex, bool glb) {
  ExportOptions o;
  o.obj = !glb;
  o.glb = glb;
  if (glb)
    o.maps = {{"metallic_roughness", tex.metallic_roughness}, {"normal", tex.normal}};
  else
    o.maps = {{"roughness", tex.roughness}, {"metallic", tex.metallic}, {"normal", tex.normal}, {"height", tex.height}};
  return o;
}

ExportedFiles export_material_textures(AtomicOutput& out, const fs::path& dir, const std::string& name,
                                       const TriMesh& mesh, const Parameterization& param,
                                       const MaterialTextures& tex, bool obj, bool glb) {
  ExportedFiles files;
  if (obj) files = export_textured_mesh(out, dir, name, mesh, param, tex.base_color, material_export_options(tex, false));
  if (glb)
    files.glb = export_textured_mesh(out, dir, name, mesh, param, tex.base_color, material_export_options(tex, true)).glb;
  return files;
}

}  // namespace adaptex
