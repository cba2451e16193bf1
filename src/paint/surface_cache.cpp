/// \file surface_cache.cpp
/// Mesh-Colors-style surface cache of the painted signal (surface_cache.h): per-face barycentric
/// lattices (surface_lattice.h) holding 16-bit colours, linear interpolation.
#include "adaptex/paint/surface_cache.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "adaptex/core/errors.h"
#include "adaptex/paint/decal.h"
#include "surface_lattice.h"

namespace adaptex {

namespace {

/// Colours and coverage are stored as 16-bit fixed point in [0, 1] (1/65535 steps, far below the
/// 8-bit texture's): 8 bytes per sample.
constexpr float kUnit = 65535.0f;
inline std::uint16_t to_fixed(float v) {
  return static_cast<std::uint16_t>(std::clamp(v, 0.0f, 1.0f) * kUnit + 0.5f);  // round to nearest
}

/// brush_falloff() (strokes.h) in single precision: the cache stores 16 bits.
inline float falloff(float t, float hardness) {
  if (t <= hardness) return 1.0f;
  if (t >= 1.0f) return 0.0f;
  const float s = (t - hardness) / (1.0f - hardness);
  return 1.0f - s * s * (3.0f - 2.0f * s);
}

}  // namespace

struct SurfaceSignalCache::Impl {
  detail::SurfaceLattice lattice;
  std::vector<std::array<std::uint16_t, 3>> colour;  // S (samples face by face, lattice_index order)
  std::vector<std::uint16_t> alpha;   // S: coverage of the stroke being added (0 elsewhere)
  std::unique_ptr<DecalProjector> projector;
  int count = 0;

  Impl(const TriMesh& m, double spacing, long long max_samples) : lattice(m, spacing, max_samples, "surface cache") {}

  void brush(const Stroke& s) {
    const double r = s.radius;
    const float inv_r = static_cast<float>(1.0 / r), h = static_cast<float>(s.hardness), op = static_cast<float>(s.opacity);
    tbb::enumerable_thread_specific<std::vector<long long>> first_touch;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, s.dabs.size(), 4), [&](const tbb::blocked_range<size_t>& rg) {
      auto& mine = first_touch.local();
      for (size_t d = rg.begin(); d < rg.end(); ++d)
        lattice.for_each_face_near(s.dabs[d], r, [&](int f) {
          lattice.for_each_sample_in_ball(f, s.dabs[d], r, [&](long long k, double d2) {
            const std::uint16_t w = to_fixed(op * falloff(std::sqrt(static_cast<float>(d2)) * inv_r, h));
            std::atomic_ref<std::uint16_t> a(alpha[static_cast<size_t>(k)]);
            std::uint16_t cur = a.load(std::memory_order_relaxed);
            while (w > cur)
              if (a.compare_exchange_weak(cur, w, std::memory_order_relaxed)) {
                if (cur == 0) mine.push_back(k);
                break;
              }
          });
        });
    });
    const float col[3] = {float(s.color[0]), float(s.color[1]), float(s.color[2])};
    for (auto& list : first_touch)
      tbb::parallel_for(size_t(0), list.size(), [&](size_t q) {
        const size_t k = static_cast<size_t>(list[q]);
        const float w = alpha[k] / kUnit;
        for (int c = 0; c < 3; ++c) colour[k][c] = to_fixed(colour[k][c] / kUnit * (1.0f - w) + col[c] * w);
        alpha[k] = 0;
      });
  }

  void decal(const Stroke& s) {
    if (!projector) projector = std::make_unique<DecalProjector>(lattice.mesh());
    lattice.for_each_sample([&](int f, long long k, const Vec3& p) {
      const Eigen::Vector4d v = projector->evaluate(s, p, f);
      const float a = static_cast<float>(v[3]);
      if (!(a > 0)) return;
      auto& col = colour[static_cast<size_t>(k)];
      for (int c = 0; c < 3; ++c) col[c] = to_fixed(col[c] / kUnit * (1.0f - a) + static_cast<float>(v[c]) * a);
    });
  }

  Vec3f interpolate(const detail::LatticeStencil& st) const {
    auto at = [&](int q) {
      const auto& c = colour[static_cast<size_t>(st.sample[q])];
      return Vec3f(c[0], c[1], c[2]);
    };
    const Vec3f mixed = st.weight[0] * at(0) + st.weight[1] * at(1) + st.weight[2] * at(2);
    return mixed / kUnit;
  }
};

SurfaceSignalCache::SurfaceSignalCache(const TriMesh& mesh, double spacing, const Vec3& background,
                                       long long max_samples)
    : impl_(nullptr) {
  if (!(spacing > 0) || !std::isfinite(spacing))
    throw InvalidInputError("surface cache: spacing must be positive and finite");
  if (!background.allFinite() || background.minCoeff() < 0 || background.maxCoeff() > 1)
    throw InvalidInputError("surface cache: background colour must be in [0, 1]");
  impl_ = std::make_unique<Impl>(mesh, spacing, max_samples);
  const std::array<std::uint16_t, 3> bg{to_fixed(float(background[0])), to_fixed(float(background[1])),
                                        to_fixed(float(background[2]))};
  const size_t S = static_cast<size_t>(impl_->lattice.num_samples());
  impl_->colour.assign(S, bg);
  impl_->alpha.assign(S, 0);
}
SurfaceSignalCache::~SurfaceSignalCache() = default;
SurfaceSignalCache::SurfaceSignalCache(SurfaceSignalCache&&) noexcept = default;
SurfaceSignalCache& SurfaceSignalCache::operator=(SurfaceSignalCache&&) noexcept = default;

void SurfaceSignalCache::add_stroke(const Stroke& stroke) {
  validate_stroke(stroke, "surface cache");
  if (stroke.type == Stroke::Type::Decal)
    impl_->decal(stroke);
  else
    impl_->brush(stroke);
  ++impl_->count;
}

void SurfaceSignalCache::update(const StrokeFile& history) {
  for (size_t k = static_cast<size_t>(impl_->count); k < history.strokes.size(); ++k) add_stroke(history.strokes[k]);
}

Vec3f SurfaceSignalCache::colour(int face, double b0, double b1) const {
  return impl_->interpolate(impl_->lattice.stencil(face, b0, b1));
}

std::vector<Vec3f> SurfaceSignalCache::texel_colours(const TexelMap& map, const TriMesh& map_mesh,
                                                     const std::vector<int>* parent_face) const {
  std::vector<Vec3f> out(map.inside.size());
  impl_->lattice.for_each_texel(map, map_mesh, parent_face, "surface cache",
                                [&](int k, const detail::LatticeStencil& st) { out[k] = impl_->interpolate(st); });
  return out;
}

long long SurfaceSignalCache::count_samples(const TriMesh& mesh, double spacing) {
  if (!(spacing > 0) || !std::isfinite(spacing))
    throw InvalidInputError("surface cache: spacing must be positive and finite");
  return detail::SurfaceLattice::count_samples(mesh, spacing);
}

int SurfaceSignalCache::strokes() const { return impl_->count; }
long long SurfaceSignalCache::num_samples() const { return impl_->lattice.num_samples(); }

}  // namespace adaptex
