/// \file material_paint.cpp
/// Channel textures of a layered material on one layout, and the normal map derived from its height.
#include "adaptex/paint/material_paint.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <optional>
#include <tuple>

#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "adaptex/paint/material_signal.h"
#include "adaptex/paint/padding.h"
#include "adaptex/paint/tangent_frame.h"

namespace adaptex {

namespace {

/// round(clamp(v, 0, 1) * 255), halves away from zero (std::lround's result, without its call: the
/// textures convert every texel of every map). NaN gives 0, as lround's out-of-range value does.
std::uint8_t to_byte(double v) {
  const double x = std::clamp(v, 0.0, 1.0) * 255.0;
  if (!(x >= 0)) return 0;
  const int i = static_cast<int>(x);  // truncation; x - i is exact
  return static_cast<std::uint8_t>(i + (x - i >= 0.5 ? 1 : 0));
}

/// Derivative of the height along one texel axis at texel (i, j): central where both neighbours lie in
/// a chart, one-sided where one does, 0 where none does. \p step is the neighbour offset (1 or W).
double axis_derivative(const TexelMap& map, const std::vector<double>& h, int t, int i, int n, int step, double texel) {
  const bool lo = i > 0 && map.face[t - step] >= 0, hi = i + 1 < n && map.face[t + step] >= 0;
  if (lo && hi) return (h[t + step] - h[t - step]) / (2 * texel);
  if (hi) return (h[t + step] - h[t]) / texel;
  if (lo) return (h[t] - h[t - step]) / texel;
  return 0;
}

void put_normal(ImageRGBA8& img, int t, const Vec3& n) {
  for (int c = 0; c < 3; ++c) img.data[4 * t + c] = to_byte(0.5 * (n[c] + 1));
  img.data[4 * t + 3] = 255;
}

/// The unit normal of texel \p t from the height's derivatives ((0, 0, 1) outside the charts, where
/// the height is flat, or on a degenerate UV triangle).
Vec3f height_normal_at(const TriMesh& mesh, const Parameterization& param, const HeightNormalTerms& terms,
                       const TexelMap& map, const std::vector<double>& height, int t) {
  const int i = t % map.width, j = t / map.width, f = map.face[t];
  if (f < 0) return Vec3f(0, 0, 1);
  const double hu = axis_derivative(map, height, t, i, map.width, 1, 1.0 / map.width);
  const double hv = axis_derivative(map, height, t, j, map.height, map.width, 1.0 / map.height);
  if (hu == 0 && hv == 0) return Vec3f(0, 0, 1);  // flat height: the surface's own normal, in any frame
  const HeightNormalTerms::Face& x = terms.faces[f];
  if (!x.usable) return Vec3f(0, 0, 1);  // degenerate UV triangle: flat
  // Surface gradient: ∇H = [pu pv] G⁻¹ (hu, hv), G the metric of the face's UV map.
  const Vec3 grad = x.pu * ((x.c * hu - x.b * hv) / x.det) + x.pv * ((x.a * hv - x.b * hu) / x.det);
  // n' = normalize(n − ∇H) in the frame a renderer interpolates from the exported NORMAL and TANGENT.
  const TangentFrame fr = interpolated_frame(mesh, param, terms.vertex_normals, terms.tangents, f, map.bary[t].x(),
                                             map.bary[t].y(), x.normal, x.pu);
  return Vec3(-grad.dot(fr.t), -grad.dot(fr.b), 1).normalized().cast<float>();
}

}  // namespace

std::vector<Vec3f> height_normals(const TriMesh& mesh, const Parameterization& param, const TexelMap& map,
                                  const std::vector<double>& height) {
  std::vector<Vec3f> normals(height.size(), Vec3f(0, 0, 1));
  update_height_normals(mesh, param, map, height, map.inside, normals);
  return normals;
}

HeightNormalTerms height_normal_terms(const TriMesh& mesh, const Parameterization& param) {
  if (param.uv_faces.size() != mesh.faces.size())
    throw InvalidInputError("height normals: the layout and the mesh have different face counts");
  HeightNormalTerms out;
  out.vertex_normals = vertex_normals(mesh);
  out.tangents = wedge_tangents(mesh, param, out.vertex_normals);
  out.faces.resize(mesh.faces.size());
  tbb::parallel_for(size_t(0), mesh.faces.size(), [&](size_t f) {
    HeightNormalTerms::Face& x = out.faces[f];
    face_uv_gradients(mesh, param, static_cast<int>(f), x.pu, x.pv);
    x.normal = face_normal(mesh, static_cast<int>(f));
    x.a = x.pu.dot(x.pu), x.b = x.pu.dot(x.pv), x.c = x.pv.dot(x.pv), x.det = x.a * x.c - x.b * x.b;
    x.usable = x.pu.norm() > 0 && x.pv.norm() > 0 && x.det > 0;
  });
  return out;
}

void update_height_normals(const TriMesh& mesh, const Parameterization& param, const TexelMap& map,
                           const std::vector<double>& height, const std::vector<int>& texels,
                           std::vector<Vec3f>& normals) {
  update_height_normals(mesh, param, height_normal_terms(mesh, param), map, height, texels, normals);
}

void update_height_normals(const TriMesh& mesh, const Parameterization& param, const HeightNormalTerms& terms,
                           const TexelMap& map, const std::vector<double>& height, const std::vector<int>& texels,
                           std::vector<Vec3f>& normals) {
  if (height.size() != static_cast<size_t>(map.width) * map.height || normals.size() != height.size())
    throw InvalidInputError("normal_map_from_height: one height per texel expected");
  tbb::parallel_for(size_t(0), texels.size(), [&](size_t k) {
    const int t = texels[k];
    normals[t] = height_normal_at(mesh, param, terms, map, height, t);
  });
}

ImageRGBA8 normal_map_from_height(const TriMesh& mesh, const Parameterization& param, const TexelMap& map,
                                  const std::vector<double>& height) {
  ImageRGBA8 img;
  normal_map_from_height(mesh, param, map, height, img);
  return img;
}

void normal_map_from_height(const TriMesh& mesh, const Parameterization& param, const TexelMap& map,
                            const std::vector<double>& height, ImageRGBA8& out, const HeightNormalTerms* terms) {
  if (height.size() != static_cast<size_t>(map.width) * map.height)
    throw InvalidInputError("normal_map_from_height: one height per texel expected");
  std::optional<HeightNormalTerms> own;
  if (!terms) terms = &own.emplace(height_normal_terms(mesh, param));
  // A layout's terms hold one tangent per wedge: terms of another layout of the same mesh differ there.
  if (terms->faces.size() != mesh.faces.size() || terms->vertex_normals.size() != mesh.positions.size() ||
      terms->tangents.size() != param.uv.size())
    throw InvalidInputError("normal_map_from_height: the normal terms are of another mesh or layout");
  out.width = map.width, out.height = map.height;
  out.data.resize(height.size() * 4);
  // Most texels are flat (outside the charts, or a flat height): put_normal()'s bytes of (0, 0, 1), once.
  ImageRGBA8 flat(1, 1);
  put_normal(flat, 0, Vec3(0, 0, 1));
  tbb::parallel_for(tbb::blocked_range<size_t>(0, height.size(), 1 << 14), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t t = r.begin(); t < r.end(); ++t) {
      const Vec3f n = height_normal_at(mesh, param, *terms, map, height, static_cast<int>(t));
      if (n == Vec3f(0, 0, 1))
        std::copy_n(flat.data.begin(), 4, out.data.begin() + 4 * t);
      else
        put_normal(out, static_cast<int>(t), n.cast<double>());
    }
  });
}

namespace {

void check_paint_options(const TriMesh& mesh, const Parameterization& param, const MaterialPaintOptions& options) {
  if (options.size < 1 || options.size > kMaxTextureSize)
    throw InvalidInputError("paint_material: size must be in [1, " + std::to_string(kMaxTextureSize) + "]");
  if (options.padding < 0) throw InvalidInputError("paint_material: padding must be >= 0");
  if (param.uv_faces.size() != mesh.faces.size())
    throw InvalidInputError("paint_material: the layout and the mesh have different face counts");
}

/// The channels layer \p l paints: those its brush, fill and decal strokes name.
unsigned painted_channels(const MaterialLayer& l) {
  unsigned bits = 0;
  for (const MaterialStroke& s : l.strokes)
    if (s.type != MaterialStroke::Type::Erase) bits |= s.channels;
  return bits;
}

}  // namespace

std::vector<LayerTextures> paint_material_layers(const TriMesh& mesh, const Parameterization& param,
                                                 const MaterialStrokeFile& file, const MaterialPaintOptions& options) {
  check_paint_options(mesh, param, options);
  const int N = options.size;
  const TexelMap map = build_texel_map(mesh, param, N, N);
  const std::vector<SurfacePoint> points = texel_points(map);
  const SeamPadding pad = build_seam_padding(map, options.padding);
  std::vector<LayerTextures> out(file.layers.size());
  for (size_t l = 0; l < file.layers.size(); ++l) {
    const MaterialLayerSamples st = evaluate_layer(mesh, file, static_cast<int>(l), points);
    const unsigned bits = painted_channels(file.layers[l]);
    for (int c = 0; c < kNumChannels; ++c) {
      const auto ch = static_cast<Channel>(c);
      if (!(bits & channel_bit(ch))) continue;
      ImageRGBA8 img(N, N);
      const int o = channel_offset(ch), n = channel_components(ch);
      for (size_t k = 0; k < points.size(); ++k) {
        std::uint8_t* p = &img.data[4 * static_cast<size_t>(map.inside[k])];
        for (int j = 0; j < 3; ++j) p[j] = to_byte(st.value[k][o + std::min(j, n - 1)]);
        p[3] = to_byte(st.cover[k][c]);
      }
      apply_seam_padding(img, pad);
      out[l].channels.emplace_back(ch, std::move(img));
    }
    if (file.layers[l].mask) {
      ImageRGBA8 img(N, N, {0, 0, 0, 255});
      for (size_t k = 0; k < points.size(); ++k)
        std::fill_n(&img.data[4 * static_cast<size_t>(map.inside[k])], 3, to_byte(st.mask[k]));
      apply_seam_padding(img, pad);
      out[l].mask = std::move(img);
    }
  }
  return out;
}

std::vector<SurfacePoint> texel_points(const TexelMap& map) {
  std::vector<SurfacePoint> points(map.inside.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 1 << 14), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t k = r.begin(); k < r.end(); ++k) {
      const int t = map.inside[k];
      points[k] = SurfacePoint{map.face[t], map.bary[t].x(), map.bary[t].y()};
    }
  });
  return points;
}

double material_height_scale(const TriMesh& mesh, const MaterialStrokeFile& file) {
  return file.height_scale > 0 ? file.height_scale : 0.01 * bounding_box(mesh).diagonal();
}

MaterialTextures paint_material(const TriMesh& mesh, const Parameterization& param, const MaterialStrokeFile& file,
                                const MaterialPaintOptions& options) {
  check_paint_options(mesh, param, options);
  const int N = options.size;
  const TexelMap map = build_texel_map(mesh, param, N, N);
  MaterialTextures out;
  material_textures_from_values(mesh, param, map, evaluate_material(mesh, file, texel_points(map)), file.background,
                                options.padding, material_height_scale(mesh, file), out, painted_channels(file));
  return out;
}

namespace {

bool paints(unsigned painted, Channel c) { return (painted & channel_bit(c)) != 0; }

/// set_material_texel() into the images of the \p painted channels only (each component's byte
/// converted once, written as whole texels).
void set_painted_texel(MaterialTextures& tex, int t, const MaterialValue& v, unsigned painted) {
  const size_t o = 4 * static_cast<size_t>(t);
  std::uint8_t b[kMaterialComponents];
  for (int c = 0; c < kMaterialComponents; ++c) b[c] = to_byte(v[c]);
  if (paints(painted, Channel::BaseColor) || paints(painted, Channel::Alpha)) std::memcpy(&tex.base_color.data[o], b, 4);
  const std::pair<Channel, ImageRGBA8*> greys[] = {
      {Channel::Roughness, &tex.roughness}, {Channel::Metallic, &tex.metallic}, {Channel::Height, &tex.height}};
  for (int g = 0; g < 3; ++g)
    if (paints(painted, greys[g].first)) std::fill_n(&greys[g].second->data[o], 3, b[4 + g]);
  if (paints(painted, Channel::Roughness) || paints(painted, Channel::Metallic)) {
    const std::uint8_t mr[4] = {255, b[4], b[5], 255};
    std::memcpy(&tex.metallic_roughness.data[o], mr, 4);
  }
}

}  // namespace

void set_material_texel(MaterialTextures& tex, int t, const MaterialValue& v) { set_painted_texel(tex, t, v, kAllChannels); }

unsigned painted_channels(const MaterialStrokeFile& file) {
  unsigned bits = 0;
  for (const MaterialLayer& l : file.layers) bits |= painted_channels(l);
  return bits;
}

void set_normal_texel(ImageRGBA8& normal_map, int t, const Vec3f& n) { put_normal(normal_map, t, n.cast<double>()); }

namespace {

/// \p img as a w x h image filled with \p rgba, reusing its storage (filled in parallel, a texel per
/// 4-byte store: a copy per texel was a library call).
void fill_image(ImageRGBA8& img, int w, int h, std::array<std::uint8_t, 4> rgba) {
  img.width = w, img.height = h;
  img.data.resize(static_cast<size_t>(w) * h * 4);
  std::uint32_t word;
  std::memcpy(&word, rgba.data(), 4);
  std::uint8_t* out = img.data.data();
  tbb::parallel_for(tbb::blocked_range<size_t>(0, static_cast<size_t>(w) * h, 1 << 14), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t k = r.begin(); k < r.end(); ++k) std::memcpy(out + 4 * k, &word, 4);
  });
}

}  // namespace

MaterialTextures material_textures_from_values(const TriMesh& mesh, const Parameterization& param, const TexelMap& map,
                                               const std::vector<MaterialValue>& values,
                                               const MaterialValue& background, int padding, double height_scale) {
  MaterialTextures out;
  material_textures_from_values(mesh, param, map, values, background, padding, height_scale, out);
  return out;
}

void material_textures_from_values(const TriMesh& mesh, const Parameterization& param, const TexelMap& map,
                                   const std::vector<MaterialValue>& values, const MaterialValue& background,
                                   int padding, double height_scale, MaterialTextures& out, unsigned painted,
                                   const HeightNormalTerms* terms) {
  if (values.size() != map.inside.size())
    throw InvalidInputError("material textures: one value per chart texel expected");
  if (padding < 0) throw InvalidInputError("material textures: padding must be >= 0");
  const int N = map.width;
  out.height_scale = height_scale;
  const MaterialValue& bg = background;
  fill_image(out.base_color, N, map.height, {to_byte(bg[0]), to_byte(bg[1]), to_byte(bg[2]), to_byte(bg[3])});
  const std::pair<ImageRGBA8*, double> grey_images[] = {{&out.roughness, bg[4]}, {&out.metallic, bg[5]}, {&out.height, bg[6]}};
  for (const auto& [img, g] : grey_images) fill_image(*img, N, map.height, {to_byte(g), to_byte(g), to_byte(g), 255});
  fill_image(out.metallic_roughness, N, map.height, {255, to_byte(bg[4]), to_byte(bg[5]), 255});
  // Chart texels from their values; padded texels then copy their source texel's bytes (what copying
  // the source's value would give); the normal map reads chart texels' heights only. A channel not
  // painted is its flat fill already, and a flat height's normal is (0, 0, 1) at every texel.
  const bool height = paints(painted, Channel::Height);
  std::vector<double> h(height ? static_cast<size_t>(N) * map.height : 0, (bg[6] - 0.5) * height_scale);
  // A texel of the background's value keeps the fill's bytes and height (most texels of a short history).
  tbb::parallel_for(size_t(0), values.size(), [&](size_t k) {
    if (values[k] == bg) return;
    const int t = map.inside[k];
    set_painted_texel(out, t, values[k], painted);
    if (height) h[t] = (values[k][6] - 0.5) * height_scale;
  });
  const SeamPadding pad = build_seam_padding(map, padding);
  const std::pair<ImageRGBA8*, unsigned> images[] = {
      {&out.base_color, channel_bit(Channel::BaseColor) | channel_bit(Channel::Alpha)},
      {&out.roughness, channel_bit(Channel::Roughness)},
      {&out.metallic, channel_bit(Channel::Metallic)},
      {&out.height, channel_bit(Channel::Height)},
      {&out.metallic_roughness, channel_bit(Channel::Roughness) | channel_bit(Channel::Metallic)}};
  for (const auto& [img, bits] : images)
    if (painted & bits) apply_seam_padding(*img, pad);
  if (!height) return fill_image(out.normal, N, map.height, {to_byte(0.5), to_byte(0.5), to_byte(1.0), 255});
  normal_map_from_height(mesh, param, map, h, out.normal, terms);  // into the storage of \p out's normal map
  apply_seam_padding(out.normal, pad);
}

}  // namespace adaptex
