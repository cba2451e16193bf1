/// \file surface_lattice.cpp
/// The surface caches' per-face sample lattice (surface_lattice.h): building it and its face index,
/// the interpolation stencil, the chart texels grouped by face.
#include "surface_lattice.h"

#include <string>

namespace adaptex::detail {

namespace {

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

}  // namespace

Eigen::Vector2d barycentric_in(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e1 = b - a, e2 = c - a, d = p - a;
  const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2), dp1 = d.dot(e1), dp2 = d.dot(e2);
  const double den = d11 * d22 - d12 * d12;
  if (!(std::abs(den) > 0)) return {1.0 / 3, 1.0 / 3};
  const double u = (d22 * dp1 - d12 * dp2) / den, v = (d11 * dp2 - d12 * dp1) / den;  // weights of b, c
  return {1.0 - u - v, u};
}

SurfaceLattice::SurfaceLattice(const TriMesh& mesh, double spacing, long long max_samples, const char* what)
    : mesh_(mesh) {
  const int F = mesh.num_faces();
  n_.resize(F);
  offset_.assign(F + 1, 0);
  centroid_.resize(F);
  face_radius_.resize(F);
  double smallest = std::numeric_limits<double>::infinity();
  for (int f = 0; f < F; ++f) {
    const Face& t = mesh.faces[f];
    const Vec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
    n_[f] = subdivisions(mesh, f, spacing);
    offset_[f + 1] = offset_[f] + lattice_size(n_[f]);
    if (offset_[f + 1] > max_samples)
      throw InvalidInputError(std::string(what) + ": more than " + std::to_string(max_samples) +
                              " samples at spacing " + std::to_string(spacing));
    const Vec3 m = (a + b + c) / 3.0;
    centroid_[f] = m;
    face_radius_[f] = std::max({(a - m).norm(), (b - m).norm(), (c - m).norm()});
    if (face_radius_[f] > 0) smallest = std::min(smallest, face_radius_[f]);
    slack_ = std::max(slack_, 1e-6 * m.cwiseAbs().maxCoeff());
  }
  if (!std::isfinite(smallest)) smallest = 1;
  // Classes: radius in (smallest·2^(k-1), smallest·2^k].
  std::vector<int> cls(F);
  int top = 0;
  for (int f = 0; f < F; ++f) {
    cls[f] = face_radius_[f] > smallest ? static_cast<int>(std::ceil(std::log2(face_radius_[f] / smallest))) : 0;
    cls[f] = std::clamp(cls[f], 0, 60);
    top = std::max(top, cls[f]);
  }
  classes_.resize(top + 1);
  for (int f = 0; f < F; ++f) classes_[cls[f]].faces.push_back(f);
  for (int k = 0; k <= top; ++k) {
    FaceClass& fc = classes_[k];
    fc.radius = smallest * std::ldexp(1.0, k) * (1 + 1e-6);
    if (fc.faces.empty()) continue;
    std::vector<Vec3f> points(fc.faces.size());
    for (size_t q = 0; q < fc.faces.size(); ++q) points[q] = centroid_[fc.faces[q]].cast<float>();
    fc.grid = std::make_unique<TexelGrid>(points, fc.radius);
    std::vector<int> sorted(fc.faces.size());
    for (size_t s = 0; s < sorted.size(); ++s) sorted[s] = fc.faces[fc.grid->order()[s]];
    fc.faces = std::move(sorted);
  }
}

SurfaceLattice::~SurfaceLattice() = default;
SurfaceLattice::SurfaceLattice(SurfaceLattice&&) noexcept = default;

long long SurfaceLattice::count_samples(const TriMesh& mesh, double spacing) {
  long long total = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) total += lattice_size(subdivisions(mesh, f, spacing));
  return total;
}

long long SurfaceLattice::memory_bytes() const {
  long long b = static_cast<long long>(n_.capacity() * sizeof(int) + offset_.capacity() * sizeof(long long) +
                                       centroid_.capacity() * sizeof(Vec3) + face_radius_.capacity() * sizeof(double));
  for (const FaceClass& fc : classes_)  // faces, and the grid's sorted points, order and cell table (about)
    b += static_cast<long long>(fc.faces.capacity()) * (sizeof(int) * 3 + sizeof(TexelGrid::P3));
  return b;
}

std::vector<SurfacePoint> SurfaceLattice::sample_points() const {
  std::vector<SurfacePoint> out(static_cast<size_t>(num_samples()));
  tbb::parallel_for(0, mesh_.num_faces(), [&](int f) {
    const int m = n_[f];
    for (int i = 0; i <= m; ++i)
      for (int j = 0; i + j <= m; ++j) {
        // As for_each_sample(): the point a + (b - a) i/m + (c - a) j/m.
        SurfacePoint& p = out[static_cast<size_t>(offset_[f] + lattice_index(m, i, j))];
        p.face = f;
        p.b1 = double(i) / m;
        p.b0 = 1.0 - p.b1 - double(j) / m;
      }
  });
  return out;
}

LatticeStencil SurfaceLattice::stencil(int f, double b0, double b1) const {
  const int m = n_[f];
  const long long base = offset_[f];
  double u = std::max(0.0, b1) * m, v = std::max(0.0, 1.0 - b0 - b1) * m;  // lattice coords of corners 1, 2
  if (u + v > m) {
    const double k = m / (u + v);
    u *= k;
    v *= k;
  }
  const int i0 = std::min(static_cast<int>(u), m - 1);
  const int j0 = std::min(static_cast<int>(v), m - 1 - i0);
  const float fu = static_cast<float>(u - i0), fv = static_cast<float>(v - j0);
  auto at = [&](int i, int j) { return base + lattice_index(m, i, j); };
  if (fu + fv <= 1.0f || i0 + j0 + 2 > m)
    return {{at(i0, j0), at(i0 + 1, j0), at(i0, j0 + 1)}, {1.0f - fu - fv, fu, fv}};
  return {{at(i0 + 1, j0 + 1), at(i0 + 1, j0), at(i0, j0 + 1)}, {fu + fv - 1.0f, 1.0f - fv, 1.0f - fu}};
}

SurfaceLattice::TexelOrder SurfaceLattice::texels_by_face(const TexelMap& map, const TriMesh& map_mesh,
                                                          const std::vector<int>* parent_face, const char* what) const {
  const int F = mesh_.num_faces();
  const int MF = map_mesh.num_faces();
  const std::string w = what;
  if (parent_face && static_cast<int>(parent_face->size()) != MF)
    throw InvalidInputError(w + ": parent_face has " + std::to_string(parent_face->size()) + " entries, the mesh " +
                            std::to_string(MF) + " faces");
  if (!parent_face && MF != F)
    throw InvalidInputError(w + ": the map's mesh has " + std::to_string(MF) + " faces, the cache's " +
                            std::to_string(F));
  const size_t T = map.inside.size();
  std::vector<int> cache_face(T);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, T, 1 << 14), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t k = r.begin(); k < r.end(); ++k) {
      const int f = map.face[map.inside[k]];
      if (f < 0 || f >= MF) throw InvalidInputError(w + ": texel map face out of range");
      const int p = parent_face ? (*parent_face)[f] : f;
      if (p < 0 || p >= F) throw InvalidInputError(w + ": parent face out of range");
      cache_face[k] = p;
    }
  });
  TexelOrder o;
  o.first.assign(static_cast<size_t>(F) + 1, 0);
  for (size_t k = 0; k < T; ++k) ++o.first[static_cast<size_t>(cache_face[k]) + 1];
  for (int f = 0; f < F; ++f) o.first[f + 1] += o.first[f];
  o.by_face.resize(T);
  std::vector<int> next(o.first.begin(), o.first.end() - 1);
  for (size_t k = 0; k < T; ++k) o.by_face[static_cast<size_t>(next[cache_face[k]]++)] = static_cast<int>(k);
  return o;
}

}  // namespace adaptex::detail
