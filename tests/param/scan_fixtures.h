#pragma once
/// \file scan_fixtures.h
/// A scan-like mesh built in code for the scan segmentation tests and benchmarks: many components
/// (noisy height-field patches with single-face holes, tiny strips, fans and slivers), handles
/// (a genus-g surface, a torus, a trefoil knot) and a sphere with many holes. Deterministic.
#include <algorithm>
#include <cmath>
#include <vector>

#include "adaptex/core/mesh.h"
#include "adaptex/core/shapes.h"

namespace adaptex::test {

/// About \p faces faces (>= 20000) in 100 + components: synthetic_scan(faces / 2, 40) (no
/// zero-area faces), genus_surface(\p genus), a torus, a trefoil knot, sphere_with_holes(40) and
/// tiny_components(60), each moved apart. Genus \p genus + 2, hundreds of boundary loops.
inline TriMesh scan_like_mesh(int faces = 60000, int genus = 6) {
  const int scale = std::max(2, static_cast<int>(std::sqrt(faces / 60000.0) * 4));
  std::vector<TriMesh> parts;
  parts.push_back(shapes::synthetic_scan(std::max(faces / 2, 4000), 40, 0));
  parts.push_back(shapes::genus_surface(genus, scale));
  parts.push_back(shapes::torus(8 * scale + 16, 4 * scale + 8));
  parts.push_back(shapes::trefoil_knot(40 * scale + 80, 12));
  parts.push_back(shapes::sphere_with_holes(40, 4));
  parts.push_back(shapes::tiny_components(60));
  for (size_t i = 1; i < parts.size(); ++i)
    for (Vec3& p : parts[i].positions) p += Vec3(-6.0 * static_cast<double>(i), 0, 0);
  return shapes::disjoint_union(parts);
}

/// A coarse, crumpled fragment as photogrammetry leaves them: an \p nx × \p ny grid of
/// 2 nx ny faces over \p size × \p size whose interior vertices are moved by a deterministic
/// pseudo-random height in [−\p amplitude, \p amplitude] (spikes and folds: no chart of the
/// whole fragment is close to isometric). Boundary vertices stay flat. Offset by \p origin.
inline TriMesh crumpled_patch(int nx, int ny, double size, double amplitude, Vec3 origin,
                              unsigned seed) {
  TriMesh m;
  unsigned state = seed * 2654435761u + 12345u;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      state = state * 1664525u + 1013904223u;
      const double r = static_cast<double>(state >> 8) / static_cast<double>(1u << 24);
      const bool border = i == 0 || j == 0 || i == nx || j == ny;
      const double z = border ? 0.0 : amplitude * (2.0 * r - 1.0);
      m.positions.push_back(origin + Vec3(size * i / nx, size * j / ny, z));
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = j * (nx + 1) + i, b = a + 1, c = a + nx + 1, d = c + 1;
      m.faces.push_back({a, b, d});
      m.faces.push_back({a, d, c});
    }
  return m;
}

/// A flat \p n × \p n grid of \p size × \p size at \p origin (2 n² faces): the smooth bulk of a scan.
inline TriMesh flat_patch(int n, double size, Vec3 origin) {
  return crumpled_patch(n, n, size, 0.0, origin, 0);
}

}  // namespace adaptex::test
