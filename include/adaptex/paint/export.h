#pragma once
/// \file export.h
/// Export of a painted mesh to the formats artists use: Wavefront OBJ + MTL + PNG
/// and a binary glTF 2.0 (.glb) with the PNG embedded as baseColorTexture. Conventions (OBJ v = 0
/// bottom, glTF v flipped, one glTF vertex per wedge) are described in docs/export.md.
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "adaptex/core/atomic_output.h"
#include "adaptex/core/image.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/paint/material_paint.h"
#include "adaptex/paint/texture_address.h"

namespace adaptex {

/// A map of the material besides the base colour (export_textured_mesh() writes it as NAME_SLOT.png).
struct ExportMap {
  /// "normal" (MTL `norm`, glTF normalTexture), "metallic_roughness" (glTF metallicRoughnessTexture),
  /// "occlusion" (glTF occlusionTexture), "emissive" (MTL `map_Ke`, glTF emissiveTexture),
  /// "roughness" (MTL `map_Pr`), "metallic" (MTL `map_Pm`), "bump" (MTL `bump`), "specular" (MTL
  /// `map_Ks`); a slot a format has no statement for is written as a file and named in a comment.
  std::string slot;
  ImageRGBA8 image;
};

/// Settings of export_textured_mesh() and encode_glb().
struct ExportOptions {
  bool obj = true;       ///< Write NAME.obj, NAME.mtl and NAME.png.
  bool glb = true;       ///< Write NAME.glb (glTF 2.0 binary, texture embedded).
  bool normals = true;   ///< Add a NORMAL attribute to the .glb (area-weighted vertex normals,
                         ///< smooth across UV seams); the material is double-sided either way.
  std::string material = "adaptex_paint";  ///< Material name in the MTL / glTF.
  /// The .glb sampler's wrapS / wrapT (default ClampToEdge; Repeat for layouts whose UVs tile).
  TextureAddress wrap = TextureAddress::ClampToEdge;
  /// Write `map_Kd -clamp on NAME.png` in the MTL, so OBJ importers clamp too (default off: plain map_Kd).
  bool mtl_clamp = false;
  /// More maps of the material, on the same layout (default none). Slots must be distinct.
  std::vector<ExportMap> maps;
};

/// The files export_textured_mesh() registered (empty paths for formats not written).
struct ExportedFiles {
  std::filesystem::path obj, mtl, png, glb;
};

/// Checks that \p name can be used as the base name of the exported files: non-empty, no path
/// separator, no whitespace (OBJ's `mtllib` / `map_Kd` cannot hold it portably), not "." or "..".
/// \throw InvalidInputError naming the problem
void check_export_name(const std::string& name);

/// \p stem with every character that check_export_name() rejects replaced by '_' ("mesh" if empty).
std::string sanitize_export_name(const std::string& stem);

/// Registers and writes DIR/NAME.obj (input positions unchanged, `vt`, `f v/vt`, `mtllib NAME.mtl`,
/// `usemtl`), DIR/NAME.mtl (`Kd 1 1 1`, `map_Kd NAME.png`), DIR/NAME.png (the texture; PNG top row =
/// v = 1) and DIR/NAME.glb through \p out. Nothing is visible until the caller runs out.commit(), so
/// the caller can add more files (a report) to the same all-or-nothing commit.
/// \pre param.uv_faces.size() == mesh.faces.size(), !texture.empty()
/// \throw InvalidInputError bad name or inconsistent input; OutputError a file cannot be written
ExportedFiles export_textured_mesh(AtomicOutput& out, const std::filesystem::path& dir,
                                   const std::string& name, const TriMesh& mesh,
                                   const Parameterization& param, const ImageRGBA8& texture,
                                   const ExportOptions& options = {});

/// An image of export_textured_materials(): the file DIR/file and an image embedded in the .glb.
struct ExportImage {
  std::string file;  ///< File name, e.g. "NAME_skin.png" (check_export_name()-clean, unique).
  ImageRGBA8 image;
};

/// A map of an exported material: its slot ("base_color", or an ExportMap slot) and its image.
struct ExportMaterialMap {
  std::string slot;
  int image = -1;  ///< Index into ExportMaterials::images (materials may share an image).
};

/// A material of export_textured_materials(), with its factors (the input's; glTF defaults when unset).
struct ExportMaterial {
  std::string name;                              ///< MTL / glTF name (check_export_name()-clean, unique).
  std::vector<ExportMaterialMap> maps;           ///< None: an untextured material (its factors only).
  std::array<double, 4> base_color{1, 1, 1, 1};  ///< Linear RGBA factor (MTL Kd and d; glTF baseColorFactor).
  std::array<double, 3> emissive{0, 0, 0};       ///< MTL Ke; glTF emissiveFactor (1 when a map is given and this is 0).
  std::optional<double> metallic;                ///< MTL Pm; glTF metallicFactor (unset: 1 with a metallic map, else 0).
  std::optional<double> roughness;               ///< MTL Pr; glTF roughnessFactor (unset: 1).
};

/// The materials of a mesh with several of them.
struct ExportMaterials {
  std::vector<ExportImage> images;
  std::vector<ExportMaterial> materials;
  std::vector<int> face_material;  ///< F: index into materials.
};

/// Registers and writes DIR/NAME.obj (one `usemtl` per run of faces of one material, faces in input
/// order), DIR/NAME.mtl (one `newmtl` per material with its factors and every map, `-clamp on` when
/// options.mtl_clamp), every image of \p set as DIR/FILE, and DIR/NAME.glb (one primitive per material
/// that has faces, one glTF material per material, every image embedded once, one sampler of
/// options.wrap) through \p out, as export_textured_mesh() (options.material and options.maps unused).
/// \pre param.uv_faces.size() == mesh.faces.size() == set.face_material.size()
/// \throw InvalidInputError bad name, empty image, bad index or inconsistent input; OutputError
ExportedFiles export_textured_materials(AtomicOutput& out, const std::filesystem::path& dir, const std::string& name,
                                        const TriMesh& mesh, const Parameterization& param,
                                        const ExportMaterials& set, const ExportOptions& options = {});

/// Encodes a glTF 2.0 binary (.glb) with tinygltf: one mesh, one triangle primitive with POSITION
/// (float32, with min/max), optional NORMAL, TANGENT when NORMAL is written and a map has slot "normal"
/// (MikkTSpace per wedge, w = handedness: paint/tangent_frame.h), TEXCOORD_0 = (u, 1 - v) and uint32 indices; one glTF
/// vertex per wedge (glTF has per-vertex UVs only); a material whose pbrMetallicRoughness
/// baseColorTexture is the PNG of \p texture embedded in a bufferView (sampler: linear magnification,
/// trilinear minification, wrap mode options.wrap: clamp-to-edge by default).
/// \throw InvalidInputError inconsistent input; OutputError encoding failed
std::vector<unsigned char> encode_glb(const TriMesh& mesh, const Parameterization& param,
                                      const ImageRGBA8& texture, const ExportOptions& options = {});

/// Registers a painted layered material (paint_material()) on \p param through \p out, as
/// `adaptex paint` writes it (docs/export.md): with \p obj DIR/NAME.obj/.mtl/.png (map_Kd) with
/// NAME_roughness.png (map_Pr), NAME_metallic.png (map_Pm), NAME_normal.png (norm) and
/// NAME_height.png; with \p glb DIR/NAME.glb, a glTF metallic-roughness material (baseColor,
/// metallicRoughness packed, normal).
/// \pre param.uv_faces.size() == mesh.faces.size(), textures of one size
/// \throw as export_textured_mesh()
/// The options export_material_textures() writes \p textures with: for the OBJ (\p glb false) the
/// maps roughness, metallic, normal and height; for the .glb (\p glb true) metallic_roughness and
/// normal (base colour: the texture argument, textures.base_color). encode_glb() with them gives the
/// same .glb bytes.
ExportOptions material_export_options(const MaterialTextures& textures, bool glb);
ExportedFiles export_material_textures(AtomicOutput& out, const std::filesystem::path& dir, const std::string& name,
                                       const TriMesh& mesh, const Parameterization& param,
                                       const MaterialTextures& textures, bool obj = true, bool glb = true);

/// Writes a one-material MTL file (`newmtl`, `Kd 1 1 1`, `map_Kd`; `map_Kd -clamp on` when \p clamp).
/// Writes \p path directly.
/// \throw OutputError
void write_mtl(const std::filesystem::path& path, const std::string& material,
               const std::string& texture_file, bool clamp = false);

/// A picture of the UV layout: the texture (or white when \p texture is null / empty) scaled to
/// size x size by nearest lookup, with every UV triangle edge blended 40% towards dark grey on top.
/// Rows from v = 0 (write it with write_png). \pre size > 0
ImageRGBA8 draw_uv_layout(const Parameterization& param, const ImageRGBA8* texture, int size);

}  // namespace adaptex
