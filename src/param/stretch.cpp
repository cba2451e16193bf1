/// \file stretch.cpp
/// Sander et al. 2001 stretch metrics (thesis §2.1.3), overlap counting and texel utilization.
#include "adaptex/param/stretch.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>

#include "adaptex/core/predicates.h"

namespace adaptex {

namespace {


/// Twice the signed area of the UV triangle.
double signed_area2(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
}

/// Per-face raw data shared by the summaries: 3-D area, signed UV area, singular values.
struct FaceData3 {
  double a3 = 0, a2 = 0;
  FaceStretch s;
};

/// Evaluates all faces. \p uv_of(f, k) gives the UV of corner k of face f.
template <class UvOf>
std::vector<FaceData3> evaluate_faces(const TriMesh& mesh, UvOf uv_of) {
  const int nf = mesh.num_faces();
  std::vector<FaceData3> out(nf);
  tbb::parallel_for(tbb::blocked_range<int>(0, nf, 4096), [&](const tbb::blocked_range<int>& r) {
    for (int f = r.begin(); f != r.end(); ++f) {
      const Face& t = mesh.faces[f];
      const Vec3 &p0 = mesh.positions[t[0]], &p1 = mesh.positions[t[1]], &p2 = mesh.positions[t[2]];
      const Vec2 t0 = uv_of(f, 0), t1 = uv_of(f, 1), t2 = uv_of(f, 2);
      out[f].a3 = 0.5 * (p1 - p0).cross(p2 - p0).norm();
      out[f].a2 = 0.5 * signed_area2(t0, t1, t2);
      out[f].s = face_stretch(p0, p1, p2, t0, t1, t2);
    }
  });
  return out;
}

/// Tolerance under which a UV triangle counts as degenerate (relative to the mean |A₂|).
bool is_degenerate(double a2, double mean_abs_a2) {
  return !(std::abs(a2) > 1e-14 * mean_abs_a2) || a2 == 0.0;
}

struct Sums {
  double a3 = 0, a2 = 0, abs_a2 = 0;
};

Sums area_sums(const std::vector<FaceData3>& d) {
  Sums s;
  for (const auto& x : d) {
    s.a3 += x.a3;
    s.a2 += std::max(x.a2, 0.0);
    s.abs_a2 += std::abs(x.a2);
  }
  return s;
}

std::vector<double> l2_per_face(const std::vector<FaceData3>& d) {
  const Sums s = area_sums(d);
  const double scale = s.a3 > 0 ? std::sqrt(s.a2 / s.a3) : 0.0;
  std::vector<double> out(d.size());
  for (size_t f = 0; f < d.size(); ++f) {
    const double l2 = d[f].s.l2();
    out[f] = std::isfinite(l2) ? l2 * scale : kInf;
  }
  return out;
}

/// The figures of StretchStats from the per-face data; without \p distortions, area_distortion and
/// angle_distortion stay 0 (a division per face saved where only L2 and the counts are read).
StretchStats summarize(const std::vector<FaceData3>& d, bool distortions = true) {
  StretchStats st;
  const Sums s = area_sums(d);
  const double mean_abs = d.empty() ? 0.0 : s.abs_a2 / static_cast<double>(d.size());
  double sum_l2sq = 0, max_gamma = 0, area_dist = 0, angle_dist = 0;
  for (const auto& x : d) {
    if (is_degenerate(x.a2, mean_abs)) {
      ++st.degenerate;
      continue;
    }
    if (x.a2 < 0) {
      ++st.flipped;
      continue;
    }
    const double l2 = x.s.l2();
    sum_l2sq += x.a3 * l2 * l2;
    max_gamma = std::max(max_gamma, x.s.gamma_max);
    if (!distortions) continue;
    const double rel = (x.a2 / s.a2) / (x.a3 / s.a3);
    area_dist += x.a3 * std::max(rel, 1.0 / rel);
    angle_dist += x.a3 * (x.s.gamma_min > 0 ? x.s.gamma_max / x.s.gamma_min : kInf);
  }
  if (s.a3 <= 0) return st;
  const double norm = std::sqrt(s.a2 / s.a3);
  const bool bad = st.flipped > 0 || st.degenerate > 0;
  st.l2 = bad ? kInf : std::sqrt(sum_l2sq / s.a3) * norm;
  st.linf = bad ? kInf : max_gamma * norm;
  if (distortions) {
    st.area_distortion = bad ? kInf : area_dist / s.a3;
    st.angle_distortion = bad ? kInf : angle_dist / s.a3;
  }
  return st;
}

}  // namespace

double FaceStretch::l2() const { return std::sqrt(0.5 * (gamma_max * gamma_max + gamma_min * gamma_min)); }

FaceStretch face_stretch(const Vec3& q1, const Vec3& q2, const Vec3& q3, const Vec2& t1,
                         const Vec2& t2, const Vec2& t3) {
  const double a2 = signed_area2(t1, t2, t3);  // 2A
  if (!(a2 > 0)) return {kInf, kInf};
  const Vec3 ss = (q1 * (t2.y() - t3.y()) + q2 * (t3.y() - t1.y()) + q3 * (t1.y() - t2.y())) / a2;
  const Vec3 st = (q1 * (t3.x() - t2.x()) + q2 * (t1.x() - t3.x()) + q3 * (t2.x() - t1.x())) / a2;
  const double a = ss.squaredNorm(), b = ss.dot(st), c = st.squaredNorm();
  const double root = std::sqrt((a - c) * (a - c) + 4 * b * b);
  return {std::sqrt(0.5 * ((a + c) + root)), std::sqrt(std::max(0.0, 0.5 * ((a + c) - root)))};
}

std::vector<double> face_l2_stretch(const TriMesh& mesh, const Parameterization& param) {
  return l2_per_face(evaluate_faces(
      mesh, [&](int f, int k) { return param.uv[param.uv_faces[f][k]]; }));
}

std::vector<double> face_l2_stretch(const TriMesh& mesh, const std::vector<Vec2>& vertex_uv) {
  return l2_per_face(
      evaluate_faces(mesh, [&](int f, int k) { return vertex_uv[mesh.faces[f][k]]; }));
}

StretchStats measure_stretch(const TriMesh& mesh, const Parameterization& param) {
  return summarize(evaluate_faces(
      mesh, [&](int f, int k) { return param.uv[param.uv_faces[f][k]]; }));
}

StretchStats measure_stretch(const TriMesh& mesh, const std::vector<Vec2>& vertex_uv) {
  return summarize(
      evaluate_faces(mesh, [&](int f, int k) { return vertex_uv[mesh.faces[f][k]]; }));
}

StretchStats measure_stretch(const TriMesh& mesh, const std::vector<Vec2>& vertex_uv,
                             std::vector<double>& face_l2) {
  const std::vector<FaceData3> d =
      evaluate_faces(mesh, [&](int f, int k) { return vertex_uv[mesh.faces[f][k]]; });
  face_l2 = l2_per_face(d);
  return summarize(d, false);
}

std::vector<double> l2_stretch_of_aspects(const TriMesh& mesh, const std::vector<Vec2>& vertex_uv,
                                          const std::vector<double>& aspects) {
  const int nf = mesh.num_faces();
  std::vector<double> a3(nf), a2(nf);
  double P = 0, Q = 0, abs_a2 = 0;
  for (int f = 0; f < nf; ++f) {
    const Face& t = mesh.faces[f];
    const Vec3 &q1 = mesh.positions[t[0]], &q2 = mesh.positions[t[1]], &q3 = mesh.positions[t[2]];
    const Vec2 &t1 = vertex_uv[t[0]], &t2 = vertex_uv[t[1]], &t3 = vertex_uv[t[2]];
    const double s2 = signed_area2(t1, t2, t3);  // 2A
    a3[f] = 0.5 * (q2 - q1).cross(q3 - q1).norm();
    a2[f] = 0.5 * s2;
    abs_a2 += std::abs(a2[f]);
    if (!(s2 > 0)) continue;  // flipped or degenerate: the result is +inf (below)
    const Vec3 ss = (q1 * (t2.y() - t3.y()) + q2 * (t3.y() - t1.y()) + q3 * (t1.y() - t2.y())) / s2;
    const Vec3 st = (q1 * (t3.x() - t2.x()) + q2 * (t1.x() - t3.x()) + q3 * (t2.x() - t1.x())) / s2;
    P += a3[f] * ss.squaredNorm();
    Q += a3[f] * st.squaredNorm();
  }
  // The same classification and normalization as summarize().
  const double mean_abs = nf > 0 ? abs_a2 / nf : 0.0;
  double sum_a3 = 0, sum_a2 = 0;
  bool bad = false;
  for (int f = 0; f < nf; ++f) {
    bad = bad || is_degenerate(a2[f], mean_abs) || a2[f] < 0;
    sum_a3 += a3[f];
    sum_a2 += std::max(a2[f], 0.0);
  }
  std::vector<double> out(aspects.size(), bad ? kInf : 0.0);
  if (bad || !(sum_a3 > 0)) return out;
  const double norm = std::sqrt(sum_a2 / sum_a3);
  for (size_t i = 0; i < aspects.size(); ++i)
    out[i] = std::sqrt(0.5 * (P / aspects[i] + Q * aspects[i]) / sum_a3) * norm;
  return out;
}

// ---------------------------------------------------------------------------------------------
// Overlap counting.

namespace {

int orient(const Vec2& a, const Vec2& b, const Vec2& c) { return orient2d_filtered(a, b, c); }

/// True when the interiors of the (non-degenerate) triangles a and b intersect: no edge of either
/// triangle is a (weakly) separating line (separating-axis theorem for convex polygons).
bool interiors_overlap(const std::array<Vec2, 3>& a, int sa, const std::array<Vec2, 3>& b, int sb) {
  auto separated_by_edges = [](const std::array<Vec2, 3>& t, int s, const std::array<Vec2, 3>& o) {
    for (int k = 0; k < 3; ++k) {
      const Vec2& p = t[k];
      const Vec2& q = t[(k + 1) % 3];
      bool all_out = true;
      for (int j = 0; j < 3 && all_out; ++j) all_out = s * orient(p, q, o[j]) <= 0;
      if (all_out) return true;
    }
    return false;
  };
  return !separated_by_edges(a, sa, b) && !separated_by_edges(b, sb, a);
}

}  // namespace

namespace {
/// Calls \p found(f, g) (f < g, from several threads) for every pair of UV triangles whose interiors
/// overlap, until it returns false; see count_overlapping_triangles().
template <class Found>
void for_overlapping_pairs(const Parameterization& param, Found&& found,
                           const std::vector<char>* among = nullptr) {
  const int nf = static_cast<int>(param.uv_faces.size());
  if (nf < 2) return;
  struct Tri {
    std::array<Vec2, 3> p;
    Vec2 lo, hi;
    int sign;
    int x0, y0, x1, y1;  ///< The grid cells of the bounding box's corners.
  };
  std::vector<Tri> tris(nf);
  Vec2 lo = Vec2::Constant(kInf), hi = Vec2::Constant(-kInf);
  for (int f = 0; f < nf; ++f) {
    Tri& t = tris[f];
    for (int k = 0; k < 3; ++k) t.p[k] = param.uv[param.uv_faces[f][k]];
    t.lo = t.p[0].cwiseMin(t.p[1]).cwiseMin(t.p[2]);
    t.hi = t.p[0].cwiseMax(t.p[1]).cwiseMax(t.p[2]);
    t.sign = among && !(*among)[f] ? 0 : orient(t.p[0], t.p[1], t.p[2]);  // 0: not bucketed
    lo = lo.cwiseMin(t.lo);
    hi = hi.cwiseMax(t.hi);
  }
  // Uniform grid with about one triangle per cell.
  const int n = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(nf))), 1, 4096);
  const Vec2 ext = (hi - lo).cwiseMax(Vec2::Constant(1e-300));
  auto cell_of = [&](double x, double lo_, double ext_) {
    return std::clamp(static_cast<int>((x - lo_) / ext_ * n), 0, n - 1);
  };
  for (Tri& t : tris) {
    t.x0 = cell_of(t.lo.x(), lo.x(), ext.x()), t.x1 = cell_of(t.hi.x(), lo.x(), ext.x());
    t.y0 = cell_of(t.lo.y(), lo.y(), ext.y()), t.y1 = cell_of(t.hi.y(), lo.y(), ext.y());
  }
  std::vector<int> count(static_cast<size_t>(n) * n + 1, 0);
  auto for_cells = [&](const Tri& t, auto&& fn) {
    for (int y = t.y0; y <= t.y1; ++y)
      for (int x = t.x0; x <= t.x1; ++x) fn(static_cast<size_t>(y) * n + x);
  };
  for (int f = 0; f < nf; ++f)
    if (tris[f].sign != 0) for_cells(tris[f], [&](size_t c) { ++count[c + 1]; });
  for (size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
  std::vector<int> items(count.back());
  {
    std::vector<int> fill(count.begin(), count.end() - 1);
    for (int f = 0; f < nf; ++f)
      if (tris[f].sign != 0) for_cells(tris[f], [&](size_t c) { items[fill[c]++] = f; });
  }
  std::atomic<bool> stop{false};
  tbb::parallel_for(tbb::blocked_range<size_t>(0, static_cast<size_t>(n) * n, 64),
                    [&](const tbb::blocked_range<size_t>& r) {
    for (size_t c = r.begin(); c != r.end(); ++c) {
      if (stop.load(std::memory_order_relaxed)) return;
      const int cx = static_cast<int>(c % n), cy = static_cast<int>(c / n);
      for (int i = count[c]; i < count[c + 1]; ++i)
        for (int j = i + 1; j < count[c + 1]; ++j) {
          const Tri& a = tris[items[i]];
          const Tri& b = tris[items[j]];
          // Count each pair once: in the cell holding the low corner of the boxes' intersection
          // (cell_of() is monotone, so that cell is the larger of the two boxes' low cells).
          if (std::max(a.x0, b.x0) != cx || std::max(a.y0, b.y0) != cy) continue;
          if (a.hi.x() < b.lo.x() || b.hi.x() < a.lo.x() || a.hi.y() < b.lo.y() || b.hi.y() < a.lo.y())
            continue;
          if (interiors_overlap(a.p, a.sign, b.p, b.sign) &&
              !found(std::min(items[i], items[j]), std::max(items[i], items[j])))
            stop.store(true, std::memory_order_relaxed);
        }
    }
  });
}
}  // namespace

long count_overlapping_triangles(const Parameterization& param, long max_pairs) {
  std::atomic<long> found{0};
  for_overlapping_pairs(param, [&](int, int) { return found.fetch_add(1, std::memory_order_relaxed) + 1 < max_pairs; });
  return std::min(found.load(), max_pairs);
}

std::vector<std::array<int, 2>> overlapping_triangle_pairs(const Parameterization& param, long max_pairs) {
  std::mutex m;
  std::vector<std::array<int, 2>> pairs;
  for_overlapping_pairs(param, [&](int f, int g) {
    const std::lock_guard<std::mutex> lock(m);
    if (static_cast<long>(pairs.size()) < max_pairs) pairs.push_back({f, g});
    return static_cast<long>(pairs.size()) < max_pairs;
  });
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

std::vector<int> invalid_uv_faces(const Parameterization& param, const std::vector<char>* overlaps_among,
                                  long max_pairs) {
  const int nf = static_cast<int>(param.uv_faces.size());
  std::vector<double> a2(nf);
  double sum_abs = 0;
  for (int f = 0; f < nf; ++f) {
    const Face& t = param.uv_faces[f];
    a2[f] = 0.5 * signed_area2(param.uv[t[0]], param.uv[t[1]], param.uv[t[2]]);
    sum_abs += std::abs(a2[f]);
  }
  const double mean_abs = nf > 0 ? sum_abs / nf : 0.0;
  std::vector<int> bad;
  for (int f = 0; f < nf; ++f)
    if (is_degenerate(a2[f], mean_abs) || a2[f] < 0) bad.push_back(f);
  std::mutex m;
  long pairs = 0;
  for_overlapping_pairs(
      param,
      [&](int f, int g) {
        const std::lock_guard<std::mutex> lock(m);
        bad.push_back(f);
        bad.push_back(g);
        return ++pairs < max_pairs;
      },
      overlaps_among);
  std::sort(bad.begin(), bad.end());
  bad.erase(std::unique(bad.begin(), bad.end()), bad.end());
  return bad;
}

namespace {

/// Squared distance from \p p to the segment \p a \p b.
double squared_distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (a + t * d - p).squaredNorm();
}

/// A boundary edge (wedges a < b) and the one triangle it belongs to.
struct BoundaryEdge {
  int a, b, face;
};

/// The boundary edges (wedge pairs of one triangle only) of \p faces.
std::vector<BoundaryEdge> boundary_edges(const std::vector<Face>& faces) {
  std::vector<BoundaryEdge> half;
  half.reserve(3 * faces.size());
  for (size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = faces[f][k], b = faces[f][(k + 1) % 3];
      half.push_back({std::min(a, b), std::max(a, b), static_cast<int>(f)});
    }
  const auto key = [](const BoundaryEdge& e) { return std::pair(e.a, e.b); };
  std::sort(half.begin(), half.end(), [&](const BoundaryEdge& x, const BoundaryEdge& y) { return key(x) < key(y); });
  std::vector<BoundaryEdge> out;
  for (size_t i = 0; i < half.size();) {
    size_t j = i;
    while (j < half.size() && key(half[j]) == key(half[i])) ++j;
    if (j - i == 1) out.push_back(half[i]);
    i = j;
  }
  return out;
}

}  // namespace

bool boundary_near_contact(const std::vector<Vec2>& uv, const std::vector<Face>& faces, double tol) {
  const std::vector<BoundaryEdge> edges = boundary_edges(faces);
  if (edges.empty()) return false;
  Vec2 lo = Vec2::Constant(kInf), hi = Vec2::Constant(-kInf);
  for (const BoundaryEdge& e : edges) lo = lo.cwiseMin(uv[e.a]).cwiseMin(uv[e.b]), hi = hi.cwiseMax(uv[e.a]).cwiseMax(uv[e.b]);
  // Uniform grid with about one edge per cell; an edge is listed in every cell its box, grown by
  // tol, touches, so a wedge need only look in its own cell.
  const int n = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(edges.size()))), 1, 1024);
  const Vec2 ext = (hi - lo).cwiseMax(Vec2::Constant(1e-300));
  const auto cell = [&](double x, double lo_, double ext_) {
    return std::clamp(static_cast<int>((x - lo_) / ext_ * n), 0, n - 1);
  };
  std::vector<std::vector<int>> bucket(static_cast<size_t>(n) * n);
  for (size_t i = 0; i < edges.size(); ++i) {
    const Vec2 a = uv[edges[i].a].cwiseMin(uv[edges[i].b]) - Vec2::Constant(tol);
    const Vec2 b = uv[edges[i].a].cwiseMax(uv[edges[i].b]) + Vec2::Constant(tol);
    for (int y = cell(a.y(), lo.y(), ext.y()); y <= cell(b.y(), lo.y(), ext.y()); ++y)
      for (int x = cell(a.x(), lo.x(), ext.x()); x <= cell(b.x(), lo.x(), ext.x()); ++x)
        bucket[static_cast<size_t>(y) * n + x].push_back(static_cast<int>(i));
  }
  std::vector<int> wedges;
  for (const BoundaryEdge& e : edges) wedges.push_back(e.a), wedges.push_back(e.b);
  std::sort(wedges.begin(), wedges.end());
  wedges.erase(std::unique(wedges.begin(), wedges.end()), wedges.end());
  for (int w : wedges) {
    const Vec2& p = uv[w];
    for (int i : bucket[static_cast<size_t>(cell(p.y(), lo.y(), ext.y())) * n + cell(p.x(), lo.x(), ext.x())]) {
      const BoundaryEdge& e = edges[i];
      // A wedge of the edge's own triangle is that triangle's shape (a sliver), not a contact; a
      // wedge on an endpoint (a zipped cut) stays on it under any transform: not fragile.
      const Face& t = faces[e.face];
      if (t[0] == w || t[1] == w || t[2] == w || p == uv[e.a] || p == uv[e.b]) continue;
      if (squared_distance_to_segment(p, uv[e.a], uv[e.b]) <= tol * tol) return true;
    }
  }
  return false;
}

double texel_utilization(const Parameterization& param, int res) {
  if (res <= 0) return 0;
  std::vector<unsigned char> covered(static_cast<size_t>(res) * res, 0);
  for (const Face& f : param.uv_faces) {
    const Vec2 &a = param.uv[f[0]], &b = param.uv[f[1]], &c = param.uv[f[2]];
    const double s = signed_area2(a, b, c);
    if (s == 0) continue;
    const Vec2 lo = a.cwiseMin(b).cwiseMin(c) * res, hi = a.cwiseMax(b).cwiseMax(c) * res;
    const int x0 = std::max(0, static_cast<int>(std::ceil(lo.x() - 0.5)));
    const int x1 = std::min(res - 1, static_cast<int>(std::floor(hi.x() - 0.5)));
    const int y0 = std::max(0, static_cast<int>(std::ceil(lo.y() - 0.5)));
    const int y1 = std::min(res - 1, static_cast<int>(std::floor(hi.y() - 0.5)));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const Vec2 p((x + 0.5) / res, (y + 0.5) / res);
        const double w0 = signed_area2(b, c, p), w1 = signed_area2(c, a, p), w2 = signed_area2(a, b, p);
        const bool inside = s > 0 ? (w0 >= 0 && w1 >= 0 && w2 >= 0) : (w0 <= 0 && w1 <= 0 && w2 <= 0);
        if (inside) covered[static_cast<size_t>(y) * res + x] = 1;
      }
  }
  long n = 0;
  for (unsigned char v : covered) n += v;
  return static_cast<double>(n) / (static_cast<double>(res) * res);
}

}  // namespace adaptex
