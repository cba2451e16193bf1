/// \file unfold.cpp
/// Isometric unfolding of triangulated polygons (unfold.h).
#include "adaptex/param/unfold.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <queue>
#include <string>

#include "adaptex/core/errors.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/core/topology.h"
#include "adaptex/param/stretch.h"

namespace adaptex {

namespace {

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Every edge on one or two faces, every vertex on exactly two boundary edges, V - E + F = 1 (that
/// the faces are connected is checked by the unfolding).
bool is_triangulated_polygon(const TriMesh& disk, const EdgeConnectivity& ec) {
  const int nv = disk.num_vertices();
  std::vector<int> boundary_degree(nv, 0);
  for (int e = 0; e < ec.num_edges(); ++e) {
    const size_t n = ec.edge_faces[e].size();
    if (n == 0 || n > 2) return false;
    if (n == 1) ++boundary_degree[ec.edges[e][0]], ++boundary_degree[ec.edges[e][1]];
  }
  for (int d : boundary_degree)
    if (d != 2) return false;
  return nv - ec.num_edges() + disk.num_faces() == 1;
}

/// Position of vertex c of a face whose vertex order is (x, y, c), with x at \p px and y at \p py:
/// the triangle with |xc| = \p lxc, area \p area and c on the left of x -> y. The height comes
/// from the (cross-product) area, not from the side lengths, so that slivers keep their shape.
Vec2 apex(const Vec2& px, const Vec2& py, double lxc, double lyc, double area) {
  const Vec2 d = py - px;
  const double len = d.norm();
  const Vec2 u = len > 0 ? Vec2(d / len) : Vec2(1, 0);
  const double along = len > 0 ? (lxc * lxc - lyc * lyc + len * len) / (2 * len) : 0.0;
  const double h = len > 0 ? 2 * area / len : 0.0;
  return px + along * u + h * Vec2(-u.y(), u.x());
}

/// The isometric layout, face by face across the dual tree (breadth first from face 0). Empty when
/// a face cannot be reached.
std::vector<Vec2> unfold_faces(const TriMesh& disk, const EdgeConnectivity& ec) {
  const int nf = disk.num_faces();
  auto length = [&](int a, int b) { return (disk.positions[a] - disk.positions[b]).norm(); };
  std::vector<Vec2> uv(disk.num_vertices(), Vec2::Zero());
  std::vector<char> placed_vertex(disk.num_vertices(), 0), placed_face(nf, 0);
  auto place_face = [&](int f, int k) {  // corners k and k+1 are placed; place the third
    const Face& t = disk.faces[f];
    const int x = t[k], y = t[(k + 1) % 3], c = t[(k + 2) % 3];
    const Vec3 &a = disk.positions[x], &b = disk.positions[y];
    if (!placed_vertex[c])
      uv[c] = apex(uv[x], uv[y], length(x, c), length(y, c),
                   0.5 * (b - a).cross(disk.positions[c] - a).norm());
    placed_vertex[c] = 1;
    placed_face[f] = 1;
  };
  const Face& t0 = disk.faces[0];
  uv[t0[1]] = Vec2(length(t0[0], t0[1]), 0);
  placed_vertex[t0[0]] = placed_vertex[t0[1]] = 1;
  place_face(0, 0);
  std::queue<int> queue;
  queue.push(0);
  int reached = 1;
  while (!queue.empty()) {
    const int f = queue.front();
    queue.pop();
    for (int e : ec.face_edges[f])
      for (int g : ec.edge_faces[e]) {
        if (placed_face[g]) continue;
        // The shared edge runs from corner k to corner k + 1 of g.
        int k = 0;
        while (k < 3 && ec.face_edges[g][k] != e) ++k;
        if (k == 3) return {};
        place_face(g, k);
        queue.push(g);
        ++reached;
      }
  }
  if (reached != nf) return {};
  return uv;
}

/// Convex hull (Andrew's monotone chain), counter-clockwise, without collinear points.
std::vector<Vec2> convex_hull(std::vector<Vec2> p) {
  std::sort(p.begin(), p.end(),
            [](const Vec2& a, const Vec2& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  if (p.size() < 3) return p;
  std::vector<Vec2> h(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross2(h[k - 1] - h[k - 2], p[i] - h[k - 2]) <= 0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross2(h[k - 1] - h[k - 2], p[i] - h[k - 2]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

}  // namespace

void check_layout_mesh(const TriMesh& disk, const char* who) {
  const int nv = disk.num_vertices();
  for (const Face& t : disk.faces)
    for (int v : t)
      if (v < 0 || v >= nv)
        throw InvalidInputError(std::string(who) + ": face index " + std::to_string(v) +
                                " is outside [0, " + std::to_string(nv) + ")");
  for (const Vec3& p : disk.positions)
    if (!p.allFinite()) throw InvalidInputError(std::string(who) + ": a vertex position is not finite");
}

std::optional<PolygonLayout> unfold_polygon(const TriMesh& disk) {
  check_layout_mesh(disk, "unfold_polygon");
  // A triangulated polygon has F = V - 2 (V boundary edges, 2E = 3F + V, V - E + F = 1): an O(1)
  // test that turns away every other mesh before its edges are built.
  if (disk.faces.empty() || disk.num_faces() != disk.num_vertices() - 2) return std::nullopt;
  const EdgeConnectivity ec = build_edges(disk);
  if (!is_triangulated_polygon(disk, ec)) return std::nullopt;
  std::vector<Vec2> uv = unfold_faces(disk, ec);
  // Finite positions can still overflow (coordinates near 1e308): fit_to_rectangle() rejects them.
  if (uv.empty()) return std::nullopt;
  return fit_to_rectangle(disk, std::move(uv));
}

std::optional<PolygonLayout> fit_to_rectangle(const TriMesh& disk, std::vector<Vec2> uv) {
  // The hull's sort needs comparable (non-NaN) points.
  if (disk.faces.empty() || uv.size() != disk.positions.size() ||
      !std::all_of(uv.begin(), uv.end(), [](const Vec2& q) { return q.allFinite(); }))
    return std::nullopt;
  // Smallest bounding rectangle: one of its sides lies along an edge of the convex hull.
  const std::vector<Vec2> hull = convex_hull(uv);
  if (hull.size() < 3) return std::nullopt;
  double best_area = std::numeric_limits<double>::infinity();
  Vec2 best_u(1, 0);
  for (size_t i = 0; i < hull.size(); ++i) {
    const Vec2 d = hull[(i + 1) % hull.size()] - hull[i];
    if (!(d.norm() > 0)) continue;
    const Vec2 u = d.normalized(), v(-u.y(), u.x());
    double lo_u = std::numeric_limits<double>::infinity(), hi_u = -lo_u, lo_v = lo_u, hi_v = -lo_u;
    for (const Vec2& q : hull) {
      lo_u = std::min(lo_u, q.dot(u)), hi_u = std::max(hi_u, q.dot(u));
      lo_v = std::min(lo_v, q.dot(v)), hi_v = std::max(hi_v, q.dot(v));
    }
    if ((hi_u - lo_u) * (hi_v - lo_v) < best_area) best_area = (hi_u - lo_u) * (hi_v - lo_v), best_u = u;
  }
  // Turn (a rotation keeps the orientation), then scale into the unit square.
  const Vec2 v(-best_u.y(), best_u.x());
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (Vec2& q : uv) {
    q = Vec2(q.dot(best_u), q.dot(v));
    lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  }
  const Vec2 size = hi - lo;
  if (!(size.x() > 0 && size.y() > 0)) return std::nullopt;
  PolygonLayout out;
  out.aspect = size.x() / size.y();
  double area = 0;
  for (Vec2& q : uv) q = ((q - lo).cwiseQuotient(size)).cwiseMax(0.0).cwiseMin(1.0);
  for (const Face& t : disk.faces) area += 0.5 * cross2(uv[t[1]] - uv[t[0]], uv[t[2]] - uv[t[0]]);
  out.fill = area;
  out.uv = std::move(uv);

  // Reject a layout that folds, degenerates or overlaps itself.
  const StretchStats s = measure_stretch(disk, out.uv);
  if (s.flipped > 0 || s.degenerate > 0 || !(out.fill > 0)) return std::nullopt;
  Parameterization p;
  p.uv = out.uv;
  p.uv_faces = disk.faces;
  p.wedge_vertex.resize(out.uv.size());
  std::iota(p.wedge_vertex.begin(), p.wedge_vertex.end(), 0);
  p.face_chart.assign(disk.faces.size(), 0);
  p.num_charts = 1;
  if (count_overlapping_triangles(p, 1) > 0) return std::nullopt;
  return out;
}

}  // namespace adaptex
