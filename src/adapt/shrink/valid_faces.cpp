/// \file valid_faces.cpp
/// Degenerate UV faces of an output layout (artists' atlases have them; scaling and turning keep them)
/// given a tiny area in their input orientation: one corner moves off the line of the other two by a
/// small fraction of a texel, so the face still reads the texels along its line. A shared wedge moves
/// when no other face it belongs to flips or degenerates; else the face gets a wedge of its own.
#include <algorithm>
#include <array>
#include <cmath>

#include "adaptex/core/predicates.h"
#include "shrink_internal.h"

namespace adaptex::shrink_detail {

namespace {


double face_area(const Parameterization& p, int f, int wedge, const Vec2& at) {
  Vec2 q[3];
  for (int k = 0; k < 3; ++k) q[k] = p.uv_faces[f][k] == wedge ? at : p.uv[p.uv_faces[f][k]];
  return triangle_signed_area(q[0], q[1], q[2]);
}

/// Positions of corner \p k of face \p f that give it signed area \p sign · (at least \p min_area),
/// inside [0,1]²: off the line of the other two corners, both ways; or none (empty).
std::vector<Vec2> lifts(const Parameterization& p, int f, int k, double sign, double min_area) {
  const Face& t = p.uv_faces[f];
  const Vec2 a = p.uv[t[(k + 1) % 3]], b = p.uv[t[(k + 2) % 3]], c = p.uv[t[k]];
  const Vec2 e = b - a;
  const double len = e.norm();
  if (!(len > 0)) return {};
  const Vec2 n(-e.y() / len, e.x() / len);
  std::vector<Vec2> out;
  // Kept inside [0,1]², or no further out than the corner already is (a wrapped, downsized layout).
  const Vec2 lo = c.cwiseMin(Vec2(0, 0)), hi = c.cwiseMax(Vec2(1, 1));
  for (double s : {1.0, -1.0}) {
    const Vec2 q = (c + s * (2.0 * min_area / len) * n).cwiseMax(lo).cwiseMin(hi);
    Vec2 r[3];
    r[k] = q;
    r[(k + 1) % 3] = a;
    r[(k + 2) % 3] = b;
    if (sign * triangle_signed_area(r[0], r[1], r[2]) >= 0.5 * min_area) out.push_back(q);
  }
  return out;
}

}  // namespace

int lift_degenerate_faces(Parameterization& out, const Parameterization& input, int size) {
  const int F = static_cast<int>(out.uv_faces.size());
  const double texel2 = 1.0 / (static_cast<double>(size) * size);
  const double degenerate = kDegenerateTexelArea * texel2, target = 1e3 * kDegenerateTexelArea * texel2;
  // Orientation of every chart in the output: the sign of its total UV area.
  std::vector<double> chart_area(std::max(out.num_charts, 1), 0.0);
  for (int f = 0; f < F; ++f)
    if (out.face_chart[f] >= 0 && out.face_chart[f] < out.num_charts) chart_area[out.face_chart[f]] += uv_signed_area(out, f);
  std::vector<std::vector<int>> wedge_faces(out.uv.size());
  for (int f = 0; f < F; ++f)
    for (int w : out.uv_faces[f]) wedge_faces[w].push_back(f);
  // The orientation every face must have: its own where it has an area, else its input face's,
  // else its chart's.
  std::vector<double> want(F);
  for (int f = 0; f < F; ++f) {
    const double a_out = uv_signed_area(out, f), a_in = uv_signed_area(input, f);
    const int chart = out.face_chart[f];
    want[f] = std::abs(a_out) >= degenerate ? (a_out > 0 ? 1.0 : -1.0)
              : a_in != 0                   ? (a_in > 0 ? 1.0 : -1.0)
              : chart >= 0 && chart < out.num_charts && chart_area[chart] < 0 ? -1.0
                                                                               : 1.0;
  }
  int lifted = 0;
  for (int f = 0; f < F; ++f) {
    if (std::abs(uv_signed_area(out, f)) >= degenerate) continue;
    const double sign = want[f];
    // The corner opposite the longest edge first (the middle one of three collinear corners).
    std::array<int, 3> order = {0, 1, 2};
    auto edge = [&](int k) { return (out.uv[out.uv_faces[f][(k + 1) % 3]] - out.uv[out.uv_faces[f][(k + 2) % 3]]).norm(); };
    std::sort(order.begin(), order.end(), [&](int x, int y) { return edge(x) > edge(y); });
    bool done = false;
    for (int k : order) {  // move the shared wedge if every other face keeps its orientation and area
      const int w = out.uv_faces[f][k];
      for (const Vec2& q : lifts(out, f, k, sign, target)) {
        const bool ok = std::all_of(wedge_faces[w].begin(), wedge_faces[w].end(), [&](int g) {
          if (g == f) return true;
          return want[g] * face_area(out, g, w, q) >= degenerate;
        });
        if (ok) {
          out.uv[w] = q;
          done = true;
          break;
        }
      }
      if (done) break;
    }
    for (int k : order) {  // else a wedge of the face's own
      if (done) break;
      const std::vector<Vec2> q = lifts(out, f, k, sign, target);
      if (q.empty()) continue;
      const int w = out.uv_faces[f][k];
      out.uv.push_back(q[0]);
      out.wedge_vertex.push_back(out.wedge_vertex[w]);
      out.uv_faces[f][k] = out.num_wedges() - 1;
      done = true;
    }
    if (!done) {  // all three corners at one point: a small right triangle of own wedges
      const double leg = std::sqrt(2.0 * target);
      const Vec2 c = out.uv[out.uv_faces[f][0]];
      const Vec2 dx(c.x() > 0.5 ? -leg : leg, 0), dy(0, c.y() > 0.5 ? -leg : leg);  // towards the square's centre
      const bool ccw = dx.x() * dy.y() > 0;
      const Vec2 q[3] = {c, c + ((ccw == (sign > 0)) ? dx : dy), c + ((ccw == (sign > 0)) ? dy : dx)};
      for (int k = 0; k < 3; ++k) {
        out.uv.push_back(q[k]);
        out.wedge_vertex.push_back(out.wedge_vertex[out.uv_faces[f][k]]);
        out.uv_faces[f][k] = out.num_wedges() - 1;
      }
    }
    ++lifted;
  }
  return lifted;
}

}  // namespace adaptex::shrink_detail
