/// \file surface_cache.cpp
/// Mesh-Colors-style surface cache of the painted signal (surface_cache.h): per-face barycentric
/// lattices, brush dabs through the Painter's spatial index (texel_grid.h), linear interpolation.
#include "adaptex/paint/surface_cache.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>

#include "adaptex/core/errors.h"
#include "adaptex/paint/decal.h"
#include "texel_grid.h"

namespace adaptex {

namespace {

/// Index of lattice point (i, j), i + j <= n, within its face's block (rows of constant i).
inline long long lattice_index(int n, int i, int j) {
  return static_cast<long long>(i) * (n + 1) - static_cast<long long>(i) * (i - 1) / 2 + j;
}

inline long long lattice_size(int n) { return static_cast<long long>(n + 1) * (n + 2) / 2; }

/// Barycentrics (b0, b1) of \p p in triangle (a, b, c) (p is on or next to its plane).
Eigen::Vector2d barycentric(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e1 = b - a, e2 = c - a, d = p - a;
  const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2), dp1 = d.dot(e1), dp2 = d.dot(e2);
  const double den = d11 * d22 - d12 * d12;
  if (!(std::abs(den) > 0)) return {1.0 / 3, 1.0 / 3};
  const double u = (d22 * dp1 - d12 * dp2) / den, v = (d11 * dp2 - d12 * dp1) / den;  // weights of b, c
  return {1.0 - u - v, u};
}

}  // namespace

struct SurfaceSignalCache::Impl {
  const TriMesh& mesh;
  std::vector<int> n;                 // F: subdivisions per face
  std::vector<long long> offset;      // F+1: first sample of each face
  std::vector<std::array<float, 3>> colour;  // S (samples face by face, lattice_index order)
  std::vector<float> alpha;           // S: coverage of the stroke being added (0 elsewhere)
  std::unique_ptr<detail::TexelGrid> grid;
  std::unique_ptr<DecalProjector> projector;
  int count = 0;

  explicit Impl(const TriMesh& m) : mesh(m) {}

  void build(double spacing, long long max_samples) {
    const int F = mesh.num_faces();
    n.resize(F);
    offset.assign(F + 1, 0);
    for (int f = 0; f < F; ++f) {
      const Face& t = mesh.faces[f];
      const Vec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
      // Subdivisions by the longest edge. (By sqrt(2 area), half the samples on right triangles, the
      // end-mode test on the torus lost 0.4 dB: adapted layouts put texels closer than the initial's.)
      const double e = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
      n[f] = static_cast<int>(std::clamp(std::ceil(e / spacing), 1.0, 4096.0));
      offset[f + 1] = offset[f] + lattice_size(n[f]);
      if (offset[f + 1] > max_samples)
        throw InvalidInputError("surface cache: more than " + std::to_string(max_samples) +
                                " samples at spacing " + std::to_string(spacing));
    }
    std::vector<Vec3f> position(static_cast<size_t>(offset[F]));
    for_each_sample([&](int, long long s, const Vec3& p) { position[static_cast<size_t>(s)] = p.cast<float>(); });
    // The grid keeps its own sorted copy of the points; order()[slot] maps a slot back to the sample.
    grid = std::make_unique<detail::TexelGrid>(position, spacing);
  }

  /// Calls fn(face, sample index, 3-D point) for every sample, faces in parallel.
  template <class Fn>
  void for_each_sample(Fn&& fn) const {
    tbb::parallel_for(0, mesh.num_faces(), [&](int f) {
      const Face& t = mesh.faces[f];
      const Vec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
      const int m = n[f];
      for (int i = 0; i <= m; ++i)
        for (int j = 0; i + j <= m; ++j)
          fn(f, offset[f] + lattice_index(m, i, j), a + (b - a) * (double(i) / m) + (c - a) * (double(j) / m));
    });
  }

  void brush(const Stroke& s) {
    const float r = static_cast<float>(s.radius), inv_r = 1.0f / r;
    const float h = static_cast<float>(s.hardness), op = static_cast<float>(s.opacity);
    tbb::enumerable_thread_specific<std::vector<int>> first_touch;
    const std::vector<int>& order = grid->order();
    tbb::parallel_for(tbb::blocked_range<size_t>(0, s.dabs.size(), 4), [&](const tbb::blocked_range<size_t>& rg) {
      auto& mine = first_touch.local();
      for (size_t d = rg.begin(); d < rg.end(); ++d)
        grid->for_each_in_ball(s.dabs[d], s.radius, [&](int slot, float d2) {
          const float w = op * static_cast<float>(brush_falloff(std::sqrt(d2) * inv_r, h));
          const int k = order[slot];
          std::atomic_ref<float> a(alpha[k]);
          float cur = a.load(std::memory_order_relaxed);
          while (w > cur)
            if (a.compare_exchange_weak(cur, w, std::memory_order_relaxed)) {
              if (cur == 0.0f) mine.push_back(k);
              break;
            }
        });
    });
    const float col[3] = {float(s.color[0]), float(s.color[1]), float(s.color[2])};
    for (auto& list : first_touch)
      tbb::parallel_for(size_t(0), list.size(), [&](size_t q) {
        const int k = list[q];
        const float w = alpha[k];
        for (int c = 0; c < 3; ++c) colour[k][c] = colour[k][c] * (1.0f - w) + col[c] * w;
        alpha[k] = 0.0f;
      });
  }

  void decal(const Stroke& s) {
    if (!projector) projector = std::make_unique<DecalProjector>(mesh);
    for_each_sample([&](int f, long long k, const Vec3& p) {
      const Eigen::Vector4d v = projector->evaluate(s, p, f);
      const float a = static_cast<float>(v[3]);
      if (!(a > 0)) return;
      auto& col = colour[static_cast<size_t>(k)];
      for (int c = 0; c < 3; ++c) col[c] = col[c] * (1.0f - a) + static_cast<float>(v[c]) * a;
    });
  }

  Vec3f interpolate(int f, double b0, double b1) const {
    const int m = n[f];
    const long long base = offset[f];
    double u = std::max(0.0, b1) * m, v = std::max(0.0, 1.0 - b0 - b1) * m;  // lattice coords of corners 1, 2
    if (u + v > m) {
      const double k = m / (u + v);
      u *= k;
      v *= k;
    }
    const int i0 = std::min(static_cast<int>(u), m - 1);
    const int j0 = std::min(static_cast<int>(v), m - 1 - i0);
    const float fu = static_cast<float>(u - i0), fv = static_cast<float>(v - j0);
    auto at = [&](int i, int j) {
      const auto& c = colour[static_cast<size_t>(base + lattice_index(m, i, j))];
      return Vec3f(c[0], c[1], c[2]);
    };
    if (fu + fv <= 1.0f || i0 + j0 + 2 > m)
      return (1.0f - fu - fv) * at(i0, j0) + fu * at(i0 + 1, j0) + fv * at(i0, j0 + 1);
    return (fu + fv - 1.0f) * at(i0 + 1, j0 + 1) + (1.0f - fv) * at(i0 + 1, j0) + (1.0f - fu) * at(i0, j0 + 1);
  }
};

SurfaceSignalCache::SurfaceSignalCache(const TriMesh& mesh, double spacing, const Vec3& background,
                                       long long max_samples)
    : impl_(std::make_unique<Impl>(mesh)) {
  if (!(spacing > 0) || !std::isfinite(spacing))
    throw InvalidInputError("surface cache: spacing must be positive and finite");
  if (!background.allFinite() || background.minCoeff() < 0 || background.maxCoeff() > 1)
    throw InvalidInputError("surface cache: background colour must be in [0, 1]");
  impl_->build(spacing, max_samples);
  const std::array<float, 3> bg{float(background[0]), float(background[1]), float(background[2])};
  const size_t S = static_cast<size_t>(impl_->offset.back());
  impl_->colour.assign(S, bg);
  impl_->alpha.assign(S, 0.0f);
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

Vec3f SurfaceSignalCache::colour(int face, double b0, double b1) const { return impl_->interpolate(face, b0, b1); }

std::vector<Vec3f> SurfaceSignalCache::texel_colours(const TexelMap& map, const TriMesh& map_mesh,
                                                     const std::vector<int>* parent_face) const {
  const Impl& m = *impl_;
  const int F = m.mesh.num_faces();
  const int MF = map_mesh.num_faces();
  if (parent_face && static_cast<int>(parent_face->size()) != MF)
    throw InvalidInputError("surface cache: parent_face has " + std::to_string(parent_face->size()) +
                            " entries, the mesh " + std::to_string(MF) + " faces");
  if (!parent_face && MF != F)
    throw InvalidInputError("surface cache: the map's mesh has " + std::to_string(MF) + " faces, the cache's " +
                            std::to_string(F));
  std::vector<Vec3f> out(map.inside.size());
  tbb::parallel_for(size_t(0), map.inside.size(), [&](size_t k) {
    const int t = map.inside[k];
    const int f = map.face[t];
    if (f < 0 || f >= MF) throw InvalidInputError("surface cache: texel map face out of range");
    if (!parent_face) {
      out[k] = m.interpolate(f, map.bary[t].x(), map.bary[t].y());
      return;
    }
    const int p = (*parent_face)[f];
    if (p < 0 || p >= F) throw InvalidInputError("surface cache: parent face out of range");
    const Face& tri = m.mesh.faces[p];
    const Eigen::Vector2d b = barycentric(map.position[t].cast<double>(), m.mesh.positions[tri[0]],
                                          m.mesh.positions[tri[1]], m.mesh.positions[tri[2]]);
    out[k] = m.interpolate(p, b.x(), b.y());
  });
  return out;
}

int SurfaceSignalCache::strokes() const { return impl_->count; }
long long SurfaceSignalCache::num_samples() const { return impl_->offset.back(); }

}  // namespace adaptex
