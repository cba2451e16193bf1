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
#include "adaptex/paint/signal.h"
#include "adaptex/paint/tangent_frame.h"
#include "adaptex/paint/texel_map.h"

namespace adaptex {

struct HeightNormalTerms;

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

/// The textures of a layout from the material at its chart texels: paint_material() after the
/// evaluation (padding, 8-bit channels, the glTF packing, the normal map derived with \p height_scale).
/// \p map is the layout's texel map (its size is the textures'); \p values one per map.inside texel
/// (as evaluate_material() at texel_points(map)); texels outside charts and padding hold \p background.
/// \throw InvalidInputError values.size() != map.inside.size(), padding < 0
MaterialTextures material_textures_from_values(const TriMesh& mesh, const Parameterization& param, const TexelMap& map,
                                               const std::vector<MaterialValue>& values,
                                               const MaterialValue& background, int padding, double height_scale);
/// As above, into \p out, reusing its storage (a session's next candidate layout). \p painted: the
/// channels whose values may differ from the background (painted_channels()); the images of the others
/// (the normal map: of the height) are filled flat without reading \p values, the same bytes when their
/// values are the background exactly (as evaluate_material() gives them). \p terms: the layout's
/// height_normal_terms() when the caller has them (the same normals), else computed when needed.
/// \throw as above
void material_textures_from_values(const TriMesh& mesh, const Parameterization& param, const TexelMap& map,
                                   const std::vector<MaterialValue>& values, const MaterialValue& background,
                                   int padding, double height_scale, MaterialTextures& out,
                                   unsigned painted = kAllChannels, const HeightNormalTerms* terms = nullptr);

/// The channels some layer of \p file paints (its brush and fill strokes name them; a decal paints
/// the base colour): every other channel of the composite is the background, exactly.
unsigned painted_channels(const MaterialStrokeFile& file);

/// Writes the material \p v into texel \p t (row-major index) of the 8-bit channel textures of \p tex
/// (base colour and alpha, roughness, metallic, height, the metallic-roughness packing; not the normal
/// map), as paint_material() does. \pre t inside the textures
void set_material_texel(MaterialTextures& tex, int t, const MaterialValue& v);
/// Writes the unit normal \p n into texel \p t of a normal map, as normal_map_from_height() does.
void set_normal_texel(ImageRGBA8& normal_map, int t, const Vec3f& n);

/// The height scale of \p file on \p mesh: the file's, or 1 % of the bounding-box diagonal.
double material_height_scale(const TriMesh& mesh, const MaterialStrokeFile& file);

/// The surface points of the chart texels' centres of \p map, shape [map.inside.size()].
std::vector<SurfacePoint> texel_points(const TexelMap& map);

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

/// height_normals() at the texels \p texels only (row-major indices; a texel outside charts gets the
/// flat normal): after the heights of some texels changed, these texels and their 4-neighbours.
/// \pre height.size() == normals.size() == map.width * map.height
void update_height_normals(const TriMesh& mesh, const Parameterization& param, const TexelMap& map,
                           const std::vector<double>& height, const std::vector<int>& texels,
                           std::vector<Vec3f>& normals);

/// What height_normals() reads per face of one layout, computed once for it: the vertex normals and
/// wedge tangents of the exported frame, and per face ∂P/∂u, ∂P/∂v, their metric and the face normal.
struct HeightNormalTerms {
  struct Face {
    Vec3 pu, pv;           ///< face_uv_gradients()
    Vec3 normal;           ///< face_normal()
    double a, b, c, det;   ///< The metric [a b; b c] of the face's UV map and its determinant.
    bool usable;           ///< pu, pv non-zero and det > 0 (else the face's texels keep the flat normal)
  };
  std::vector<Vec3> vertex_normals;        ///< vertex_normals(mesh)
  std::vector<Eigen::Vector4d> tangents;   ///< wedge_tangents(mesh, param, vertex_normals)
  std::vector<Face> faces;                 ///< Shape F.
};

/// The terms of \p param on \p mesh.
/// \throw InvalidInputError the layout and the mesh disagree in size
HeightNormalTerms height_normal_terms(const TriMesh& mesh, const Parameterization& param);

/// update_height_normals() with the layout's terms computed already (height_normal_terms() of the
/// same mesh and layout): the same normals.
/// \pre height.size() == normals.size() == map.width * map.height, terms of mesh and param
void update_height_normals(const TriMesh& mesh, const Parameterization& param, const HeightNormalTerms& terms,
                           const TexelMap& map, const std::vector<double>& height, const std::vector<int>& texels,
                           std::vector<Vec3f>& normals);

/// The tangent-space normal of a height field H (world units per texel of \p map, W*H values; only
/// texels inside charts are read) over the surface: n' = normalize(n − ∇H) with ∇H the surface
/// gradient from central differences along u and v within the chart, expressed in the frame a renderer
/// interpolates at the texel from the vertex normals and MikkTSpace tangents that the .glb carries
/// (paint/tangent_frame.h: tangent along ∂P/∂u, bitangent w · n × tangent, w = ±1 the chart's handedness).
/// Texels outside every chart hold the flat normal (0, 0, 1).
/// \pre height.size() == map.width * map.height
ImageRGBA8 normal_map_from_height(const TriMesh& mesh, const Parameterization& param, const TexelMap& map,
                                  const std::vector<double>& height);
/// normal_map_from_height() into \p out, reusing its storage (a session's candidate layouts); \p terms:
/// height_normal_terms() of \p mesh and \p param when the caller has them, else computed here.
/// \throw InvalidInputError \p terms are of another mesh or layout (face, vertex or wedge count)
void normal_map_from_height(const TriMesh& mesh, const Parameterization& param, const TexelMap& map,
                            const std::vector<double>& height, ImageRGBA8& out,
                            const HeightNormalTerms* terms = nullptr);

}  // namespace adaptex
