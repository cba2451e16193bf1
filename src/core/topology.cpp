#include "adaptex/core/topology.h"

#include <algorithm>
#include <numeric>

#include "adaptex/core/orientation.h"
#include "adaptex/core/union_find.h"

namespace adaptex {

namespace {

/// Corner index 3f+k of vertex v in face f (v must be a corner of f).
int corner_index(const TriMesh& mesh, int f, int v) {
  const Face& t = mesh.faces[f];
  return 3 * f + (t[0] == v ? 0 : t[1] == v ? 1 : 2);
}

}  // namespace

EdgeBuckets bucket_edges(const std::vector<Face>& faces, int num_vertices) {
  // A counting sort by a (stable, so faces stay in increasing order), then a small sort by b within
  // each bucket.
  const int nf = static_cast<int>(faces.size());
  const int nv = num_vertices;
  EdgeBuckets eb;
  eb.start.assign(static_cast<size_t>(nv) + 1, 0);
  for (const Face& t : faces)
    for (int k = 0; k < 3; ++k) ++eb.start[std::min(t[k], t[(k + 1) % 3]) + 1];
  for (int v = 0; v < nv; ++v) eb.start[v + 1] += eb.start[v];
  eb.records.resize(static_cast<size_t>(nf) * 3);
  {
    std::vector<int> fill(eb.start.begin(), eb.start.end() - 1);
    for (int f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) {
        const int a = faces[f][k], b = faces[f][(k + 1) % 3];
        eb.records[fill[std::min(a, b)]++] = {std::max(a, b), f, k};
      }
  }
  using Rec = EdgeBuckets::Record;
  for (int a = 0; a < nv; ++a) {
    const auto first = eb.records.begin() + eb.start[a], last = eb.records.begin() + eb.start[a + 1];
    if (last - first <= 16) {  // insertion sort (stable, no allocation) for the usual small bucket
      for (auto i = first + (first != last); i < last; ++i)
        for (auto j = i; j != first && (j - 1)->b > j->b; --j) std::iter_swap(j - 1, j);
    } else {
      std::stable_sort(first, last, [](const Rec& x, const Rec& y) { return x.b < y.b; });
    }
  }
  return eb;
}

EdgeConnectivity build_edges(const TriMesh& mesh) {
  const int nf = mesh.num_faces();
  int nv = mesh.num_vertices();
  for (const Face& t : mesh.faces)
    for (int v : t) nv = std::max(nv, v + 1);
  const EdgeBuckets eb = bucket_edges(mesh.faces, nv);
  EdgeConnectivity ec;
  ec.face_edges.assign(nf, {-1, -1, -1});
  ec.edges.reserve(static_cast<size_t>(nf) * 3 / 2 + 16);
  ec.edge_faces.reserve(ec.edges.capacity(), 3 * static_cast<size_t>(nf));
  for (int a = 0; a < nv; ++a) {
    const auto first = eb.records.begin() + eb.start[a], last = eb.records.begin() + eb.start[a + 1];
    for (auto i = first; i != last;) {
      const int e = static_cast<int>(ec.edges.size());
      ec.edges.push_back({a, i->b});
      auto j = i;
      for (; j != last && j->b == i->b; ++j) {
        ec.face_edges[j->face][j->corner] = e;
        ec.edge_faces.add_face(j->face);
      }
      ec.edge_faces.end_edge();
      i = j;
    }
  }
  return ec;
}

VertexFaces build_vertex_faces(const TriMesh& mesh) { return build_vertex_faces(mesh.faces, mesh.num_vertices()); }

VertexFaces build_vertex_faces(const std::vector<Face>& faces, int num_vertices) {
  VertexFaces vf;
  const int nv = num_vertices;
  vf.offsets.assign(nv + 1, 0);
  for (const Face& t : faces)
    for (int v : t) ++vf.offsets[v + 1];
  for (int v = 0; v < nv; ++v) vf.offsets[v + 1] += vf.offsets[v];
  vf.faces.resize(vf.offsets[nv]);
  std::vector<int> fill(vf.offsets.begin(), vf.offsets.end() - 1);
  for (int f = 0; f < static_cast<int>(faces.size()); ++f)
    for (int v : faces[f]) vf.faces[fill[v]++] = f;
  return vf;
}

int MeshTopology::total_genus() const {
  int g = 0;
  for (int x : component_genus) g += x;
  return g;
}

VertexFans build_vertex_fans(const TriMesh& mesh, const EdgeConnectivity& ec) {
  const int nf = mesh.num_faces();
  UnionFind corners(3 * nf);
  for (int e = 0; e < ec.num_edges(); ++e) {
    const auto& fs = ec.edge_faces[e];
    for (size_t k = 1; k < fs.size(); ++k)
      for (int v : ec.edges[e]) corners.unite(corner_index(mesh, fs[0], v), corner_index(mesh, fs[k], v));
  }
  VertexFans out;
  out.corner_fan.assign(3 * static_cast<size_t>(nf), -1);
  std::vector<int> fan_of_root(3 * static_cast<size_t>(nf), -1);
  for (int c = 0; c < 3 * nf; ++c) {
    int& fan = fan_of_root[corners.find(c)];
    if (fan < 0) {
      fan = out.num_fans();
      out.fan_vertex.push_back(mesh.faces[c / 3][c % 3]);
    }
    out.corner_fan[c] = fan;
  }
  return out;
}

namespace {

/// Connected components of the faces through edges shared by two or more faces, numbered in the
/// order of the lowest vertex (then fan) they contain. Returns the number of components.
int face_components(const TriMesh& mesh, const EdgeConnectivity& ec, const VertexFans& fans,
                    std::vector<int>& face_component) {
  const int nf = mesh.num_faces();
  UnionFind faces(nf);
  for (const auto& fs : ec.edge_faces)
    for (size_t k = 1; k < fs.size(); ++k) faces.unite(fs[0], fs[k]);
  std::vector<int> fan_face(fans.num_fans(), -1);  // a face of every fan
  for (int c = 0; c < 3 * nf; ++c)
    if (fan_face[fans.corner_fan[c]] < 0) fan_face[fans.corner_fan[c]] = c / 3;
  std::vector<int> order(fans.num_fans());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return fans.fan_vertex[a] < fans.fan_vertex[b]; });
  std::vector<int> root_comp(nf, -1);
  int nc = 0;
  for (int fan : order) {
    int& c = root_comp[faces.find(fan_face[fan])];
    if (c < 0) c = nc++;
  }
  face_component.resize(nf);
  for (int f = 0; f < nf; ++f) face_component[f] = root_comp[faces.find(f)];
  return nc;
}

/// Boundary loops traced fan by fan (see MeshTopology::boundary_loops).
std::vector<std::vector<int>> trace_boundary_loops(const TriMesh& mesh, const EdgeConnectivity& ec,
                                                   const VertexFans& fans,
                                                   std::vector<int>& loop_first_edge) {
  // The (at most two) boundary edges of every fan.
  std::vector<std::array<int, 2>> fan_boundary(fans.num_fans(), {-1, -1});
  for (int e = 0; e < ec.num_edges(); ++e) {
    if (!ec.is_boundary(e)) continue;
    for (int v : ec.edges[e]) {
      auto& slot = fan_boundary[fans.corner_fan[corner_index(mesh, ec.edge_faces[e][0], v)]];
      (slot[0] < 0 ? slot[0] : slot[1]) = e;
    }
  }
  std::vector<std::vector<int>> loops;
  std::vector<char> visited(ec.num_edges(), 0);
  for (int e0 = 0; e0 < ec.num_edges(); ++e0) {
    if (!ec.is_boundary(e0) || visited[e0]) continue;
    visited[e0] = 1;
    const int f0 = ec.edge_faces[e0][0];
    const Face& t = mesh.faces[f0];
    int k = 0;
    while (ec.face_edges[f0][k] != e0) ++k;
    std::vector<int> loop{t[k]};
    int e = e0, cur = t[(k + 1) % 3];
    for (;;) {
      const auto& slot = fan_boundary[fans.corner_fan[corner_index(mesh, ec.edge_faces[e][0], cur)]];
      const int next = slot[0] == e ? slot[1] : slot[0];
      if (next < 0 || next == e0 || visited[next]) break;  // closed (or open on non-manifold input)
      loop.push_back(cur);
      visited[next] = 1;
      e = next;
      cur = ec.edges[e][0] == cur ? ec.edges[e][1] : ec.edges[e][0];
    }
    loops.push_back(std::move(loop));
    loop_first_edge.push_back(e0);
  }
  return loops;
}

}  // namespace

MeshTopology analyze_topology(const TriMesh& mesh) {
  MeshTopology topo;
  const int nv = mesh.num_vertices(), nf = mesh.num_faces();
  topo.num_vertices = nv;
  topo.num_faces = nf;
  const EdgeConnectivity ec = build_edges(mesh);
  topo.num_edges = ec.num_edges();
  const VertexFans fans = build_vertex_fans(mesh, ec);

  // Unreferenced and pinched vertices.
  std::vector<int> vertex_fans(nv, 0);
  for (int v : fans.fan_vertex) ++vertex_fans[v];
  for (int v = 0; v < nv; ++v) {
    topo.num_unreferenced_vertices += vertex_fans[v] == 0;
    if (vertex_fans[v] > 1) topo.nonmanifold_vertices.push_back(v);
  }
  for (int e = 0; e < ec.num_edges(); ++e)
    if (ec.edge_faces[e].size() > 2) topo.nonmanifold_edges.push_back(ec.edges[e]);

  topo.num_components = face_components(mesh, ec, fans, topo.face_component);
  std::vector<int> loop_first_edge;
  topo.boundary_loops = trace_boundary_loops(mesh, ec, fans, loop_first_edge);

  // Per-component counts; vertices are counted as fans (pinched vertices split).
  const int nc = topo.num_components;
  topo.components.assign(nc, {});
  for (int f = 0; f < nf; ++f) ++topo.components[topo.face_component[f]].faces;
  for (int e = 0; e < ec.num_edges(); ++e) ++topo.components[topo.face_component[ec.edge_faces[e][0]]].edges;
  std::vector<char> fan_seen(fans.num_fans(), 0);
  for (int c = 0; c < 3 * nf; ++c) {
    const int fan = fans.corner_fan[c];
    if (!fan_seen[fan]) ++topo.components[topo.face_component[c / 3]].vertices;
    fan_seen[fan] = 1;
  }
  for (size_t l = 0; l < topo.boundary_loops.size(); ++l) {
    const int c = topo.face_component[ec.edge_faces[loop_first_edge[l]][0]];
    topo.loop_component.push_back(c);
    topo.components[c].loops.push_back(static_cast<int>(l));
  }
  const FaceOrientation orientation = orient_faces(mesh, ec);
  for (int f = 0; f < nf; ++f) {
    ComponentTopology& ct = topo.components[topo.face_component[f]];
    ct.orientable = ct.orientable && !orientation.non_orientable[f];
    ct.consistently_oriented = ct.consistently_oriented && !orientation.flip[f] && !orientation.non_orientable[f];
  }
  topo.component_genus.resize(nc);
  topo.component_loops.resize(nc);
  for (int c = 0; c < nc; ++c) {
    ComponentTopology& ct = topo.components[c];
    ct.euler = ct.vertices - ct.edges + ct.faces;
    const int loops = static_cast<int>(ct.loops.size());
    ct.genus = std::max(0, (2 - ct.euler - loops) / 2);
    topo.component_genus[c] = ct.genus;
    topo.component_loops[c] = loops;
  }
  topo.euler_characteristic = (nv - topo.num_unreferenced_vertices) - topo.num_edges + nf;
  return topo;
}

}  // namespace adaptex
