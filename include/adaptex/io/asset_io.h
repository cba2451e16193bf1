#pragma once
/// \file asset_io.h
/// Reading a textured asset as an artist made it: the mesh, its UV atlas, the materials of its faces
/// and every texture map they name (OBJ + MTL; glTF/GLB materials). The atlas is read as it is:
/// mirrored and overlapping (shared) charts stay, degenerate UV triangles are kept and counted. Only
/// whole charts outside [0,1]^2 are moved, by an integer offset (the same texels under repeat
/// wrapping). What is supported, exactly: docs/io.md ("Textured assets").
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "adaptex/core/image.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/io/mesh_io.h"

namespace adaptex {

/// What a texture map means to the renderer.
enum class MapSlot {
  BaseColor,          ///< Diffuse / albedo colour (OBJ map_Kd, glTF baseColorTexture). sRGB.
  MetallicRoughness,  ///< glTF metallicRoughnessTexture: roughness in G, metalness in B. Linear.
  Roughness,          ///< OBJ map_Pr (one channel). Linear.
  Metallic,           ///< OBJ map_Pm (one channel). Linear.
  Normal,             ///< Tangent-space normal map (OBJ norm; glTF normalTexture). Linear.
  Bump,               ///< Height map (OBJ bump / map_Bump holding heights). Linear.
  Occlusion,          ///< Ambient occlusion in R (glTF occlusionTexture). Linear.
  Emissive,           ///< Emitted colour (OBJ map_Ke, glTF emissiveTexture). sRGB.
};

/// "base_color", "metallic_roughness", "roughness", "metallic", "normal", "bump", "occlusion", "emissive".
const char* map_slot_name(MapSlot slot);

/// One texture map of a material.
struct TextureMap {
  MapSlot slot = MapSlot::BaseColor;
  /// The image file (resolved: relative names against the MTL's / glTF's folder). For an image
  /// embedded in a glTF/GLB: the asset's path followed by "#image<N>".
  std::filesystem::path path;
  ImageRGBA8 image;   ///< The decoded map (empty when AssetReadOptions::load_images is false).
  bool srgb = false;  ///< Colour data in sRGB (base colour, emissive); the rest are linear data.
  /// Strength: OBJ `-bm` (bump multiplier), glTF normalTexture.scale / occlusionTexture.strength; 1 otherwise.
  double scale = 1.0;
  /// Where the map was named, for messages: "model.mtl: line 7: map_Kd 'skin.tga'" or
  /// "model.glb: material 0 'Skin': baseColorTexture (image 1)".
  std::string origin;
};

/// A material: its factors and its texture maps (at most one per slot; the first statement wins).
struct Material {
  std::string name;
  std::vector<TextureMap> maps;
  std::array<double, 4> base_color{1, 1, 1, 1};  ///< Linear RGBA factor (OBJ Kd and d; glTF baseColorFactor).
  std::array<double, 3> emissive{0, 0, 0};       ///< OBJ Ke; glTF emissiveFactor.
  std::optional<double> metallic;                ///< OBJ Pm; glTF metallicFactor (unset: the format's default).
  std::optional<double> roughness;               ///< OBJ Pr; glTF roughnessFactor.

  /// The map of \p slot, or nullptr.
  const TextureMap* find(MapSlot slot) const;
};

/// UV faces with |signed area| at most this are degenerate (about 1e-6 of a texel of an 8192² map).
inline constexpr double kDegenerateUvArea = 1e-14;

/// What an asset's UV atlas contains (analyze_uvs(); read_textured_asset() adds what it moved).
struct UvReport {
  int charts = 0;               ///< Charts: faces connected through shared UV corners (wedges).
  int mirrored_faces = 0;       ///< UV signed area < -kDegenerateUvArea (reversed against the 3-D winding).
  int mirrored_charts = 0;      ///< Charts whose mirrored UV area exceeds their unmirrored UV area.
  int degenerate_uv_faces = 0;  ///< |UV signed area| <= kDegenerateUvArea (kept as they are).
  int faces_outside_unit = 0;   ///< Faces with a UV corner outside [0,1]^2 as read (before wrapping).
  int wrapped_charts = 0;       ///< Charts lying in one integer tile other than [0,1]^2, moved into it.
  int clamped_uvs = 0;          ///< UV coordinates within AssetReadOptions::uv_tolerance outside their tile, clamped.
  /// Charts crossing a UV tile border, left where they are (AssetReadOptions::keep_straddling_charts).
  int straddling_charts = 0;
  /// Faces without texture coordinates (a glTF primitive without TEXCOORD_0 whose material has no
  /// map): every corner gets UV (0, 0), so they are degenerate too.
  int untextured_faces = 0;
  /// Fraction of the texels of a kTexelUsageResolution² grid over [0,1]^2 whose centre lies in a UV
  /// triangle (after wrapping): how much of the square the atlas uses.
  double covered_fraction = 0;
  /// Fraction of those covered texels that lie in two or more UV triangles: texels shared by
  /// overlapping (e.g. mirrored) charts or folds.
  double shared_fraction = 0;
};

/// Grid of UvReport::covered_fraction and shared_fraction.
inline constexpr int kTexelUsageResolution = 1024;

/// Covered and shared texels of an atlas on a \p size x \p size grid over [0,1]^2 (texel centres;
/// edges shared by two triangles count once, by the top-left rule; degenerate triangles cover nothing;
/// parts outside [0,1]^2 are not counted). When the triangles' bounding boxes would make it test more
/// than 64 Mi texel centres (hostile input) the grid is made coarser so that it does not.
struct TexelUsage {
  double covered_fraction = 0;  ///< Covered texels / size².
  double shared_fraction = 0;   ///< Texels in two or more triangles / covered texels (0 when none is covered).
};
/// \pre size >= 1, every UV finite. \throw InvalidInputError size < 1 or larger than kMaxTextureSize
TexelUsage measure_texel_usage(const Parameterization& param, int size = kTexelUsageResolution);

/// Options of read_textured_asset().
struct AssetReadOptions {
  ReadOptions mesh;            ///< Mesh validation and repair, as read_mesh().
  bool load_images = true;     ///< Decode every map (false: maps are found and named, image left empty).
  /// How far (in UV units) a chart may cross the border of its integer tile and still count as inside
  /// it; such coordinates are clamped to the border (and counted). Default 0.001: one texel at 1024².
  double uv_tolerance = 1e-3;
  /// Leave charts that cross a UV tile border where they are, with UVs outside [0,1]^2 (counted in
  /// UvReport::straddling_charts, with a warning), as real atlases often have them (a chart a little
  /// past the border reads the edge texels under clamp-to-edge). Default true; false rejects such an
  /// asset with an InvalidInputError that names the chart.
  bool keep_straddling_charts = true;
};

/// A mesh with its artist's UV atlas and materials.
struct TexturedAsset {
  TriMesh mesh;
  /// The atlas: charts are the connected components of the UV faces; every UV lies in [0,1]^2 after
  /// wrapping (see UvReport::wrapped_charts), except in charts kept by keep_straddling_charts. Wedges
  /// are ordered as read_textured_obj() orders them.
  Parameterization param;
  std::vector<int> face_material;   ///< F: index into materials, or -1 (no material).
  std::vector<Material> materials;  ///< In the order the file defines them.
  UvReport uv;                      ///< What the atlas contains.
};

/// Reads an OBJ (with its `mtllib` material files) or a glTF/GLB with texture coordinates, its
/// materials and their texture maps (PNG, JPEG, TGA through read_image()).
/// Mesh validation as read_mesh() (with \p options.mesh); the UVs as read_textured_obj() reads them,
/// then whole charts outside [0,1]^2 are moved into it by an integer offset.
/// \pre none (every problem is reported by an exception).
/// \throw IoError unreadable or corrupt file, a material file or map that is missing, unreadable,
/// corrupt, or the asset/material file itself
/// \throw InvalidInputError no UVs, NaN/inf UVs, UDIM tiles, a chart that straddles a UV tile border
/// (only with keep_straddling_charts false)
/// \throw TopologyError as read_mesh()
TexturedAsset read_textured_asset(const std::filesystem::path& path, const AssetReadOptions& options = {},
                                  ReadReport* report = nullptr);

/// read_textured_asset() on the bytes of the mesh file already in memory; \p format is its extension
/// ("obj", ".glb", ...). \p name stands for the file: messages name it, and its folder resolves
/// material files, texture maps and external buffers (which are read from disk).
/// \pre none. \throw as read_textured_asset()
TexturedAsset read_textured_asset_from_memory(const std::string& bytes, const std::string& format,
                                              const std::filesystem::path& name, const AssetReadOptions& options = {},
                                              ReadReport* report = nullptr);

/// Parses MTL text (newmtl, Kd, d, Tr, Ke, Pr, Pm and the map statements map_Kd, map_Pr, map_Pm,
/// map_Ke, norm, map_Bump, bump with their options). Map paths are resolved against \p name's folder
/// but not opened; images are left empty. Other statements are ignored.
/// \pre none. \throw IoError a malformed statement (named by file and line)
std::vector<Material> parse_mtl(const std::string& text, const std::filesystem::path& name,
                                std::vector<std::string>* warnings = nullptr);

/// Counts what an atlas contains (UvReport; wrapped_charts and clamped_uvs stay 0; the texel usage is
/// measured on the UVs as they are).
/// \pre param.uv_faces.size() == mesh.faces.size(), param.face_chart set
UvReport analyze_uvs(const TriMesh& mesh, const Parameterization& param);

}  // namespace adaptex
