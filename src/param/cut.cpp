/// \file cut.cpp
/// Thesis §3.2 topological surgery (Gu, Gortler, Hoppe 2002): initial cut by face peeling with
/// dangling-edge pruning, genus-0 cut, slicing, shortest paths for the cut augmentation.
#include "adaptex/param/cut.h"

#include <algorithm>
#include <limits>
#include <queue>
#include <string>

#include "adaptex/core/errors.h"
#include "adaptex/core/union_find.h"

namespace adaptex {

namespace {


/// Dijkstra from \p sources (distance 0). Fills dist and the edge to the parent (-1 at sources).
/// Stops early once \p stop (if any) returns true for a settled vertex; returns that vertex or -1.
template <class Stop>
int dijkstra(const EdgeGraph& g, const std::vector<int>& sources, std::vector<double>& dist,
             std::vector<int>& parent_edge, Stop stop) {
  const int nv = static_cast<int>(g.offsets.size()) - 1;
  dist.assign(nv, kInf);
  parent_edge.assign(nv, -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> pq;
  for (int s : sources) {
    dist[s] = 0;
    pq.push({0.0, s});
  }
  while (!pq.empty()) {
    const auto [d, v] = pq.top();
    pq.pop();
    if (d > dist[v]) continue;
    if (stop(v)) return v;
    for (int k = g.offsets[v]; k < g.offsets[v + 1]; ++k) {
      const int u = g.nbr[k];
      const double nd = d + g.length[g.edge[k]];
      if (nd < dist[u]) {
        dist[u] = nd;
        parent_edge[u] = g.edge[k];
        pq.push({nd, u});
      }
    }
  }
  return -1;
}

int other_end(const EdgeConnectivity& ec, int e, int v) {
  return ec.edges[e][0] == v ? ec.edges[e][1] : ec.edges[e][0];
}

/// Closed genus 0: shortest path between two far-apart vertices (double sweep), >= 2 edges.
std::vector<char> genus0_cut(const TriMesh& mesh, const EdgeConnectivity& ec, const EdgeGraph& g) {
  const int nv = mesh.num_vertices();
  std::vector<double> dist;
  std::vector<int> parent;
  auto farthest = [&](int from) {
    dijkstra(g, {from}, dist, parent, [](int) { return false; });
    int best = from;
    for (int v = 0; v < nv; ++v)
      if (dist[v] < kInf && dist[v] > dist[best]) best = v;
    return best;
  };
  const int b = farthest(mesh.faces[0][0]);
  const int a = farthest(b);  // dist/parent now rooted at b
  std::vector<char> cut(ec.num_edges(), 0);
  int path_edges = 0;
  for (int v = a; parent[v] >= 0; v = other_end(ec, parent[v], v)) {
    cut[parent[v]] = 1;
    ++path_edges;
  }
  // A boundary of fewer than 4 wedges cannot be mapped onto the square: lengthen the slit.
  for (int tip = a; path_edges < 2;) {
    int next = -1;
    for (int k = g.offsets[tip]; k < g.offsets[tip + 1] && next < 0; ++k)
      if (!cut[g.edge[k]]) {
        bool fresh = true;  // the new end must not already be on the path
        for (int j = g.offsets[g.nbr[k]]; j < g.offsets[g.nbr[k] + 1]; ++j) fresh &= !cut[g.edge[j]];
        if (fresh) next = k;
      }
    if (next < 0) break;
    cut[g.edge[next]] = 1;
    tip = g.nbr[next];
    ++path_edges;
  }
  return cut;
}

/// True if every vertex of \p g is reachable from vertex 0 (an isolated vertex makes it false).
bool connected_by_edges(const EdgeGraph& g) {
  const int nv = static_cast<int>(g.offsets.size()) - 1;
  if (nv <= 1) return true;
  std::vector<char> seen(nv, 0);
  std::vector<int> stack{0};
  seen[0] = 1;
  int count = 1;
  while (!stack.empty()) {
    const int v = stack.back();
    stack.pop_back();
    for (int k = g.offsets[v]; k < g.offsets[v + 1]; ++k)
      if (!seen[g.nbr[k]]) {
        seen[g.nbr[k]] = 1;
        ++count;
        stack.push_back(g.nbr[k]);
      }
  }
  return count == nv;
}

}  // namespace

EdgeGraph build_edge_graph(const TriMesh& mesh, const EdgeConnectivity& ec) {
  EdgeGraph g;
  const int nv = mesh.num_vertices(), ne = ec.num_edges();
  g.offsets.assign(nv + 1, 0);
  for (const auto& e : ec.edges) {
    ++g.offsets[e[0] + 1];
    ++g.offsets[e[1] + 1];
  }
  for (int v = 0; v < nv; ++v) g.offsets[v + 1] += g.offsets[v];
  g.nbr.resize(g.offsets[nv]);
  g.edge.resize(g.offsets[nv]);
  g.length.resize(ne);
  std::vector<int> fill(g.offsets.begin(), g.offsets.end() - 1);
  for (int e = 0; e < ne; ++e) {
    const int a = ec.edges[e][0], b = ec.edges[e][1];
    g.length[e] = (mesh.positions[a] - mesh.positions[b]).norm();
    g.nbr[fill[a]] = b;
    g.edge[fill[a]++] = e;
    g.nbr[fill[b]] = a;
    g.edge[fill[b]++] = e;
  }
  return g;
}

std::vector<char> initial_cut(const TriMesh& mesh, const EdgeConnectivity& ec, const EdgeGraph& g) {
  const int nv = mesh.num_vertices(), nf = mesh.num_faces(), ne = ec.num_edges();
  if (nf == 0) throw TopologyError("initial_cut: the mesh has no faces");
  // A closed connected surface with Euler characteristic 2 (genus 0): the cut graph of steps 1-3
  // is a spanning tree of the vertices (E - F + 1 = V - 1 edges left by the face tree, no cycle),
  // which the pruning removes entirely; step 4 decides directly.
  bool closed = true;
  for (int e = 0; e < ne && closed; ++e) closed = !ec.is_boundary(e);
  if (closed && nv - ne + nf == 2 && connected_by_edges(g)) return genus0_cut(mesh, ec, g);

  // 1. Shortest-path forest T rooted at the boundary (or at one base vertex of a closed surface).
  std::vector<int> sources;
  std::vector<char> on_boundary(nv, 0);
  for (int e = 0; e < ne; ++e)
    if (ec.is_boundary(e)) on_boundary[ec.edges[e][0]] = on_boundary[ec.edges[e][1]] = 1;
  for (int v = 0; v < nv; ++v)
    if (on_boundary[v]) sources.push_back(v);
  if (sources.empty()) sources.push_back(mesh.faces[0][0]);
  std::vector<double> dist;
  std::vector<int> parent;
  dijkstra(g, sources, dist, parent, [](int) { return false; });
  std::vector<char> in_tree(ne, 0);
  for (int v = 0; v < nv; ++v)
    if (parent[v] >= 0) in_tree[parent[v]] = 1;

  // 2. Face peeling: a spanning tree of the faces (Kruskal) across interior edges. Non-tree edges
  //    with the longest loops (dist(a) + len + dist(b)) are crossed first, so the edges left over
  //    close the shortest loops; T edges are crossed only if nothing else connects the faces.
  // Sort keys: T edges last, then by decreasing loop length (ties by edge id, for determinism).
  std::vector<std::pair<double, int>> order;
  order.reserve(ne);
  for (int e = 0; e < ne; ++e)
    if (ec.edge_faces[e].size() == 2) {
      const double loop = dist[ec.edges[e][0]] + dist[ec.edges[e][1]] + g.length[e];
      order.push_back({in_tree[e] ? kInf : -loop, e});
    }
  std::sort(order.begin(), order.end());
  UnionFind faces_uf(nf);
  std::vector<char> in_graph(ne, 1);  // the cut graph: every edge the face tree does not cross
  for (const auto& [key, e] : order)
    if (faces_uf.unite(ec.edge_faces[e][0], ec.edge_faces[e][1])) in_graph[e] = 0;

  // 3. Dangling-edge pruning.
  std::vector<int> valence(nv, 0);
  for (int e = 0; e < ne; ++e)
    if (in_graph[e]) ++valence[ec.edges[e][0]], ++valence[ec.edges[e][1]];
  std::vector<int> stack;
  for (int v = 0; v < nv; ++v)
    if (valence[v] == 1) stack.push_back(v);
  while (!stack.empty()) {
    const int v = stack.back();
    stack.pop_back();
    if (valence[v] != 1) continue;
    for (int k = g.offsets[v]; k < g.offsets[v + 1]; ++k) {
      const int e = g.edge[k];
      if (!in_graph[e] || ec.is_boundary(e)) continue;
      in_graph[e] = 0;
      --valence[v];
      if (--valence[g.nbr[k]] == 1) stack.push_back(g.nbr[k]);
      break;
    }
  }
  std::vector<char> cut(ne, 0);
  bool any = false, boundary = false;
  for (int e = 0; e < ne; ++e) {
    if (ec.is_boundary(e)) {
      boundary = true;
      continue;
    }
    cut[e] = in_graph[e];
    any |= cut[e] != 0;
  }
  // 4. Closed genus 0: the pruned graph is empty.
  if (!any && !boundary) return genus0_cut(mesh, ec, g);
  return cut;
}

SlicedDisk slice_along_cut(const TriMesh& mesh, const EdgeConnectivity& ec,
                           const std::vector<char>& cut) {
  const int nf = mesh.num_faces(), ne = ec.num_edges();
  auto corner_of = [&](int f, int v) {
    const Face& t = mesh.faces[f];
    return 3 * f + (t[0] == v ? 0 : t[1] == v ? 1 : 2);
  };
  // Corners glued across every uncut interior edge belong to the same wedge.
  UnionFind uf(3 * nf);
  for (int e = 0; e < ne; ++e) {
    if (ec.edge_faces[e].size() != 2 || cut[e]) continue;
    const int f1 = ec.edge_faces[e][0], f2 = ec.edge_faces[e][1];
    for (int v : ec.edges[e]) uf.unite(corner_of(f1, v), corner_of(f2, v));
  }
  SlicedDisk out;
  std::vector<int> wedge_of_root(3 * static_cast<size_t>(nf), -1);
  out.disk.faces.resize(nf);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int r = uf.find(3 * f + k);
      if (wedge_of_root[r] < 0) {
        wedge_of_root[r] = static_cast<int>(out.wedge_vertex.size());
        out.wedge_vertex.push_back(mesh.faces[f][k]);
        out.disk.positions.push_back(mesh.positions[mesh.faces[f][k]]);
      }
      out.disk.faces[f][k] = wedge_of_root[r];
    }
  // Boundary half-edges of the disk, and the single loop they must form.
  const int nw = static_cast<int>(out.wedge_vertex.size());
  std::vector<int> next(nw, -1);
  long num_boundary = 0;
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int e = ec.face_edges[f][k];
      if (!(ec.is_boundary(e) || cut[e])) continue;
      const int a = out.disk.faces[f][k], b = out.disk.faces[f][(k + 1) % 3];
      if (next[a] >= 0)
        throw TopologyError("slice_along_cut: the sliced mesh is pinched at vertex " +
                            std::to_string(out.wedge_vertex[a]) + " (not a disk)");
      next[a] = b;
      ++num_boundary;
    }
  const long chi = nw - (3L * nf + num_boundary) / 2 + nf;
  if (num_boundary == 0 || chi != 1)
    throw TopologyError("slice_along_cut: the sliced mesh is not a disk (Euler characteristic " +
                        std::to_string(chi) + ", " + std::to_string(num_boundary) +
                        " boundary edges)");
  int start = 0;
  while (next[start] < 0) ++start;
  for (int w = start;;) {
    out.boundary_loop.push_back(w);
    w = next[w];
    if (w < 0) throw TopologyError("slice_along_cut: the boundary of the sliced mesh is open");
    if (w == start) break;
    if (static_cast<long>(out.boundary_loop.size()) > num_boundary) break;
  }
  if (static_cast<long>(out.boundary_loop.size()) != num_boundary)
    throw TopologyError("slice_along_cut: the sliced mesh has more than one boundary loop");
  return out;
}

std::vector<char> cut_vertices(const TriMesh& mesh, const EdgeConnectivity& ec,
                               const std::vector<char>& cut) {
  std::vector<char> on(mesh.num_vertices(), 0);
  for (int e = 0; e < ec.num_edges(); ++e)
    if (cut[e] || ec.is_boundary(e)) on[ec.edges[e][0]] = on[ec.edges[e][1]] = 1;
  return on;
}

std::vector<int> shortest_path_to_cut(const EdgeGraph& g, const std::vector<char>& on_cut,
                                      int from) {
  if (on_cut[from]) return {};
  std::vector<double> dist;
  std::vector<int> parent;
  const int hit = dijkstra(g, {from}, dist, parent, [&](int v) { return on_cut[v] != 0; });
  if (hit < 0)
    throw TopologyError("shortest_path_to_cut: no cut vertex is reachable from vertex " +
                        std::to_string(from));
  std::vector<int> path;
  for (int v = hit; parent[v] >= 0;) {
    const int e = parent[v];
    path.push_back(e);
    // Walk back towards `from` through the adjacency of v.
    int u = -1;
    for (int k = g.offsets[v]; k < g.offsets[v + 1]; ++k)
      if (g.edge[k] == e) u = g.nbr[k];
    v = u;
  }
  return path;
}

std::vector<double> distance_to_cut(const EdgeGraph& g, const std::vector<char>& on_cut) {
  std::vector<int> sources;
  for (size_t v = 0; v < on_cut.size(); ++v)
    if (on_cut[v]) sources.push_back(static_cast<int>(v));
  std::vector<double> dist;
  std::vector<int> parent;
  dijkstra(g, sources, dist, parent, [](int) { return false; });
  return dist;
}

double cut_length(const EdgeGraph& g, const std::vector<char>& cut) {
  double len = 0;
  for (size_t e = 0; e < cut.size(); ++e)
    if (cut[e]) len += g.length[e];
  return len;
}

}  // namespace adaptex
