#pragma once
/// \file surface_lattice.h
/// Internal: the per-face barycentric sample lattice of the surface caches (surface_cache.h for one
/// colour, material_surface_cache.h for a layered material): face f of longest edge e carries
/// n_f = ceil(e / spacing) subdivisions, (n_f+1)(n_f+2)/2 samples at barycentrics
/// (1 - i/n - j/n, i/n, j/n), 0 <= i + j <= n, stored face by face; an index of the face centroids
/// (faces binned by size) finds the faces a ball may reach; a query interpolates linearly in the
/// lattice triangle around the point (Yuksel, Keyser, House: "Mesh Colors", TAMU 2010).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "adaptex/core/errors.h"
#include "adaptex/core/mesh.h"
#include "adaptex/paint/signal.h"
#include "adaptex/paint/texel_map.h"
#include "texel_grid.h"

namespace adaptex::detail {

/// Index of lattice point (i, j), i + j <= n, within its face's block (rows of constant i).
inline long long lattice_index(int n, int i, int j) {
  return static_cast<long long>(i) * (n + 1) - static_cast<long long>(i) * (i - 1) / 2 + j;
}

/// Barycentrics (b0, b1) of \p p in triangle (a, b, c) (p is on or next to its plane).
Eigen::Vector2d barycentric_in(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

/// The three samples around a point and their linear weights (summing to 1).
struct LatticeStencil {
  std::array<long long, 3> sample;
  std::array<float, 3> weight;
};

class SurfaceLattice {
 public:
  /// \param mesh kept by reference (must outlive the lattice) \pre spacing > 0 and finite
  /// \throw InvalidInputError more than \p max_samples samples (\p what names the cache in the message)
  SurfaceLattice(const TriMesh& mesh, double spacing, long long max_samples, const char* what);
  ~SurfaceLattice();
  SurfaceLattice(SurfaceLattice&&) noexcept;

  /// The samples a lattice of \p mesh at \p spacing would have (O(faces)). \pre spacing > 0
  static long long count_samples(const TriMesh& mesh, double spacing);

  const TriMesh& mesh() const { return mesh_; }
  long long num_samples() const { return offset_.back(); }
  /// Bytes of the lattice's own arrays and index (not the values a cache keeps per sample).
  long long memory_bytes() const;
  /// The samples as surface points of the mesh, shape [num_samples()] (lattice order).
  std::vector<SurfacePoint> sample_points() const;

  /// The interpolation stencil at barycentrics (b0, b1) of face \p f. \pre 0 <= f < F
  LatticeStencil stencil(int f, double b0, double b1) const;

  /// Calls fn(face, sample index, 3-D point) for every sample, faces in parallel.
  template <class Fn>
  void for_each_sample(Fn&& fn) const {
    tbb::parallel_for(0, mesh_.num_faces(), [&](int f) {
      const Face& t = mesh_.faces[f];
      const Vec3 &a = mesh_.positions[t[0]], &b = mesh_.positions[t[1]], &c = mesh_.positions[t[2]];
      const int m = n_[f];
      for (int i = 0; i <= m; ++i)
        for (int j = 0; i + j <= m; ++j)
          fn(f, offset_[f] + lattice_index(m, i, j), a + (b - a) * (double(i) / m) + (c - a) * (double(j) / m));
    });
  }

  /// Calls fn(sample index, squared distance) for the samples of face \p f within \p r of \p p:
  /// only the lattice rows and columns the ball's shadow on the face's plane can reach.
  template <class Fn>
  void for_each_sample_in_ball(int f, const Vec3& p, double r, Fn&& fn) const {
    const Face& t = mesh_.faces[f];
    const Vec3& a = mesh_.positions[t[0]];
    const int m = n_[f];
    const Vec3 e1 = (mesh_.positions[t[1]] - a) / m, e2 = (mesh_.positions[t[2]] - a) / m;  // lattice steps
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
        if (d2 < r2) fn(offset_[f] + lattice_index(m, i, j), d2);
      }
    }
  }

  /// Calls fn(face) for every face that may have samples within \p r of \p p.
  template <class Fn>
  void for_each_face_near(const Vec3& p, double r, Fn&& fn) const {
    for (const FaceClass& fc : classes_) {
      if (!fc.grid) continue;
      // The index compares in single precision: a wider ball, then the exact test in double.
      fc.grid->for_each_in_ball(p, r + fc.radius + slack_, [&](int slot, float) {
        const int f = fc.faces[slot];
        if ((centroid_[f] - p).norm() < r + face_radius_[f]) fn(f);
      });
    }
  }

  /// Calls fn(k, stencil) for every chart texel k of \p map (index into map.inside), in parallel,
  /// grouped by lattice face so that each face's samples are read in one place (the lattice is many
  /// times the texture: in raster order the reads miss the caches). \p parent_face: if not null,
  /// \p map_mesh is a refinement of the lattice's mesh and parent_face[c] the lattice face that face
  /// c lies on (the texel's 3-D point is located in that face); else map_mesh has the lattice's faces.
  /// \throw InvalidInputError a map face out of range of map_mesh or parent_face (\p what prefixes it)
  template <class Fn>
  void for_each_texel(const TexelMap& map, const TriMesh& map_mesh, const std::vector<int>* parent_face,
                      const char* what, Fn&& fn) const {
    const TexelOrder order = texels_by_face(map, map_mesh, parent_face, what);
    const std::vector<int>&first = order.first, &by_face = order.by_face;
    tbb::parallel_for(tbb::blocked_range<int>(0, mesh_.num_faces(), 256), [&](const tbb::blocked_range<int>& r) {
      for (int p = r.begin(); p < r.end(); ++p) {
        const Face& tri = mesh_.faces[p];
        for (int q = first[p]; q < first[p + 1]; ++q) {
          const int k = by_face[q];
          const int t = map.inside[k];
          if (!parent_face) {
            fn(k, stencil(p, map.bary[t].x(), map.bary[t].y()));
            continue;
          }
          const Eigen::Vector2d b = barycentric_in(map.position[t].cast<double>(), mesh_.positions[tri[0]],
                                                   mesh_.positions[tri[1]], mesh_.positions[tri[2]]);
          fn(k, stencil(p, b.x(), b.y()));
        }
      }
    });
  }

 private:
  /// Faces whose bounding radius (largest distance from the centroid to a corner) is at most
  /// `radius`, indexed by their centroids: a ball query of radius r + `radius` finds every face of
  /// the class that may reach into a ball of radius r. Faces are binned by powers of two of their
  /// radius so that a few large faces do not widen the queries of all the others.
  struct FaceClass {
    double radius = 0;
    std::vector<int> faces;  // slot order of the grid's input points
    std::unique_ptr<TexelGrid> grid;
  };

  /// The chart texels grouped by lattice face (a counting sort): face p's are by_face[first[p] ..
  /// first[p+1]).
  struct TexelOrder {
    std::vector<int> first, by_face;
  };
  TexelOrder texels_by_face(const TexelMap& map, const TriMesh& map_mesh, const std::vector<int>* parent_face,
                                  const char* what) const;

  const TriMesh& mesh_;
  std::vector<int> n_;               // F: subdivisions per face
  std::vector<long long> offset_;    // F+1: first sample of each face
  std::vector<Vec3> centroid_;       // F
  std::vector<double> face_radius_;  // F: bounding radius around the centroid
  double slack_ = 0;  // widens the index's queries by its single-precision rounding (TexelGrid stores floats)
  std::vector<FaceClass> classes_;
};

}  // namespace adaptex::detail
