/// \file material_signal.cpp
/// Layered material at surface points (docs/strokes.md, "Version 2"): per layer, each stroke's
/// coverage is found through a hash grid of its dabs, then the layer is blended over the result.
#include "adaptex/paint/material_signal.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <unordered_map>

#include "adaptex/core/errors.h"
#include "adaptex/paint/decal.h"
#include "material_layer_ops.h"

namespace adaptex {

namespace material_detail {

void apply_stroke(const MaterialStroke& s, double alpha, const double* rgb, MaterialValue& L,
                  std::array<double, kNumChannels>& a) {
  if (!(alpha > 0)) return;
  for (int c = 0; c < kNumChannels; ++c) {
    const auto ch = static_cast<Channel>(c);
    if (!(s.channels & channel_bit(ch))) continue;
    if (s.type == MaterialStroke::Type::Erase) {
      a[c] *= 1 - alpha;
      continue;
    }
    const double cover = a[c] * (1 - alpha) + alpha;
    const int o = channel_offset(ch);
    for (int k = 0; k < channel_components(ch); ++k) {
      const double v = rgb && s.image_color && ch == Channel::BaseColor ? rgb[k] : s.value[o + k];
      L[o + k] = cover > 0 ? (L[o + k] * a[c] * (1 - alpha) + v * alpha) / cover : 0;
    }
    a[c] = cover;
  }
}

void blend_layer(const MaterialLayer& layer, const MaterialValue& L, const std::array<double, kNumChannels>& a,
                 double mask, MaterialValue& R) {
  for (int c = 0; c < kNumChannels; ++c) {
    const auto ch = static_cast<Channel>(c);
    const double k = a[c] * mask * layer.opacity;
    if (!(k > 0)) continue;
    const int o = channel_offset(ch);
    for (int j = 0; j < channel_components(ch); ++j)
      R[o + j] = R[o + j] * (1 - k) + blend_component(layer.blend, R[o + j], L[o + j]) * k;
  }
}

double fill_or_dab_coverage(const MaterialStroke& s, const DabGrid* grid, const Vec3& p) {
  return s.type == MaterialStroke::Type::Fill ? s.opacity : grid->coverage(p);
}

double mask_stroke_value(const LayerMask& mask, const MaterialStroke& s) {
  return s.type == MaterialStroke::Type::Erase ? mask.value : s.mask_value;
}

}  // namespace material_detail

using namespace material_detail;

namespace {

/// State of one layer at the points: value L (7 per point), coverage a (5 per point), mask M.
using LayerState = MaterialLayerSamples;

void paint_mask(const LayerMask& mask, const std::vector<Vec3>& pos, std::vector<double>& M) {
  M.assign(pos.size(), mask.value);
  for (const MaterialStroke& s : mask.strokes) {
    std::unique_ptr<DabGrid> grid = s.type == MaterialStroke::Type::Fill ? nullptr : std::make_unique<DabGrid>(s);
    tbb::parallel_for(size_t(0), pos.size(), [&](size_t k) {
      const double alpha = fill_or_dab_coverage(s, grid.get(), pos[k]);
      M[k] = M[k] * (1 - alpha) + mask_stroke_value(mask, s) * alpha;
    });
  }
}

void paint_layer(const MaterialLayer& layer, const std::vector<Vec3>& pos, const std::vector<SurfacePoint>& points,
                 const DecalProjector* decals, LayerState& st) {
  st.value.assign(pos.size(), MaterialValue{});
  st.cover.assign(pos.size(), std::array<double, kNumChannels>{});
  for (const MaterialStroke& s : layer.strokes) {
    if (s.type == MaterialStroke::Type::Decal) {
      tbb::parallel_for(size_t(0), pos.size(), [&](size_t k) {
        const Eigen::Vector4d d = decals->evaluate(s.decal, pos[k], points[k].face);
        const double rgb[3] = {d[0], d[1], d[2]};
        apply_stroke(s, d[3], rgb, st.value[k], st.cover[k]);
      });
      continue;
    }
    std::unique_ptr<DabGrid> grid = s.type == MaterialStroke::Type::Fill ? nullptr : std::make_unique<DabGrid>(s);
    tbb::parallel_for(size_t(0), pos.size(), [&](size_t k) {
      apply_stroke(s, fill_or_dab_coverage(s, grid.get(), pos[k]), nullptr, st.value[k], st.cover[k]);
    });
  }
  if (layer.mask)
    paint_mask(*layer.mask, pos, st.mask);
  else
    st.mask.assign(pos.size(), 1.0);
}

bool has_decal(const MaterialStrokeFile& file) {
  for (const MaterialLayer& l : file.layers)
    for (const MaterialStroke& s : l.strokes)
      if (s.type == MaterialStroke::Type::Decal) return true;
  return false;
}

}  // namespace

double material_stroke_coverage(const MaterialStroke& s, const Vec3& p) {
  double alpha = 0;
  for (size_t i = 0; i < s.dabs.size(); ++i) {
    double r, o;
    dab_shape(s, i, r, o);
    if (!(r > 0)) continue;
    alpha = std::max(alpha, o * brush_falloff((p - s.dabs[i]).norm() / r, s.hardness));
  }
  return alpha;
}

namespace {

/// The 3-D positions of \p points. \throw InvalidInputError a face out of range
std::vector<Vec3> point_positions(const TriMesh& mesh, const std::vector<SurfacePoint>& points) {
  std::vector<Vec3> pos(points.size());
  for (size_t k = 0; k < points.size(); ++k) {
    const SurfacePoint& sp = points[k];
    if (sp.face < 0 || sp.face >= mesh.num_faces())
      throw InvalidInputError("evaluate_material: point " + std::to_string(k) + " has face " + std::to_string(sp.face) +
                              " outside [0, " + std::to_string(mesh.num_faces()) + ")");
    const auto& f = mesh.faces[sp.face];
    pos[k] = sp.b0 * mesh.positions[f[0]] + sp.b1 * mesh.positions[f[1]] + (1 - sp.b0 - sp.b1) * mesh.positions[f[2]];
  }
  return pos;
}

}  // namespace

MaterialLayerSamples evaluate_layer(const TriMesh& mesh, const MaterialStrokeFile& file, int layer,
                                    const std::vector<SurfacePoint>& points) {
  if (layer < 0 || layer >= static_cast<int>(file.layers.size()))
    throw InvalidInputError("evaluate_layer: layer " + std::to_string(layer) + " of " +
                            std::to_string(file.layers.size()));
  const std::vector<Vec3> pos = point_positions(mesh, points);
  const std::unique_ptr<DecalProjector> decals = has_decal(file) ? std::make_unique<DecalProjector>(mesh) : nullptr;
  MaterialLayerSamples st;
  paint_layer(file.layers[layer], pos, points, decals.get(), st);
  return st;
}

std::vector<MaterialValue> evaluate_material(const TriMesh& mesh, const MaterialStrokeFile& file,
                                             const std::vector<SurfacePoint>& points) {
  const std::vector<Vec3> pos = point_positions(mesh, points);
  const std::unique_ptr<DecalProjector> decals = has_decal(file) ? std::make_unique<DecalProjector>(mesh) : nullptr;
  std::vector<MaterialValue> R(points.size(), file.background);
  LayerState st;
  for (const MaterialLayer& layer : file.layers) {
    if (!layer.visible) continue;
    paint_layer(layer, pos, points, decals.get(), st);
    tbb::parallel_for(size_t(0), pos.size(), [&](size_t k) { blend_layer(layer, st.value[k], st.cover[k], st.mask[k], R[k]); });
  }
  return R;
}

MaterialValue evaluate_material_reference(const MaterialStrokeFile& file, const Vec3& p) {
  MaterialValue R = file.background;
  for (const MaterialLayer& layer : file.layers) {
    if (!layer.visible) continue;
    double M = layer.mask ? layer.mask->value : 1.0;
    if (layer.mask)
      for (const MaterialStroke& s : layer.mask->strokes) {
        const double alpha = s.type == MaterialStroke::Type::Fill ? s.opacity : material_stroke_coverage(s, p);
        M = M * (1 - alpha) + mask_stroke_value(*layer.mask, s) * alpha;
      }
    // The layer as premultiplied values P = L a, composited over nothing.
    MaterialValue P{};
    std::array<double, kNumChannels> a{};
    for (const MaterialStroke& s : layer.strokes) {
      if (s.type == MaterialStroke::Type::Decal) throw InvalidInputError("evaluate_material_reference: decals are not supported");
      const double alpha = s.type == MaterialStroke::Type::Fill ? s.opacity : material_stroke_coverage(s, p);
      for (int c = 0; c < kNumChannels; ++c) {
        const auto ch = static_cast<Channel>(c);
        if (!(s.channels & channel_bit(ch))) continue;
        const bool erase = s.type == MaterialStroke::Type::Erase;
        for (int j = 0; j < channel_components(ch); ++j) {
          const int o = channel_offset(ch) + j;
          P[o] = P[o] * (1 - alpha) + (erase ? 0 : s.value[o] * alpha);
        }
        a[c] = erase ? a[c] * (1 - alpha) : a[c] * (1 - alpha) + alpha;
      }
    }
    for (int c = 0; c < kNumChannels; ++c) {
      const auto ch = static_cast<Channel>(c);
      const double k = a[c] * M * layer.opacity;
      for (int j = 0; j < channel_components(ch); ++j) {
        const int o = channel_offset(ch) + j;
        const double L = a[c] > 0 ? P[o] / a[c] : 0;
        R[o] = R[o] * (1 - k) + blend_component(layer.blend, R[o], L) * k;
      }
    }
  }
  return R;
}

}  // namespace adaptex
