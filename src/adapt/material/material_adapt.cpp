/// \file material_adapt.cpp
/// The material's error planes, one density-flow warp from their summed model, the textures again on
/// the new layout, and a measured never-worse check.
#include "adaptex/adapt/material_adapt.h"

#include <map>
#include <memory>
#include <mutex>

#include <tbb/parallel_for.h>

#include "adaptex/core/errors.h"
#include "adaptex/paint/material_eval.h"
#include "adaptex/paint/material_signal.h"

namespace adaptex {

namespace {

/// The exact material at the chart texels of a texel map, evaluated once per map for all planes.
class TexelMaterial {
 public:
  TexelMaterial(const TriMesh& mesh, const MaterialStrokeFile& file) : mesh_(mesh), file_(file) {}
  const std::vector<MaterialValue>& at(const TexelMap& map) {
    const std::lock_guard lock(mutex_);
    auto [it, fresh] = cache_.try_emplace(&map);
    if (fresh) it->second = evaluate_material(mesh_, file_, texel_points(map));
    return it->second;
  }

 private:
  const TriMesh& mesh_;
  const MaterialStrokeFile& file_;
  std::mutex mutex_;
  std::map<const TexelMap*, std::vector<MaterialValue>> cache_;
};

/// W*H values of \p map: f(value) at the chart texels (\p v in map.inside order), \p zero elsewhere.
template <class T, class F>
std::vector<T> on_texels(const TexelMap& map, const std::vector<MaterialValue>& v, const T& zero, F f) {
  if (v.size() != map.inside.size()) throw Error("material_error_planes: the source gave another number of texels");
  std::vector<T> out(static_cast<size_t>(map.width) * map.height, zero);
  tbb::parallel_for(size_t(0), v.size(), [&](size_t k) { out[map.inside[k]] = f(v[k]); });
  return out;
}

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
  auto exact = std::make_shared<TexelMaterial>(mesh, file);
  return material_error_planes(mesh, param, map, textures, [exact](const TexelMap& at) -> const std::vector<MaterialValue>& {
    return exact->at(at);
  }, data_weight);
}

std::vector<ErrorPlane> material_error_planes(const TriMesh& mesh, const Parameterization& param, const TexelMap& map,
                                              const MaterialTextures& textures, MaterialTexelSource exact,
                                              double data_weight, MaterialNormalSource normals) {
  if (map.width != textures.base_color.width || map.height != textures.base_color.height)
    throw InvalidInputError("material_error_planes: the texel map and the textures differ in size");
  if (!exact) throw InvalidInputError("material_error_planes: no exact source");
  double albedo2 = 0;  // mean square of the base colour over the chart texels
  for (int t : map.inside)
    for (int c = 0; c < 3; ++c) albedo2 += std::pow(textures.base_color.data[4 * t + c] / 255.0, 2) / 3;
  albedo2 = map.inside.empty() ? 1 : albedo2 / static_cast<double>(map.inside.size());
  const double scale = textures.height_scale;
  std::vector<ErrorPlane> planes(3);
  planes[0].texture = textures.base_color;
  planes[0].exact = [exact](const TexelMap& at) {
    return on_texels<Vec3f>(at, exact(at), Vec3f::Zero(), [](const MaterialValue& v) { return Vec3f(float(v[0]), float(v[1]), float(v[2])); });
  };
  planes[1].weight = data_weight;
  planes[1].texture = data_texture(textures);
  planes[1].exact = [exact](const TexelMap& at) {
    return on_texels<Vec3f>(at, exact(at), Vec3f::Zero(), [](const MaterialValue& v) { return Vec3f(float(v[4]), float(v[5]), float(v[3])); });
  };
  // The normal map stores (n + 1) / 2: its squared error is |Δn|² / 4, so 4 · albedo² gives Lambert's.
  planes[2].weight = std::max(4 * albedo2, 1e-6);
  planes[2].texture = textures.normal;
  planes[2].exact = [exact, normals, &mesh, &param, scale](const TexelMap& at) {
    std::vector<Vec3f> n;
    if (normals) {
      n = normals(at);
    } else {
      const std::vector<double> h =
          on_texels<double>(at, exact(at), 0.0, [scale](const MaterialValue& v) { return (v[6] - 0.5) * scale; });
      n = height_normals(mesh, param, at, h);
    }
    for (Vec3f& x : n) x = 0.5f * (x + Vec3f::Ones());
    return n;
  };
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
