// Conforming longest-edge refinement of a mesh for a warp of its UV domain.
#include "adaptex/adapt/refine.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "adaptex/core/errors.h"
#include "adaptex/core/predicates.h"

namespace adaptex {
namespace {

// Half-edge h = 3 f + k is the edge from corner k to corner k+1 of face f.
inline int next3(int k) { return k == 2 ? 0 : k + 1; }

// Undirected 3-D edges of the current mesh.
struct Edges {
  std::vector<int> he_edge;                // 3F: edge id of every half-edge
  std::vector<std::array<int, 2>> edge_he; // E: its half-edges, the second -1 on the boundary
  int size() const { return static_cast<int>(edge_he.size()); }
};

// O(F): half-edges bucketed by their smaller vertex (counting sort), matched inside each bucket.
Edges build_edge_table(const TriMesh& mesh) {
  const int V = mesh.num_vertices(), F = mesh.num_faces();
  std::vector<int> start(V + 1, 0);
  for (const Face& f : mesh.faces)
    for (int k = 0; k < 3; ++k) ++start[std::min(f[k], f[next3(k)]) + 1];
  for (int v = 0; v < V; ++v) start[v + 1] += start[v];
  std::vector<int> cursor(start.begin(), start.end() - 1);
  std::vector<std::pair<int, int>> bucket(3 * static_cast<size_t>(F));  // (larger vertex, half-edge)
  for (int f = 0; f < F; ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.faces[f][k], b = mesh.faces[f][next3(k)];
      bucket[cursor[std::min(a, b)]++] = {std::max(a, b), 3 * f + k};
    }
  Edges e;
  e.he_edge.assign(bucket.size(), -1);
  e.edge_he.reserve(bucket.size() / 2 + 16);
  for (int v = 0; v < V; ++v)
    for (int i = start[v]; i < start[v + 1]; ++i) {
      const auto [b, h] = bucket[i];
      int j = start[v];
      while (j < i && bucket[j].first != b) ++j;
      if (j == i) {
        e.he_edge[h] = e.size();
        e.edge_he.push_back({h, -1});
        continue;
      }
      const int found = e.he_edge[bucket[j].second];
      if (e.edge_he[found][1] >= 0)
        throw TopologyError("refine_for_warp: edge (" + std::to_string(v) + ", " + std::to_string(b) +
                            ") has more than two faces (non-manifold mesh)");
      e.he_edge[h] = found;
      e.edge_he[found][1] = h;
    }
  return e;
}


// The mesh being refined, with the warp of every wedge and the bookkeeping of the rounds.
struct State {
  TriMesh mesh;
  Parameterization param;
  FaceData<int> parent;
  std::vector<Vec2> warped;  // U: warp(param.uv[w])
  std::vector<char> active;  // F: created by the last round (its edges are not yet checked)
  std::vector<double> face_dev;  // F: largest midpoint deviation of the face's UV edges (when checked)
  std::vector<char> face_bad;    // F: the warp flips or degenerates the face (when checked)
};

// What one round measured on the active faces.
struct Measure {
  std::vector<double> dev;   // 3F: midpoint deviation of each half-edge's UV edge, -1 if not measured
  std::vector<Vec2> mid;     // 3F: warp of the UV midpoint where measured
  std::vector<char> bad;     // F: the warp flips or degenerates the face
};

// True if the warp flips face f or makes it degenerate (faces degenerate before the warp excepted).
bool face_is_bad(const State& s, int f, double min_area) {
  const Face& w = s.param.uv_faces[f];
  const double a0 = triangle_signed_area(s.param.uv[w[0]], s.param.uv[w[1]], s.param.uv[w[2]]);
  if (std::abs(a0) <= min_area) return false;
  const double a1 = triangle_signed_area(s.warped[w[0]], s.warped[w[1]], s.warped[w[2]]);
  return a1 * (a0 > 0 ? 1.0 : -1.0) <= min_area;
}

Vec2 checked_warp(const std::function<Vec2(const Vec2&)>& warp, const Vec2& p) {
  const Vec2 q = warp(p);
  if (!std::isfinite(q.x()) || !std::isfinite(q.y()))
    throw InvalidInputError("refine_for_warp: the warp returned a non-finite point for (" +
                            std::to_string(p.x()) + ", " + std::to_string(p.y()) + ")");
  return q;
}

// Deviation of every UV edge of the active faces, in parallel; also updates face_dev / face_bad.
Measure measure(State& s, const std::function<Vec2(const Vec2&)>& warp, const RefineOptions& o) {
  const int F = s.mesh.num_faces();
  Measure m;
  m.dev.assign(3 * static_cast<size_t>(F), -1.0);
  m.mid.resize(3 * static_cast<size_t>(F));
  m.bad.assign(F, 0);
  tbb::parallel_for(tbb::blocked_range<int>(0, F, 1024), [&](const tbb::blocked_range<int>& r) {
    for (int f = r.begin(); f < r.end(); ++f) {
      if (!s.active[f]) continue;
      const Face& w = s.param.uv_faces[f];
      for (int k = 0; k < 3; ++k) {
        const int a = w[k], b = w[next3(k)];
        const Vec2 q = checked_warp(warp, 0.5 * (s.param.uv[a] + s.param.uv[b]));
        m.mid[3 * f + k] = q;
        m.dev[3 * f + k] = (q - 0.5 * (s.warped[a] + s.warped[b])).norm();
      }
      m.bad[f] = face_is_bad(s, f, o.min_area);
      s.face_bad[f] = m.bad[f];
      s.face_dev[f] = std::max({m.dev[3 * f], m.dev[3 * f + 1], m.dev[3 * f + 2]});
    }
  });
  return m;
}

// Local index of the longest UV edge of face f (first one on ties).
int longest_edge(const Parameterization& p, int f) {
  const Face& w = p.uv_faces[f];
  int best = 0;
  double best_len = -1;
  for (int k = 0; k < 3; ++k) {
    const double len = (p.uv[w[next3(k)]] - p.uv[w[k]]).squaredNorm();
    if (len > best_len) best = k, best_len = len;
  }
  return best;
}

// Edges that fail the criterion, worst first (flipping faces first, then by deviation, then by id).
std::vector<int> seed_edges(const Edges& e, const Measure& m, double tolerance) {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<std::pair<double, int>> seeds;
  for (int id = 0; id < e.size(); ++id) {
    double sev = -1;
    for (int h : e.edge_he[id])
      if (h >= 0) sev = std::max(sev, m.bad[h / 3] ? inf : m.dev[h]);
    if (sev > tolerance) seeds.push_back({sev, id});
  }
  std::sort(seeds.begin(), seeds.end(), [](const auto& x, const auto& y) {
    return x.first != y.first ? x.first > y.first : x.second < y.second;
  });
  std::vector<int> out(seeds.size());
  for (size_t i = 0; i < seeds.size(); ++i) out[i] = seeds[i].second;
  return out;
}

// Marks the seeds and closes the marking (a face with a marked edge has its longest edge marked),
// seed by seed, while the refined face count stays within max_faces. Returns the marked edges in
// marking order; sets budget_reached if a seed did not fit.
std::vector<int> close_marking(const State& s, const Edges& e, const std::vector<int>& seeds,
                               long max_faces, std::vector<char>& marked, bool& budget_reached) {
  marked.assign(e.size(), 0);
  std::vector<int> order, stack;
  long faces = s.mesh.num_faces();
  for (int seed : seeds) {
    if (marked[seed]) continue;
    const size_t first = order.size();
    long cost = 0;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const int id = stack.back();
      stack.pop_back();
      if (marked[id]) continue;
      marked[id] = 1;
      order.push_back(id);
      for (int h : e.edge_he[id]) {
        if (h < 0) continue;
        ++cost;  // each face of a split edge gains one child
        const int f = h / 3, longest = e.he_edge[3 * f + longest_edge(s.param, f)];
        if (!marked[longest]) stack.push_back(longest);
      }
    }
    if (faces + cost > max_faces) {  // undo this seed's closure and stop
      for (size_t i = first; i < order.size(); ++i) marked[order[i]] = 0;
      order.resize(first);
      budget_reached = true;
      break;
    }
    faces += cost;
  }
  return order;
}

// Indices of the new vertex of every marked edge and of the new wedge of each of its half-edges
// (one wedge per distinct UV edge: two on a seam, one elsewhere). Appends the vertices and wedges
// (positions, UVs, wedge_vertex, warped) to the state.
std::vector<int> add_midpoints(State& s, const Edges& e, const std::vector<int>& order, const Measure& m,
                               const std::function<Vec2(const Vec2&)>& warp) {
  std::vector<int> he_wedge(3 * static_cast<size_t>(s.mesh.num_faces()), -1);
  std::vector<int> source;  // half-edge each new wedge was made from
  for (int id : order) {
    const int vnew = s.mesh.num_vertices();
    const auto [h0, h1] = e.edge_he[id];
    const Face& f0 = s.mesh.faces[h0 / 3];
    s.mesh.positions.push_back(0.5 * (s.mesh.positions[f0[h0 % 3]] + s.mesh.positions[f0[next3(h0 % 3)]]));
    for (int h : {h0, h1}) {
      if (h < 0) continue;
      const Face& w = s.param.uv_faces[h / 3];
      const int a = w[h % 3], b = w[next3(h % 3)];
      if (h == h1) {  // same UV edge as the other side (not a seam): share its wedge
        const Face& w0 = s.param.uv_faces[h0 / 3];
        const int a0 = w0[h0 % 3], b0 = w0[next3(h0 % 3)];
        if (std::min(a, b) == std::min(a0, b0) && std::max(a, b) == std::max(a0, b0)) {
          he_wedge[h] = he_wedge[h0];
          continue;
        }
      }
      he_wedge[h] = s.param.num_wedges();
      source.push_back(h);
      s.param.uv.push_back(0.5 * (s.param.uv[a] + s.param.uv[b]));
      s.param.wedge_vertex.push_back(vnew);
    }
  }
  const size_t U0 = s.warped.size();
  s.warped.resize(s.param.uv.size());
  tbb::parallel_for(size_t(0), source.size(), [&](size_t i) {
    const int h = source[i];
    s.warped[U0 + i] = m.dev[h] >= 0 ? m.mid[h] : checked_warp(warp, s.param.uv[U0 + i]);
  });
  return he_wedge;
}

// Splits every face with marked edges by longest-edge bisection: the longest edge (always marked)
// first, then each child at its other marked edge: 2, 3 or 4 children with the parent's winding.
// The first child keeps the face id, the others are appended; children become active.
void split_faces(State& s, const Edges& e, const std::vector<char>& marked, const std::vector<int>& he_wedge) {
  const int F = s.mesh.num_faces();
  std::vector<int> offset(F + 1, 0);
  for (int f = 0; f < F; ++f) {
    int n = 0;
    for (int k = 0; k < 3; ++k) n += marked[e.he_edge[3 * f + k]];
    offset[f + 1] = offset[f] + n;
  }
  const int added = offset[F];
  s.mesh.faces.resize(F + added);
  s.param.uv_faces.resize(F + added);
  s.param.face_chart.resize(F + added);
  s.parent.resize(F + added);
  s.active.assign(F + added, 0);
  s.face_dev.resize(F + added);
  s.face_bad.resize(F + added);
  tbb::parallel_for(tbb::blocked_range<int>(0, F, 1024), [&](const tbb::blocked_range<int>& r) {
    for (int f = r.begin(); f < r.end(); ++f) {
      if (offset[f + 1] == offset[f]) continue;
      const int L = longest_edge(s.param, f);
      // Corners c0, c1, c2 starting at the longest edge; midpoint corners of edges c0c1, c1c2, c2c0.
      std::array<std::pair<int, int>, 3> c, mid;
      std::array<bool, 3> has{};
      for (int i = 0; i < 3; ++i) {
        const int k = (L + i) % 3, h = 3 * f + k;
        c[i] = {s.mesh.faces[f][k], s.param.uv_faces[f][k]};
        has[i] = marked[e.he_edge[h]];
        if (has[i]) mid[i] = {s.param.wedge_vertex[he_wedge[h]], he_wedge[h]};
      }
      using Tri = std::array<std::pair<int, int>, 3>;
      std::array<Tri, 4> kids;
      int n = 0;
      if (has[1]) kids[n++] = {mid[0], c[1], mid[1]}, kids[n++] = {mid[0], mid[1], c[2]};
      else kids[n++] = {mid[0], c[1], c[2]};
      if (has[2]) kids[n++] = {c[0], mid[0], mid[2]}, kids[n++] = {mid[0], c[2], mid[2]};
      else kids[n++] = {c[0], mid[0], c[2]};
      for (int i = 0; i < n; ++i) {
        const int g = i == 0 ? f : F + offset[f] + i - 1;
        for (int k = 0; k < 3; ++k) {
          s.mesh.faces[g][k] = kids[i][k].first;
          s.param.uv_faces[g][k] = kids[i][k].second;
        }
        s.param.face_chart[g] = s.param.face_chart[f];
        s.parent[g] = s.parent[f];
        s.active[g] = 1;
      }
    }
  });
}

void check_input(const TriMesh& mesh, const Parameterization& param,
                 const std::function<Vec2(const Vec2&)>& warp, const RefineOptions& o) {
  const size_t F = mesh.faces.size();
  if (!warp) throw InvalidInputError("refine_for_warp: empty warp function");
  if (!(o.tolerance > 0) || !std::isfinite(o.tolerance))
    throw InvalidInputError("refine_for_warp: tolerance must be a positive number");
  if (o.max_levels < 0) throw InvalidInputError("refine_for_warp: max_levels must be >= 0");
  if (o.max_faces < 0) throw InvalidInputError("refine_for_warp: max_faces must be >= 0");
  if (param.uv_faces.size() != F || param.face_chart.size() != F ||
      param.wedge_vertex.size() != param.uv.size())
    throw InvalidInputError("refine_for_warp: parameterization is not parallel to the mesh");
  for (size_t f = 0; f < F; ++f)
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.faces[f][k], w = param.uv_faces[f][k];
      if (v < 0 || v >= mesh.num_vertices() || w < 0 || w >= param.num_wedges() ||
          param.wedge_vertex[w] != v)
        throw InvalidInputError("refine_for_warp: face " + std::to_string(f) +
                                " has a vertex or wedge index out of range or a wedge of another vertex");
    }
}

// Largest midpoint deviation and number of bad faces over the whole refined mesh (face_dev /
// face_bad are current: a face that was checked and not split keeps its UVs).
void final_stats(const State& s, RefineResult& res) {
  res.max_deviation = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, s.face_dev.size(), 4096), 0.0,
      [&](const tbb::blocked_range<size_t>& r, double x) {
        for (size_t i = r.begin(); i < r.end(); ++i) x = std::max(x, s.face_dev[i]);
        return x;
      },
      [](double a, double b) { return std::max(a, b); });
  res.flipped = static_cast<int>(std::count(s.face_bad.begin(), s.face_bad.end(), char(1)));
}

}  // namespace

RefineResult refine_for_warp(const TriMesh& mesh, const Parameterization& param,
                             const std::function<Vec2(const Vec2&)>& warp, const RefineOptions& o) {
  check_input(mesh, param, warp, o);
  const long max_faces = o.max_faces > 0 ? o.max_faces : 4L * mesh.num_faces();
  const size_t F = mesh.faces.size();
  State s{mesh, param, std::vector<int>(F), std::vector<Vec2>(param.uv.size()), std::vector<char>(F, 1),
          std::vector<double>(F, 0.0), std::vector<char>(F, 0)};
  for (size_t f = 0; f < F; ++f) s.parent[f] = static_cast<int>(f);
  tbb::parallel_for(size_t(0), s.warped.size(), [&](size_t w) { s.warped[w] = checked_warp(warp, param.uv[w]); });
  RefineResult res;
  bool checked = false;  // the active faces have been measured since the last split
  for (int level = 0; level < o.max_levels && !res.budget_reached; ++level) {
    const Edges e = build_edge_table(s.mesh);
    const Measure m = measure(s, warp, o);
    checked = true;
    std::vector<char> marked;
    const std::vector<int> order = close_marking(s, e, seed_edges(e, m, o.tolerance), max_faces, marked,
                                                 res.budget_reached);
    if (order.empty()) break;
    const std::vector<int> he_wedge = add_midpoints(s, e, order, m, warp);
    split_faces(s, e, marked, he_wedge);
    checked = false;
    ++res.levels;
  }
  if (!checked) measure(s, warp, o);
  final_stats(s, res);
  res.added_vertices = s.mesh.num_vertices() - mesh.num_vertices();
  res.added_wedges = s.param.num_wedges() - param.num_wedges();
  res.added_faces = s.mesh.num_faces() - mesh.num_faces();
  res.mesh = std::move(s.mesh);
  res.param = std::move(s.param);
  res.parent_face = std::move(s.parent);
  return res;
}

}  // namespace adaptex
