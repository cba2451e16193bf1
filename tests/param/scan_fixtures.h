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

}  // namespace adaptex::test
