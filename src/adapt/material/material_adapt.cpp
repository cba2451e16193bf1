/// \file material_adapt.cpp
/// The material's error planes, one density-flow warp from their summed model, the textures again on
/// the new layout, and a measured never-worse check.
#include "adaptex/adapt/material_adapt.h"

#include <array>
#include <map>
#include <memory>
#include <mutex>

#include <tbb/parallel_for.h>

#include "adaptex/core/errors.h"
#include "adaptex/paint/material_eval.h"
#include "adaptex/paint/material_signal.h"

namespace adaptex {

namespace {

/// The planes' exact values at the texel maps asked for: the material evaluated once per map for all
/// planes, each plane's values converted into its own W*H storage.
class TexelPlanes {
 public:
  TexelPlanes(const TriMesh& mesh, const Parameterization& param, const MaterialStrokeFile& file, double height_scale)
      : mesh_(mesh), param_(param), file_(file), scale_(height_scale) {}
  const std::vector<Vec3f>& at(int plane, const TexelMap& map) {
    const std::lock_guard lock(mutex_);
    auto [it, fresh] = material_.try_emplace(&map);
    if (fresh) it->second = evaluate_material(mesh_, file_, texel_points(map));
    const std::vector<MaterialValue>& v = it->second;
    std::vector<Vec3f>& out = planes_[plane];
    if (plane == 2) {
      std::vector<double> h(static_cast<size_t>(map.width) * map.height, 0.0);
      tbb::parallel_for(size_t(0), v.size(), [&](size_t k) { h[map.inside[k]] = (v[k][6] - 0.5) * scale_; });
      out = height_normals(mesh_, param_, map, h);
      for (Vec3f& x : out) x = normal_plane_value(x);
      return out;
    }
    out.assign(static_cast<size_t>(map.width) * map.height, Vec3f::Zero());
    tbb::parallel_for(size_t(0), v.size(), [&](size_t k) { out[map.inside[k]] = material_plane_value(plane, v[k]); });
    return out;
  }

 private:
  const TriMesh& mesh_;
  const Parameterization& param_;
  const MaterialStrokeFile& file_;
  double scale_;
  std::mutex mutex_;
  std::map<const TexelMap*, std::vector<MaterialValue>> material_;
  std::vector<Vec3f> planes_[3];
};

ImageRGBA8 data_texture(const MaterialTextures& t) {
  ImageRGBA8 img(t.roughness.width, t.roughness.height);
  for (size_t k = 0; k < img.data.size() / 4; ++k) {
    img.data[4 * k] = t.roughness.data[4 * k];
    img.data[4 * k + 1] = t.metallic.data[4 * k];
    img.data[4 * k + 2] = t.base_color.data[4 * k + 3];
    img.data[4 * k + 3] = 255;
  }
  return img;
}

/// The weighted error of every channel (the height through its normal) of \p tex on \p param.
double sampled_error(const TriMesh& mesh, const Parameterization& param, const MaterialTextures& tex,
                     const MaterialStrokeFile& file, double data_weight, long long samples) {
  MaterialEvalOptions eo;
  eo.samples = samples;
  eo.seed = 17;
  eo.data_weight = data_weight;
  return evaluate_material_textures(mesh, param, tex, file, eo).weighted;
}

}  // namespace

std::vector<ErrorPlane> material_error_planes(const TriMesh& mesh, const Parameterization& param, const TexelMap& map,
                                              const MaterialStrokeFile& file, const MaterialTextures& textures,
                                              double data_weight) {
  auto exact = std::make_shared<TexelPlanes>(mesh, param, file, textures.height_scale);
  return material_error_planes(map, textures, [exact](int plane, const TexelMap& at) -> const std::vector<Vec3f>& {
    return exact->at(plane, at);
  }, data_weight);
}

std::vector<ErrorPlane> material_error_planes(const TexelMap& map, const MaterialTextures& textures,
                                              MaterialPlaneSource exact, double data_weight) {
  if (map.width != textures.base_color.width || map.height != textures.base_color.height)
    throw InvalidInputError("material_error_planes: the texel map and the textures differ in size");
  if (!exact) throw InvalidInputError("material_error_planes: no exact source");
  // Mean square of the base colour over the chart texels; each byte's term from a table (the same values).
  static const std::array<double, 256> square = [] {
    std::array<double, 256> q{};
    for (int b = 0; b < 256; ++b) q[b] = std::pow(b / 255.0, 2) / 3;
    return q;
  }();
  double albedo2 = 0;
  for (int t : map.inside)
    for (int c = 0; c < 3; ++c) albedo2 += square[textures.base_color.data[4 * t + c]];
  albedo2 = map.inside.empty() ? 1 : albedo2 / static_cast<double>(map.inside.size());
  std::vector<ErrorPlane> planes(3);
  planes[0].texture = textures.base_color;
  planes[1].weight = data_weight;
  planes[1].texture = data_texture(textures);
  // The normal map stores (n + 1) / 2: its squared error is |Δn|² / 4, so 4 · albedo² gives Lambert's.
  planes[2].weight = std::max(4 * albedo2, 1e-6);
  planes[2].texture = textures.normal;
  for (int k = 0; k < 3; ++k)
    planes[k].exact = [exact, k](const TexelMap& at) -> const std::vector<Vec3f>& { return exact(k, at); };
  return planes;
}

MaterialAdaptResult adapt_material(const TriMesh& mesh, const Parameterization& layout, const MaterialStrokeFile& file,
                                   const MaterialAdaptOptions& options) {
  const AdaptMode mode = options.adapt.mode;
  if (mode != AdaptMode::None && mode != AdaptMode::DensityFlow)
    throw InvalidInputError(std::string("adapt_material: layered materials adapt with density-flow or none (got ") +
                            to_string(mode) + ")");
  MaterialAdaptResult out;
  out.mesh = mesh;
  out.param = layout;
  out.textures = paint_material(mesh, layout, file, options.paint);
  out.report.mode = mode;
  if (mode == AdaptMode::None) return out;
  const int N = options.paint.size;
  const TexelMap map = build_texel_map(mesh, layout, N, N);
  const ErrorDensity model = compute_error_density(
      mesh, layout, map, material_error_planes(mesh, layout, map, file, out.textures, options.data_weight),
      options.adapt.density_flow.density);
  const AdaptResult res = adapt_parameterization(mesh, layout, out.textures.base_color, map, model, options.adapt);
  const TriMesh& adapted_mesh = res.refined_mesh ? *res.refined_mesh : mesh;
  MaterialTextures adapted = paint_material(adapted_mesh, res.param, file, options.paint);
  out.report = res.report;
  out.error_fixed = sampled_error(mesh, layout, out.textures, file, options.data_weight, options.check_samples);
  out.error_adapted = sampled_error(adapted_mesh, res.param, adapted, file, options.data_weight, options.check_samples);
  if (res.report.accepted && out.error_adapted < out.error_fixed) {
    out.mesh = adapted_mesh;
    if (res.refined_mesh) out.parent_face = res.parent_face;
    out.param = res.param;
    out.textures = std::move(adapted);
    out.adapted = true;
  }
  return out;
}

}  // namespace adaptex
