/// \file planar.cpp
/// Planar chart growth and projection layouts (planar.h).
#include "adaptex/param/planar.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <queue>
#include <string>

#include "adaptex/core/errors.h"
#include "adaptex/core/topology.h"

namespace adaptex {

namespace {

/// Unit normal (zero for a zero-area face) and area of every face.
void face_normals(const TriMesh& mesh, std::vector<Vec3>& normal, std::vector<double>& area) {
  normal.resize(mesh.faces.size());
  area.resize(mesh.faces.size());
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& t = mesh.faces[f];
    const Vec3 c = (mesh.positions[t[1]] - mesh.positions[t[0]])
                       .cross(mesh.positions[t[2]] - mesh.positions[t[0]]);
    const double n = c.norm();
    area[f] = 0.5 * n;
    normal[f] = n > 0 && std::isfinite(n) ? Vec3(c / n) : Vec3::Zero();
  }
}

}  // namespace

PlanarCharts planar_charts(const TriMesh& mesh, const PlanarChartOptions& options) {
  if (!(options.max_normal_angle > 0 && options.max_normal_angle < 90) ||
      !(options.min_area_fraction >= 0 && options.min_area_fraction <= 1) ||
      options.normal_smoothing < 0)
    throw InvalidInputError("planar_charts: max_normal_angle must be in (0, 90), "
                            "min_area_fraction in [0, 1] and normal_smoothing >= 0");
  const int nf = mesh.num_faces();
  std::vector<Vec3> normal;
  std::vector<double> area;
  face_normals(mesh, normal, area);
  const double total = std::accumulate(area.begin(), area.end(), 0.0);
  const double cos_max = std::cos(options.max_normal_angle * M_PI / 180.0);
  const EdgeConnectivity ec = build_edges(mesh);
  // Smoothed normals decide the growth (a depth scan's faces are noisy at every scale); the face's
  // own normal must still face the chart's (its projection keeps its orientation).
  std::vector<Vec3> smooth = normal;
  for (int it = 0; it < options.normal_smoothing; ++it) {
    std::vector<Vec3> next(nf);
    for (int f = 0; f < nf; ++f) {
      Vec3 sum = smooth[f] * area[f];
      for (int e : ec.face_edges[f])
        for (int g : ec.edge_faces[e])
          if (g != f) sum += smooth[g] * area[g];
      const double len = sum.norm();
      next[f] = len > 0 && std::isfinite(len) ? Vec3(sum / len) : smooth[f];
    }
    smooth = std::move(next);
  }
  std::vector<int> order(nf);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return area[a] > area[b]; });

  // Planar charts: label >= 0; faces of charts given back: -2; not yet reached: -1.
  PlanarCharts out;
  out.label.assign(nf, -1);
  std::vector<int> members;
  for (int seed : order) {
    if (out.label[seed] != -1 || !(area[seed] > 0)) continue;
    const int id = out.num_planar;
    Vec3 sum = smooth[seed] * area[seed];
    double chart_area = area[seed];
    members.assign(1, seed);
    out.label[seed] = id;
    for (size_t i = 0; i < members.size(); ++i) {
      const Vec3 mean = sum.normalized();
      for (int e : ec.face_edges[members[i]])
        for (int g : ec.edge_faces[e]) {
          if (out.label[g] != -1 || !(area[g] > 0) || smooth[g].dot(mean) < cos_max ||
              !(normal[g].dot(mean) > 0))
            continue;
          out.label[g] = id;
          members.push_back(g);
          sum += smooth[g] * area[g];
          chart_area += area[g];
        }
    }
    if (chart_area >= options.min_area_fraction * total) {
      ++out.num_planar;
    } else {
      for (int f : members) out.label[f] = -2;
    }
  }
  // The remaining faces, in parts connected through edges.
  out.num_charts = out.num_planar;
  for (int f = 0; f < nf; ++f) {
    if (out.label[f] >= 0) continue;
    const int id = out.num_charts++;
    std::queue<int> queue;
    queue.push(f);
    out.label[f] = id;
    while (!queue.empty()) {
      const int h = queue.front();
      queue.pop();
      for (int e : ec.face_edges[h])
        for (int g : ec.edge_faces[e])
          if (out.label[g] < 0) out.label[g] = id, queue.push(g);
    }
  }
  return out;
}

std::optional<PolygonLayout> projection_layout(const TriMesh& piece) {
  std::vector<Vec3> normal;
  std::vector<double> area;
  face_normals(piece, normal, area);
  Vec3 sum = Vec3::Zero();
  for (size_t f = 0; f < normal.size(); ++f) sum += normal[f] * area[f];
  if (!(sum.norm() > 0) || !sum.allFinite()) return std::nullopt;
  const Vec3 n = sum.normalized();
  const Vec3 u = (std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized();
  const Vec3 v = n.cross(u);
  std::vector<Vec2> uv(piece.positions.size());
  for (size_t i = 0; i < uv.size(); ++i) uv[i] = Vec2(piece.positions[i].dot(u), piece.positions[i].dot(v));
  return fit_to_rectangle(piece, std::move(uv));
}

}  // namespace adaptex
