#pragma once
/// \file height_field.h
/// The curved height field the adapt benchmarks share: an n x n quad grid of the unit square (2 n²
/// faces) lifted by z = 0.25 sin(3x) cos(2y), with uv = xy: one chart filling the square.
#include <cmath>

#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/core/shapes.h"

namespace adaptex::bench {

/// Fills \p mesh and \p param with the n x n height field. \pre n >= 1
inline void height_field(int n, TriMesh& mesh, Parameterization& param) {
  mesh = shapes::plane(n);
  for (Vec3& p : mesh.positions) p.z() = 0.25 * std::sin(3.0 * p.x()) * std::cos(2.0 * p.y());
  param = Parameterization{};
  for (const Vec3& p : mesh.positions) param.uv.push_back(Vec2(p.x(), p.y()));
  param.uv_faces = mesh.faces;
  for (int k = 0; k < mesh.num_vertices(); ++k) param.wedge_vertex.push_back(k);
  param.face_chart.assign(mesh.faces.size(), 0);
  param.num_charts = 1;
}

}  // namespace adaptex::bench
