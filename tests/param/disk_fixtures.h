#pragma once
/// \file disk_fixtures.h
/// Disk meshes built in code for the parameterization tests (param-solver tests).
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/core/shapes.h"

namespace adaptex::test {

/// The faces of \p m whose centroid satisfies \p keep, with unused vertices removed.
inline TriMesh submesh(const TriMesh& m, const std::function<bool(const Vec3&)>& keep) {
  TriMesh out;
  std::vector<int> remap(m.positions.size(), -1);
  for (const Face& f : m.faces) {
    const Vec3 c = (m.positions[f[0]] + m.positions[f[1]] + m.positions[f[2]]) / 3.0;
    if (!keep(c)) continue;
    Face g;
    for (int k = 0; k < 3; ++k) {
      if (remap[f[k]] < 0) {
        remap[f[k]] = static_cast<int>(out.positions.size());
        out.positions.push_back(m.positions[f[k]]);
      }
      g[k] = remap[f[k]];
    }
    out.faces.push_back(g);
  }
  return out;
}

/// The same mesh with every face wound the other way (a "CW" mesh).
inline TriMesh reversed(TriMesh m) {
  for (Face& f : m.faces) std::swap(f[1], f[2]);
  return m;
}

/// Lower half of a UV sphere (a curved disk, one clean boundary loop on the equator).
inline TriMesh hemisphere(int slices = 32) {
  return submesh(shapes::sphere(slices, slices / 2), [](const Vec3& c) { return c.z() < 0; });
}

/// Lower part of an icosphere: a curved disk with a jagged boundary full of "ear" triangles.
inline TriMesh jagged_cap(int subdivisions = 3) {
  return submesh(shapes::icosphere(subdivisions), [](const Vec3& c) { return c.z() < 0.05; });
}

/// The unit plane with a Gaussian bump (a curved, non-developable disk).
inline TriMesh bump(int n = 24, double height = 0.5) {
  TriMesh m = shapes::plane(n);
  for (Vec3& p : m.positions)
    p.z() = height * std::exp(-((p.x() - 0.5) * (p.x() - 0.5) + (p.y() - 0.5) * (p.y() - 0.5)) / 0.05);
  return m;
}

/// A 1 x n strip of quads: every vertex is on the boundary (chords everywhere).
inline TriMesh strip(int n) {
  TriMesh m;
  for (int i = 0; i <= n; ++i) {
    m.positions.push_back(Vec3(i, 0, 0));
    m.positions.push_back(Vec3(i, 1, 0.2 * i));
  }
  for (int i = 0; i < n; ++i) {
    const int a = 2 * i, b = 2 * i + 2, c = 2 * i + 3, d = 2 * i + 1;
    m.faces.push_back({a, b, c});
    m.faces.push_back({a, c, d});
  }
  return m;
}

/// A hexagonal fan with an "ear" triangle glued on each rim edge: 6 ears, no valid square corners.
inline TriMesh six_ears() {
  TriMesh m;
  m.positions.push_back(Vec3(0, 0, 0));
  for (int i = 0; i < 6; ++i) {
    const double a = i * M_PI / 3;
    m.positions.push_back(Vec3(std::cos(a), std::sin(a), 0));
  }
  for (int i = 0; i < 6; ++i) {
    const double a = (i + 0.5) * M_PI / 3;
    m.positions.push_back(Vec3(1.5 * std::cos(a), 1.5 * std::sin(a), 0.3));
  }
  for (int i = 0; i < 6; ++i) {
    const int r0 = 1 + i, r1 = 1 + (i + 1) % 6;
    m.faces.push_back({0, r0, r1});
    m.faces.push_back({r0, 7 + i, r1});
  }
  return m;
}

/// A single-chart Parameterization from per-vertex uv.
inline Parameterization as_param(const TriMesh& m, const std::vector<Vec2>& uv) {
  Parameterization p;
  p.uv = uv;
  p.uv_faces = m.faces;
  p.wedge_vertex.resize(uv.size());
  for (size_t i = 0; i < uv.size(); ++i) p.wedge_vertex[i] = static_cast<int>(i);
  p.face_chart.assign(m.faces.size(), 0);
  p.num_charts = 1;
  return p;
}

struct NamedDisk {
  std::string name;
  TriMesh mesh;
  bool curved;  ///< Yoshizawa must strictly lower L2.
};

/// The disks every parameterization test runs over (libigl style: one body, many meshes).
inline std::vector<NamedDisk> test_disks() {
  return {
      {"plane", shapes::plane(12), false},
      {"hemisphere", hemisphere(32), true},
      {"hemisphere_cw", reversed(hemisphere(24)), true},
      {"jagged_cap", jagged_cap(3), false},
      {"bump", bump(24), true},
      {"bump_cw", reversed(bump(16)), true},
      {"strip", strip(10), false},
      {"six_ears", six_ears(), false},
  };
}

}  // namespace adaptex::test
