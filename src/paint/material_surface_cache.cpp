/// \file material_surface_cache.cpp
/// A layered material's surface cache (material_surface_cache.h): the per-layer point cache at the
/// samples of the surface caches' lattice, interpolated at texels.
#include "adaptex/paint/material_surface_cache.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdint>
#include <string>

#include "adaptex/core/errors.h"
#include "adaptex/paint/material_point_cache.h"
#include "surface_lattice.h"

namespace adaptex {

namespace {

void check_spacing(double spacing) {
  if (!(spacing > 0) || !std::isfinite(spacing))
    throw InvalidInputError("material surface cache: spacing must be positive and finite");
}

}  // namespace

/// The composite as 16-bit fixed point in [0, 1] (as SurfaceSignalCache's colours): the texels read
/// 14 bytes per sample instead of 56 (the lattice is several times the texture, and reading it is
/// bound by memory).
using Packed = std::array<std::uint16_t, kMaterialComponents>;
constexpr float kUnit = 65535.0f;

struct MaterialSurfaceCache::Impl {
  detail::SurfaceLattice lattice;
  MaterialPointCache samples;
  std::vector<Packed> packed;  // S: the composite of the last pack()

  /// Brings `packed` up to date with the composite of \p file (where it was recomputed).
  void pack(const MaterialStrokeFile& file) {
    auto store = [&](size_t k, const MaterialValue& v) {
      for (int q = 0; q < kMaterialComponents; ++q)
        packed[k][q] = static_cast<std::uint16_t>(std::clamp(v[q], 0.0, 1.0) * kUnit + 0.5);
    };
    if (packed.empty()) {
      packed.resize(static_cast<size_t>(lattice.num_samples()));
      const std::vector<MaterialValue>& at = samples.values(file);
      tbb::parallel_for(size_t(0), packed.size(), [&](size_t k) { store(k, at[k]); });
      return;
    }
    samples.values(file, store);  // the points recomputed since
  }

  Impl(const TriMesh& mesh, double spacing, const MaterialStrokeFile& file, long long max_samples)
      : lattice(mesh, spacing, max_samples, "material surface cache"), samples(mesh, lattice.sample_points(), file) {}
};

MaterialSurfaceCache::MaterialSurfaceCache(const TriMesh& mesh, double spacing, const MaterialStrokeFile& file,
                                           long long max_samples) {
  check_spacing(spacing);
  impl_ = std::make_unique<Impl>(mesh, spacing, file, max_samples);
}

MaterialSurfaceCache::~MaterialSurfaceCache() = default;
MaterialSurfaceCache::MaterialSurfaceCache(MaterialSurfaceCache&&) noexcept = default;
MaterialSurfaceCache& MaterialSurfaceCache::operator=(MaterialSurfaceCache&&) noexcept = default;

void MaterialSurfaceCache::update(const MaterialStrokeFile& file) { impl_->samples.update(file); }

std::vector<MaterialValue> MaterialSurfaceCache::texel_values(const MaterialStrokeFile& file, const TexelMap& map,
                                                              const TriMesh& map_mesh,
                                                              const std::vector<int>* parent_face) {
  std::vector<MaterialValue> out;
  texel_values(file, map, map_mesh, parent_face, out);
  return out;
}

void MaterialSurfaceCache::texel_values(const MaterialStrokeFile& file, const TexelMap& map, const TriMesh& map_mesh,
                                        const std::vector<int>* parent_face, std::vector<MaterialValue>& out) {
  Impl& m = *impl_;
  m.pack(file);
  out.resize(map.inside.size());
  m.lattice.for_each_texel(map, map_mesh, parent_face, "material surface cache",
                           [&](int k, const detail::LatticeStencil& st) {
                             const Packed &a = m.packed[st.sample[0]], &b = m.packed[st.sample[1]],
                                          &c = m.packed[st.sample[2]];
                             for (int q = 0; q < kMaterialComponents; ++q)
                               out[k][q] = (st.weight[0] * a[q] + st.weight[1] * b[q] + st.weight[2] * c[q]) / kUnit;
                           });
}

long long MaterialSurfaceCache::count_samples(const TriMesh& mesh, double spacing) {
  check_spacing(spacing);
  return detail::SurfaceLattice::count_samples(mesh, spacing);
}

long long MaterialSurfaceCache::num_samples() const { return impl_->lattice.num_samples(); }
long long MaterialSurfaceCache::strokes() const { return impl_->samples.strokes(); }

}  // namespace adaptex
