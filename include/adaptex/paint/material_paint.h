#pragma once
/// \file material_paint.h
/// A layered material (stroke file version 2) painted into the textures of one layout: every channel
/// point-sampled at the texel centres (as the version 1 painter does), the glTF packings, and the
/// tangent-space normal map derived from the height (docs/strokes.md, "The derived normal").
#include <optional>
#include <utility>
#include <vector>

#include "adaptex/core/image.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/paint/material_strokes.h"
#include "adaptex/paint/texel_map.h"

namespace adaptex {

/// Settings of paint_material().
struct MaterialPaintOptions {
  int size = 1024;  ///< Width = height of every texture, in [1, kMaxTextureSize] (default 1024).
  int padding = 4;  ///< Seam padding in texels around the charts (default 4).
};

/// The textures of a painted material, all size x size on the same layout (row 0 at v = 0).
struct MaterialTextures {
  ImageRGBA8 base_color;          ///< RGB base colour, A = the alpha channel.
  ImageRGBA8 roughness;           ///< Grey (R = G = B), A = 255.
  ImageRGBA8 metallic;            ///< Grey.
  ImageRGBA8 height;              ///< Grey.
  ImageRGBA8 metallic_roughness;  ///< glTF packing: R = 255 (unused), G = roughness, B = metallic.
  ImageRGBA8 normal;              ///< Tangent space (glTF: +X along u, +Y along v), RGB = 127.5 (n + 1).
  double height_scale = 0;        ///< World units per unit of height that the normal map used.
};

/// Paints \p file into textures on \p param: each texel inside a chart holds the exact material at its
/// centre's surface point, padded texels copy their nearest chart texel, the rest hold the background.
/// The height scale is the file's, or 1 % of the bounding-box diagonal when the file gives none.
/// \pre param matches mesh
/// \throw InvalidInputError size or padding out of range, inconsistent layout, a decal breaking the rules
MaterialTextures paint_material(const TriMesh& mesh, const Parameterization& param, const MaterialStrokeFile& file,
                                const MaterialPaintOptions& options = {});

/// One layer of a material as pictures on the layout (docs/export.md, "Layers as separate PNGs"),
/// all size x size, row 0 at v = 0.
struct LayerTextures {
  /// Each channel the layer paints (a brush or fill stroke names it; decals paint base colour), in
  /// Channel order: RGB = the layer's value L_c (grey for one-component channels), A = its coverage a_c.
  std::vector<std::pair<Channel, ImageRGBA8>> channels;
  std::optional<ImageRGBA8> mask;  ///< The mask M as grey (A = 255); only for a layer with a mask.
};

/// Paints every layer of \p file alone (MaterialLayerSamples) into textures on \p param, texel by
/// texel as paint_material() (chart texels exact at their centres, padded texels copy their nearest
/// chart texel, the rest transparent black / mask 0). Compositing them over the background with each
/// layer's visibility, opacity and blend mode gives paint_material()'s textures (up to 8-bit rounding).
/// \pre param matches mesh
/// \throw as paint_material()
std::vector<LayerTextures> paint_material_layers(const TriMesh& mesh, const Parameterization& param,
                                                 const MaterialStrokeFile& file, const MaterialPaintOptions& options = {});

/// The unit tangent-space normals behind normal_map_from_height(), W*H ((0, 0, 1) outside charts).
/// \pre height.size() == map.width * map.height
std::vector<Vec3f> height_normals(const TriMesh& mesh, const Parameterization& param, const TexelMap& map,
                                  const std::vector<double>& height);

/// The tangent-space normal of a height field H (world units per texel of \p map, W*H values; only
/// texels inside charts are read) over the surface: n' = normalize(n − ∇H) with ∇H the surface
/// gradient from central differences along u and v within the chart, expressed in the frame a renderer
/// interpolates at the texel from the vertex normals and MikkTSpace tangents that the .glb carries
/// (paint/tangent_frame.h: tangent along ∂P/∂u, bitangent w · n × tangent, w = ±1 the chart's handedness).
/// Texels outside every chart hold the flat normal (0, 0, 1).
/// \pre height.size() == map.width * map.height
ImageRGBA8 normal_map_from_height(const TriMesh& mesh, const Parameterization& param, const TexelMap& map,
                                  const std::vector<double>& height);

}  // namespace adaptex
