/// \file material_point_cache.cpp
/// Per-layer state of a layered material at fixed points, updated stroke by stroke (material_point_cache.h).
#include "adaptex/paint/material_point_cache.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>
#include <memory>
#include <string>

#include "adaptex/core/errors.h"
#include "adaptex/paint/decal.h"
#include "material_layer_ops.h"
#include "texel_grid.h"

namespace adaptex {

using namespace material_detail;

namespace {

/// One layer's state at the points, in single precision: L (7 per point), a (5), M (1, with a mask).
/// v.assign(n, x), growing the storage by a quarter more than asked: the next points (a session's
/// next candidate layout) are about as many, and fresh pages cost a page fault each.
template <class V>
void assign_with_slack(V& v, size_t n, const typename V::value_type& x) {
  if (v.capacity() < n) {
    V fresh;
    fresh.reserve(n + n / 4);
    v.swap(fresh);
  }
  v.assign(n, x);
}

struct LayerCache {
  std::vector<float> value, cover, mask;
  size_t strokes = 0, mask_strokes = 0;
};

}  // namespace

struct MaterialPointCache::Impl {
  const TriMesh* mesh;
  std::vector<SurfacePoint> points;
  std::vector<Vec3> pos;
  std::vector<LayerCache> layers;
  std::unique_ptr<DecalProjector> decals;
  long long count = 0;
  double spacing = 1;                        // typical distance between neighbouring points
  std::unique_ptr<detail::TexelGrid> grid;   // the points' spatial index, built for the first brush
  std::vector<Vec3> slot_pos;                // P: pos in the grid's slot order (the ball queries' exact test)
  std::vector<double> alpha;                 // P, by slot: a brush's coverage, 0 outside the stroke being added
  // The composite of the last values() call, recomputed where a stroke reached since (dirty), or
  // everywhere when the layers' blending settings changed (look).
  std::vector<MaterialValue> composite;
  std::vector<char> dirty;
  // P: some paint stroke reached the point since reset(); the others' covers are 0 in every layer, so
  // their composite is the background (every layer's blend skips a zero cover).
  std::vector<char> painted;
  bool any_dirty = true, all_dirty = true;
  std::vector<double> look;

  /// What values() reads from the file besides the caches: background, and per layer visibility,
  /// opacity, blend mode and the mask's start value.
  static std::vector<double> look_of(const MaterialStrokeFile& file) {
    std::vector<double> v(file.background.begin(), file.background.end());
    for (const MaterialLayer& l : file.layers)
      v.insert(v.end(), {double(l.visible), l.opacity, double(static_cast<int>(l.blend)), l.mask ? l.mask->value : -1.0});
    return v;
  }

  /// Points \p p on \p m, nothing painted; the storage of earlier points is kept for reuse.
  void reset(const TriMesh& m, std::vector<SurfacePoint> p) {
    mesh = &m;
    points = std::move(p);
    for (size_t k = 0; k < points.size(); ++k)
      if (points[k].face < 0 || points[k].face >= m.num_faces())
        throw InvalidInputError("material point cache: point " + std::to_string(k) + " has face " +
                                std::to_string(points[k].face) + " outside [0, " + std::to_string(m.num_faces()) + ")");
    assign_with_slack(pos, points.size(), Vec3::Zero().eval());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 1 << 14), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t k = r.begin(); k < r.end(); ++k) {
        const SurfacePoint& sp = points[k];
        const auto& f = m.faces[sp.face];
        pos[k] = sp.b0 * m.positions[f[0]] + sp.b1 * m.positions[f[1]] + (1 - sp.b0 - sp.b1) * m.positions[f[2]];
      }
    });
    assign_with_slack(dirty, points.size(), char(0));
    assign_with_slack(painted, points.size(), char(0));
    double area = 0;
    for (int f = 0; f < m.num_faces(); ++f) area += face_area(m, f);
    spacing = points.empty() || !(area > 0) ? 1.0 : std::sqrt(area / static_cast<double>(points.size()));
    for (LayerCache& lc : layers) lc.strokes = lc.mask_strokes = 0, lc.value.clear(), lc.cover.clear(), lc.mask.clear();
    grid.reset();
    decals.reset();
    count = 0;
    any_dirty = all_dirty = true;
  }

  /// Calls fn(k, alpha) for every point k a fill, brush or erase stroke reaches (alpha > 0), in
  /// parallel, once per point: a brush's dabs visit the points within their radius through the
  /// points' spatial index, and a point's coverage is the maximum over the dabs (as DabGrid's).
  template <class Fn>
  void for_covered(const MaterialStroke& s, Fn&& fn) {
    if (s.type == MaterialStroke::Type::Fill) {
      if (s.opacity > 0) tbb::parallel_for(size_t(0), pos.size(), [&](size_t k) { fn(k, s.opacity); });
      return;
    }
    if (!grid) {
      std::vector<Vec3f> p(pos.size());
      tbb::parallel_for(size_t(0), p.size(), [&](size_t k) { p[k] = pos[k].cast<float>(); });
      grid = std::make_unique<detail::TexelGrid>(p, spacing);
      assign_with_slack(alpha, pos.size(), 0.0);
      assign_with_slack(slot_pos, pos.size(), Vec3::Zero().eval());
      tbb::parallel_for(size_t(0), pos.size(), [&](size_t g) { slot_pos[g] = pos[grid->order()[g]]; });
    }
    tbb::enumerable_thread_specific<std::vector<int>> touched;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, s.dabs.size(), 4), [&](const tbb::blocked_range<size_t>& rg) {
      auto& mine = touched.local();
      for (size_t i = rg.begin(); i < rg.end(); ++i) {
        double r, o;
        dab_shape(s, i, r, o);
        if (!(r > 0) || !(o > 0)) continue;
        // The index tests distances in single precision: a slightly wider ball, then the exact test.
        // Points are read and marked by slot: those of one cell lie side by side.
        grid->for_each_in_ball(s.dabs[i], r * (1 + 1e-5), [&](int slot, float) {
          const double t = (slot_pos[static_cast<size_t>(slot)] - s.dabs[i]).norm() / r;
          if (!(t < 1)) return;
          const double w = o * brush_falloff(t, s.hardness);
          std::atomic_ref<double> a(alpha[static_cast<size_t>(slot)]);
          double cur = a.load(std::memory_order_relaxed);
          while (w > cur)
            if (a.compare_exchange_weak(cur, w, std::memory_order_relaxed)) {
              if (cur == 0) mine.push_back(slot);
              break;
            }
        });
      }
    });
    for (auto& list : touched)
      tbb::parallel_for(size_t(0), list.size(), [&](size_t q) {
        const size_t slot = static_cast<size_t>(list[q]);
        fn(static_cast<size_t>(grid->order()[slot]), alpha[slot]);
        alpha[slot] = 0;
      });
  }

  void paint(LayerCache& lc, const MaterialStroke& s) {
    const size_t P = pos.size();
    if (lc.value.empty()) {
      assign_with_slack(lc.value, P * kMaterialComponents, 0.0f);
      assign_with_slack(lc.cover, P * kNumChannels, 0.0f);
    }
    auto apply = [&](size_t k, double a_k, const double* rgb) {
      MaterialValue L;
      std::array<double, kNumChannels> a;
      float* lv = &lc.value[k * kMaterialComponents];
      float* av = &lc.cover[k * kNumChannels];
      for (int c = 0; c < kMaterialComponents; ++c) L[c] = lv[c];
      for (int c = 0; c < kNumChannels; ++c) a[c] = av[c];
      apply_stroke(s, a_k, rgb, L, a);
      for (int c = 0; c < kMaterialComponents; ++c) lv[c] = static_cast<float>(L[c]);
      for (int c = 0; c < kNumChannels; ++c) av[c] = static_cast<float>(a[c]);
      dirty[k] = 1;
      painted[k] = 1;
    };
    if (s.type == MaterialStroke::Type::Decal) {
      if (!decals) decals = std::make_unique<DecalProjector>(*mesh);
      tbb::parallel_for(size_t(0), P, [&](size_t k) {
        const Eigen::Vector4d d = decals->evaluate(s.decal, pos[k], points[k].face);
        const double rgb[3] = {d[0], d[1], d[2]};
        if (d[3] > 0) apply(k, d[3], rgb);
      });
    } else {
      for_covered(s, [&](size_t k, double a_k) { apply(k, a_k, nullptr); });
    }
    any_dirty = true;
  }

  void paint_mask(LayerCache& lc, const LayerMask& mask, const MaterialStroke& s) {
    const double v = mask_stroke_value(mask, s);
    for_covered(s, [&](size_t k, double a_k) {
      lc.mask[k] = static_cast<float>(lc.mask[k] * (1 - a_k) + v * a_k);
      dirty[k] = 1;
    });
    any_dirty = true;
  }
};

MaterialPointCache::MaterialPointCache(const TriMesh& mesh, std::vector<SurfacePoint> points,
                                       const MaterialStrokeFile& file)
    : impl_(std::make_unique<Impl>()) {
  reset(mesh, std::move(points), file);
}

void MaterialPointCache::reset(const TriMesh& mesh, std::vector<SurfacePoint> points, const MaterialStrokeFile& file) {
  impl_->reset(mesh, std::move(points));
  if (impl_->layers.size() > file.layers.size()) impl_->layers.resize(file.layers.size());
  update(file);
}

MaterialPointCache::~MaterialPointCache() = default;
MaterialPointCache::MaterialPointCache(MaterialPointCache&&) noexcept = default;
MaterialPointCache& MaterialPointCache::operator=(MaterialPointCache&&) noexcept = default;

void MaterialPointCache::update(const MaterialStrokeFile& file) {
  Impl& m = *impl_;
  if (file.layers.size() < m.layers.size())
    throw InvalidInputError("material point cache: the file has fewer layers than the cache");
  m.layers.resize(file.layers.size());
  for (size_t l = 0; l < file.layers.size(); ++l) {
    const MaterialLayer& layer = file.layers[l];
    LayerCache& lc = m.layers[l];
    const size_t mask_strokes = layer.mask ? layer.mask->strokes.size() : 0;
    if (layer.strokes.size() < lc.strokes || mask_strokes < lc.mask_strokes)
      throw InvalidInputError("material point cache: layer " + std::to_string(l) + " lost strokes");
    for (; lc.strokes < layer.strokes.size(); ++lc.strokes, ++m.count) m.paint(lc, layer.strokes[lc.strokes]);
    if (!layer.mask) continue;
    if (lc.mask.empty()) {
      lc.mask.assign(m.pos.size(), static_cast<float>(layer.mask->value));
      m.all_dirty = true;
    }
    for (; lc.mask_strokes < mask_strokes; ++lc.mask_strokes, ++m.count)
      m.paint_mask(lc, *layer.mask, layer.mask->strokes[lc.mask_strokes]);
  }
}

const std::vector<MaterialValue>& MaterialPointCache::values(const MaterialStrokeFile& file) {
  return values(file, nullptr);
}

const std::vector<MaterialValue>& MaterialPointCache::values(const MaterialStrokeFile& file,
                                                             const std::function<void(size_t, const MaterialValue&)>& changed) {
  Impl& m = *impl_;
  std::vector<double> look = Impl::look_of(file);
  if (look != m.look || m.layers.size() > file.layers.size()) m.all_dirty = true;
  if (!m.all_dirty && !m.any_dirty) return m.composite;
  m.look = std::move(look);
  if (m.composite.size() != m.pos.size()) assign_with_slack(m.composite, m.pos.size(), file.background);
  const size_t layers = std::min(file.layers.size(), m.layers.size());
  const bool all = m.all_dirty;
  tbb::parallel_for(size_t(0), m.pos.size(), [&](size_t k) {
    if (!all && !m.dirty[k]) return;
    m.dirty[k] = 0;
    MaterialValue& R = m.composite[k];
    R = file.background;
    for (size_t l = 0; l < layers && m.painted[k]; ++l) {
      const LayerCache& lc = m.layers[l];
      const MaterialLayer& layer = file.layers[l];
      if (!layer.visible || lc.value.empty()) continue;
      MaterialValue L;
      std::array<double, kNumChannels> a;
      for (int c = 0; c < kMaterialComponents; ++c) L[c] = lc.value[k * kMaterialComponents + c];
      for (int c = 0; c < kNumChannels; ++c) a[c] = lc.cover[k * kNumChannels + c];
      const double mask = layer.mask ? (lc.mask.empty() ? layer.mask->value : double(lc.mask[k])) : 1.0;
      blend_layer(layer, L, a, mask, R);
    }
    if (changed) changed(k, R);
  });
  m.all_dirty = m.any_dirty = false;
  return m.composite;
}

const std::vector<SurfacePoint>& MaterialPointCache::points() const { return impl_->points; }
long long MaterialPointCache::strokes() const { return impl_->count; }

}  // namespace adaptex
