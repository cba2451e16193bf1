#include "adaptex/core/topology.h"

#include <algorithm>
#include <numeric>
#include <unordered_map>

namespace adaptex {

namespace {

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(int a, int b) { parent[find(a)] = find(b); }
};

}  // namespace

EdgeConnectivity build_edges(const TriMesh& mesh) {
  const int nf = mesh.num_faces();
  // Sort (a, b, face, corner) records to group the corners of each undirected edge.
  struct Rec {
    int a, b, face, corner;
  };
  std::vector<Rec> recs;
  recs.reserve(static_cast<size_t>(nf) * 3);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      int a = mesh.faces[f][k], b = mesh.faces[f][(k + 1) % 3];
      if (a > b) std::swap(a, b);
      recs.push_back({a, b, f, k});
    }
  std::sort(recs.begin(), recs.end(), [](const Rec& x, const Rec& y) {
    return x.a != y.a ? x.a < y.a : x.b != y.b ? x.b < y.b : x.face < y.face;
  });
  EdgeConnectivity ec;
  ec.face_edges.assign(nf, {-1, -1, -1});
  for (size_t i = 0; i < recs.size();) {
    size_t j = i;
    const int e = static_cast<int>(ec.edges.size());
    ec.edges.push_back({recs[i].a, recs[i].b});
    ec.edge_faces.emplace_back();
    for (; j < recs.size() && recs[j].a == recs[i].a && recs[j].b == recs[i].b; ++j) {
      ec.face_edges[recs[j].face][recs[j].corner] = e;
      ec.edge_faces[e].push_back(recs[j].face);
    }
    i = j;
  }
  return ec;
}

VertexFaces build_vertex_faces(const TriMesh& mesh) {
  VertexFaces vf;
  const int nv = mesh.num_vertices();
  vf.offsets.assign(nv + 1, 0);
  for (const Face& t : mesh.faces)
    for (int v : t) ++vf.offsets[v + 1];
  for (int v = 0; v < nv; ++v) vf.offsets[v + 1] += vf.offsets[v];
  vf.faces.resize(vf.offsets[nv]);
  std::vector<int> fill(vf.offsets.begin(), vf.offsets.end() - 1);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int v : mesh.faces[f]) vf.faces[fill[v]++] = f;
  return vf;
}

int MeshTopology::total_genus() const {
  int g = 0;
  for (int x : component_genus) g += x;
  return g;
}

MeshTopology analyze_topology(const TriMesh& mesh) {
  MeshTopology topo;
  const int nv = mesh.num_vertices(), nf = mesh.num_faces();
  topo.num_vertices = nv;
  topo.num_faces = nf;
  const EdgeConnectivity ec = build_edges(mesh);
  topo.num_edges = ec.num_edges();

  // Components through shared vertices.
  UnionFind uf(nv);
  std::vector<char> used(nv, 0);
  for (const Face& t : mesh.faces) {
    uf.unite(t[0], t[1]);
    uf.unite(t[1], t[2]);
    for (int v : t) used[v] = 1;
  }
  std::vector<int> root_to_comp(nv, -1);
  std::vector<int> vertex_comp(nv, -1);
  for (int v = 0; v < nv; ++v) {
    if (!used[v]) {
      ++topo.num_unreferenced_vertices;
      continue;
    }
    int r = uf.find(v);
    if (root_to_comp[r] < 0) root_to_comp[r] = topo.num_components++;
    vertex_comp[v] = root_to_comp[r];
  }
  topo.face_component.resize(nf);
  for (int f = 0; f < nf; ++f) topo.face_component[f] = vertex_comp[mesh.faces[f][0]];

  // Non-manifold edges.
  for (int e = 0; e < ec.num_edges(); ++e)
    if (ec.edge_faces[e].size() > 2) topo.nonmanifold_edges.push_back(ec.edges[e]);

  // Non-manifold vertices: the faces around a vertex must form one fan (connected across edges).
  const VertexFaces vf = build_vertex_faces(mesh);
  std::unordered_map<int, int> other_to_face;
  for (int v = 0; v < nv; ++v) {
    const int begin = vf.offsets[v], end = vf.offsets[v + 1];
    if (end - begin <= 1) continue;
    UnionFind local(end - begin);
    other_to_face.clear();
    for (int k = begin; k < end; ++k) {
      const Face& t = mesh.faces[vf.faces[k]];
      for (int c = 0; c < 3; ++c) {
        if (t[c] == v) continue;
        auto [it, inserted] = other_to_face.emplace(t[c], k - begin);
        if (!inserted) local.unite(it->second, k - begin);
      }
    }
    int pieces = 0;
    for (int k = 0; k < end - begin; ++k) pieces += local.find(k) == k;
    if (pieces > 1) topo.nonmanifold_vertices.push_back(v);
  }

  // Boundary loops: follow directed boundary half-edges (a -> b as seen by the single face).
  std::unordered_multimap<int, int> next_of;  // a -> b
  for (int e = 0; e < ec.num_edges(); ++e) {
    if (!ec.is_boundary(e)) continue;
    const Face& t = mesh.faces[ec.edge_faces[e][0]];
    for (int c = 0; c < 3; ++c) {
      const int a = t[c], b = t[(c + 1) % 3];
      if (std::min(a, b) == ec.edges[e][0] && std::max(a, b) == ec.edges[e][1]) next_of.emplace(a, b);
    }
  }
  while (!next_of.empty()) {
    auto it = next_of.begin();
    const int start = it->first;
    std::vector<int> loop{start};
    int cur = it->second;
    next_of.erase(it);
    while (cur != start) {
      loop.push_back(cur);
      auto nx = next_of.find(cur);
      if (nx == next_of.end()) break;  // open chain: only on non-manifold input
      cur = nx->second;
      next_of.erase(nx);
    }
    topo.boundary_loops.push_back(std::move(loop));
  }

  // Per-component Euler characteristic and genus.
  const int nc = topo.num_components;
  std::vector<long> cv(nc, 0), ce(nc, 0), cf(nc, 0);
  topo.component_loops.assign(nc, 0);
  for (int v = 0; v < nv; ++v)
    if (vertex_comp[v] >= 0) ++cv[vertex_comp[v]];
  for (const auto& e : ec.edges) ++ce[vertex_comp[e[0]]];
  for (int f = 0; f < nf; ++f) ++cf[topo.face_component[f]];
  for (const auto& loop : topo.boundary_loops) ++topo.component_loops[vertex_comp[loop[0]]];
  topo.component_genus.resize(nc);
  long chi_total = 0;
  for (int c = 0; c < nc; ++c) {
    const long chi = cv[c] - ce[c] + cf[c];
    chi_total += chi;
    topo.component_genus[c] = static_cast<int>(std::max(0L, (2 - chi - topo.component_loops[c]) / 2));
  }
  topo.euler_characteristic = static_cast<int>(chi_total);
  return topo;
}

}  // namespace adaptex
