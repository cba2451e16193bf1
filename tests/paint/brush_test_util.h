#pragma once
// Shared fixtures of the brush tests: a unit plane with uv = xy (or a shrunk chart), stroke sets.
#include "adaptex/core/parameterization.h"
#include "adaptex/core/shapes.h"
#include "adaptex/paint/strokes.h"

namespace adaptex::test {

/// Parameterization of a flat mesh in z = 0 with uv = offset + scale * (x, y).
inline Parameterization planar_param(const TriMesh& mesh, double scale = 1.0, double offset = 0.0) {
  Parameterization p;
  for (const Vec3& v : mesh.positions) p.uv.push_back(Vec2(offset + scale * v.x(), offset + scale * v.y()));
  p.uv_faces = mesh.faces;
  for (int v = 0; v < mesh.num_vertices(); ++v) p.wedge_vertex.push_back(v);
  p.face_chart.assign(mesh.faces.size(), 0);
  p.num_charts = 1;
  return p;
}

inline Stroke make_stroke(Vec3 color, double radius, double hardness, double opacity, std::vector<Vec3> dabs) {
  Stroke s;
  s.color = color;
  s.radius = radius;
  s.hardness = hardness;
  s.opacity = opacity;
  s.dabs = std::move(dabs);
  return s;
}

/// Dabs along a segment of the z = 0 plane, spaced `step`.
inline std::vector<Vec3> segment(Vec2 a, Vec2 b, double step) {
  std::vector<Vec3> out;
  const int n = std::max(1, static_cast<int>((b - a).norm() / step));
  for (int k = 0; k <= n; ++k) {
    const Vec2 p = a + (b - a) * (double(k) / n);
    out.push_back(Vec3(p.x(), p.y(), 0));
  }
  return out;
}

/// A soft-edged stroke set on the unit plane (smooth enough for > 45 dB at 2048^2).
inline StrokeFile plane_strokes() {
  StrokeFile f;
  f.background = Vec3(1, 1, 1);
  f.strokes.push_back(make_stroke(Vec3(0.85, 0.1, 0.1), 0.08, 0.3, 0.9, segment({0.1, 0.2}, {0.9, 0.7}, 0.01)));
  f.strokes.push_back(make_stroke(Vec3(0.1, 0.2, 0.8), 0.05, 0.5, 0.8, segment({0.2, 0.9}, {0.6, 0.1}, 0.01)));
  f.strokes.push_back(make_stroke(Vec3(0.1, 0.7, 0.2), 0.12, 0.0, 0.6, segment({0.5, 0.5}, {0.8, 0.3}, 0.02)));
  f.strokes.push_back(make_stroke(Vec3(0.95, 0.8, 0.1), 0.03, 0.6, 1.0, segment({0.15, 0.85}, {0.85, 0.8}, 0.005)));
  return f;
}

}  // namespace adaptex::test
