/// \file surface_cache.cpp
/// Mesh-Colors-style surface cache of the painted signal (surface_cache.h): per-face barycentric
/// lattices found by a spatial index of the faces (texel_grid.h over their centroids), linear interpolation.
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
#include "texel_grid.h"

namespace adaptex {

namespace {

/// Index of lattice point (i, j), i + j <= n, within its face's block (rows of constant i).
inline long long lattice_index(int n, int i, int j) {
  return static_cast<long long>(i) * (n + 1) - static_cast<long long>(i) * (i - 1) / 2 + j;
}

inline long long lattice_size(int n) { return static_cast<long long>(n + 1) * (n + 2) / 2; }

/// Subdivisions of face \p f: by its longest edge. (By sqrt(2 area), half the samples on right
/// triangles, the end-mode test on the torus lost 0.4 dB: adapted layouts put texels closer than the
/// initial layout's.)
int subdivisions(const TriMesh& mesh, int f, double spacing) {
  const Face& t = mesh.faces[f];
  const Vec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
  const double e = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  return static_cast<int>(std::clamp(std::ceil(e / spacing), 1.0, 4096.0));
}

/// Barycentrics (b0, b1) of \p p in triangle (a, b, c) (p is on or next to its plane).
Eigen::Vector2d barycentric(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e1 = b - a, e2 = c - a, d = p - a;
  const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2), dp1 = d.dot(e1), dp2 = d.dot(e2);
  const double den = d11 * d22 - d12 * d12;
  if (!(std::abs(den) > 0)) return {1.0 / 3, 1.0 / 3};
  const double u = (d22 * dp1 - d12 * dp2) / den, v = (d11 * dp2 - d12 * dp1) / den;  // weights of b, c
  return {1.0 - u - v, u};
}

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

/// The faces whose bounding radius (largest distance from the centroid to a corner) is at most
/// `radius`, indexed by their centroids: a ball query of radius r + `radius` finds every face of
/// the class that may reach into a ball of radius r. Faces are binned by powers of two of their
/// radius so that a few large faces do not widen the queries of all the others.
struct FaceClass {
  double radius = 0;
  std::vector<int> faces;                     // slot order of the grid's input points
  std::unique_ptr<detail::TexelGrid> grid;
};

}  // namespace

struct SurfaceSignalCache::Impl {
  const TriMesh& mesh;
  std::vector<int> n;                 // F: subdivisions per face
  std::vector<long long> offset;      // F+1: first sample of each face
  std::vector<std::array<std::uint16_t, 3>> colour;  // S (samples face by face, lattice_index order)
  std::vector<std::uint16_t> alpha;   // S: coverage of the stroke being added (0 elsewhere)
  std::vector<Vec3> centroid;         // F
  std::vector<double> face_radius;    // F: bounding radius around the centroid
  double slack = 0;  // widens the index's queries by its single-precision rounding (TexelGrid stores floats)
  std::vector<FaceClass> classes;
  std::unique_ptr<DecalProjector> projector;
  int count = 0;

  explicit Impl(const TriMesh& m) : mesh(m) {}

  void build(double spacing, long long max_samples) {
    const int F = mesh.num_faces();
    n.resize(F);
    offset.assign(F + 1, 0);
    centroid.resize(F);
    face_radius.resize(F);
    double smallest = std::numeric_limits<double>::infinity();
    for (int f = 0; f < F; ++f) {
      const Face& t = mesh.faces[f];
      const Vec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
      n[f] = subdivisions(mesh, f, spacing);
      offset[f + 1] = offset[f] + lattice_size(n[f]);
      if (offset[f + 1] > max_samples)
        throw InvalidInputError("surface cache: more than " + std::to_string(max_samples) +
                                " samples at spacing " + std::to_string(spacing));
      const Vec3 m = (a + b + c) / 3.0;
      centroid[f] = m;
      face_radius[f] = std::max({(a - m).norm(), (b - m).norm(), (c - m).norm()});
      if (face_radius[f] > 0) smallest = std::min(smallest, face_radius[f]);
      slack = std::max(slack, 1e-6 * m.cwiseAbs().maxCoeff());
    }
    if (!std::isfinite(smallest)) smallest = 1;
    // Classes: radius in (smallest·2^(k-1), smallest·2^k].
    std::vector<int> cls(F);
    int top = 0;
    for (int f = 0; f < F; ++f) {
      cls[f] = face_radius[f] > smallest ? static_cast<int>(std::ceil(std::log2(face_radius[f] / smallest))) : 0;
      cls[f] = std::clamp(cls[f], 0, 60);
      top = std::max(top, cls[f]);
    }
    classes.resize(top + 1);
    for (int f = 0; f < F; ++f) classes[cls[f]].faces.push_back(f);
    for (int k = 0; k <= top; ++k) {
      FaceClass& fc = classes[k];
      fc.radius = smallest * std::ldexp(1.0, k) * (1 + 1e-6);
      if (fc.faces.empty()) continue;
      std::vector<Vec3f> points(fc.faces.size());
      for (size_t q = 0; q < fc.faces.size(); ++q) points[q] = centroid[fc.faces[q]].cast<float>();
      fc.grid = std::make_unique<detail::TexelGrid>(points, fc.radius);
      std::vector<int> sorted(fc.faces.size());
      for (size_t s = 0; s < sorted.size(); ++s) sorted[s] = fc.faces[fc.grid->order()[s]];
      fc.faces = std::move(sorted);
    }
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

  /// Calls fn(sample index, squared distance) for the samples of face \p f within \p r of \p p:
  /// only the lattice rows and columns the ball's shadow on the face's plane can reach.
  template <class Fn>
  void for_each_sample_in_ball(int f, const Vec3& p, double r, Fn&& fn) const {
    const Face& t = mesh.faces[f];
    const Vec3& a = mesh.positions[t[0]];
    const int m = n[f];
    const Vec3 e1 = (mesh.positions[t[1]] - a) / m, e2 = (mesh.positions[t[2]] - a) / m;  // lattice steps
    const double g11 = e1.dot(e1), g12 = e1.dot(e2), g22 = e2.dot(e2), det = g11 * g22 - g12 * g12;
    int i_lo = 0, i_hi = m;
    double v = 0, rv = std::numeric_limits<double>::infinity();
    if (det > 1e-12 * g11 * g22) {
      // Lattice coordinates (u, v) of p's projection; a ball of radius r covers |Δu| <= r·sqrt((G⁻¹)₁₁).
      const Vec3 d = p - a;
      const double d1 = d.dot(e1), d2 = d.dot(e2);
      const double u = (g22 * d1 - g12 * d2) / det;
      v = (g11 * d2 - g12 * d1) / det;
      const double ru = r * std::sqrt(g22 / det);
      rv = r * std::sqrt(g11 / det);
      if (u + ru < 0 || u - ru > m || v + rv < 0 || v - rv > m) return;
      i_lo = static_cast<int>(std::max(0.0, std::ceil(u - ru)));
      i_hi = static_cast<int>(std::min<double>(m, std::floor(u + ru)));
    }
    const double r2 = r * r;
    for (int i = i_lo; i <= i_hi; ++i) {
      int j_lo = 0, j_hi = m - i;
      if (std::isfinite(rv)) {
        j_lo = static_cast<int>(std::max(0.0, std::ceil(v - rv)));
        j_hi = static_cast<int>(std::min<double>(m - i, std::floor(v + rv)));
      }
      const Vec3 row = a + e1 * double(i) - p;
      for (int j = j_lo; j <= j_hi; ++j) {
        const double d2 = (row + e2 * double(j)).squaredNorm();
        if (d2 < r2) fn(offset[f] + lattice_index(m, i, j), d2);
      }
    }
  }

  /// Calls fn(face) for every face that may have samples within \p r of \p p.
  template <class Fn>
  void for_each_face_near(const Vec3& p, double r, Fn&& fn) const {
    for (const FaceClass& fc : classes) {
      if (!fc.grid) continue;
      // The index compares in single precision: a wider ball, then the exact test in double.
      fc.grid->for_each_in_ball(p, r + fc.radius + slack, [&](int slot, float) {
        const int f = fc.faces[slot];
        if ((centroid[f] - p).norm() < r + face_radius[f]) fn(f);
      });
    }
  }

  void brush(const Stroke& s) {
    const double r = s.radius;
    const float inv_r = static_cast<float>(1.0 / r), h = static_cast<float>(s.hardness), op = static_cast<float>(s.opacity);
    tbb::enumerable_thread_specific<std::vector<long long>> first_touch;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, s.dabs.size(), 4), [&](const tbb::blocked_range<size_t>& rg) {
      auto& mine = first_touch.local();
      for (size_t d = rg.begin(); d < rg.end(); ++d)
        for_each_face_near(s.dabs[d], r, [&](int f) {
          for_each_sample_in_ball(f, s.dabs[d], r, [&](long long k, double d2) {
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
    if (!projector) projector = std::make_unique<DecalProjector>(mesh);
    for_each_sample([&](int f, long long k, const Vec3& p) {
      const Eigen::Vector4d v = projector->evaluate(s, p, f);
      const float a = static_cast<float>(v[3]);
      if (!(a > 0)) return;
      auto& col = colour[static_cast<size_t>(k)];
      for (int c = 0; c < 3; ++c) col[c] = to_fixed(col[c] / kUnit * (1.0f - a) + static_cast<float>(v[c]) * a);
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
    const Vec3f mixed = fu + fv <= 1.0f || i0 + j0 + 2 > m
                            ? Vec3f((1.0f - fu - fv) * at(i0, j0) + fu * at(i0 + 1, j0) + fv * at(i0, j0 + 1))
                            : Vec3f((fu + fv - 1.0f) * at(i0 + 1, j0 + 1) + (1.0f - fv) * at(i0 + 1, j0) +
                                    (1.0f - fu) * at(i0, j0 + 1));
    return mixed / kUnit;
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
  const std::array<std::uint16_t, 3> bg{to_fixed(float(background[0])), to_fixed(float(background[1])),
                                        to_fixed(float(background[2]))};
  const size_t S = static_cast<size_t>(impl_->offset.back());
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
  // The cache face of every chart texel; then the texels grouped by that face (a counting sort), so
  // that each face's lattice is read once, in one place, instead of once per raster row that crosses
  // it (the lattice is ~25x the texture: in raster order the reads missed the caches).
  const size_t T = map.inside.size();
  std::vector<int> cache_face(T);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, T, 1 << 14), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t k = r.begin(); k < r.end(); ++k) {
      const int f = map.face[map.inside[k]];
      if (f < 0 || f >= MF) throw InvalidInputError("surface cache: texel map face out of range");
      const int p = parent_face ? (*parent_face)[f] : f;
      if (p < 0 || p >= F) throw InvalidInputError("surface cache: parent face out of range");
      cache_face[k] = p;
    }
  });
  std::vector<int> first(static_cast<size_t>(F) + 1, 0);
  for (size_t k = 0; k < T; ++k) ++first[static_cast<size_t>(cache_face[k]) + 1];
  for (int f = 0; f < F; ++f) first[f + 1] += first[f];
  std::vector<int> by_face(T);
  {
    std::vector<int> next(first.begin(), first.end() - 1);
    for (size_t k = 0; k < T; ++k) by_face[static_cast<size_t>(next[cache_face[k]]++)] = static_cast<int>(k);
  }
  std::vector<Vec3f> out(T);
  tbb::parallel_for(tbb::blocked_range<int>(0, F, 256), [&](const tbb::blocked_range<int>& r) {
    for (int p = r.begin(); p < r.end(); ++p) {
      const Face& tri = m.mesh.faces[p];
      for (int q = first[p]; q < first[p + 1]; ++q) {
        const int k = by_face[q];
        const int t = map.inside[k];
        if (!parent_face) {
          out[k] = m.interpolate(p, map.bary[t].x(), map.bary[t].y());
          continue;
        }
        const Eigen::Vector2d b = barycentric(map.position[t].cast<double>(), m.mesh.positions[tri[0]],
                                              m.mesh.positions[tri[1]], m.mesh.positions[tri[2]]);
        out[k] = m.interpolate(p, b.x(), b.y());
      }
    }
  });
  return out;
}

long long SurfaceSignalCache::count_samples(const TriMesh& mesh, double spacing) {
  if (!(spacing > 0) || !std::isfinite(spacing))
    throw InvalidInputError("surface cache: spacing must be positive and finite");
  long long total = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) total += lattice_size(subdivisions(mesh, f, spacing));
  return total;
}

int SurfaceSignalCache::strokes() const { return impl_->count; }
long long SurfaceSignalCache::num_samples() const { return impl_->offset.back(); }

}  // namespace adaptex
