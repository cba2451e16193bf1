/// \file pinched.cpp
/// Splitting pinched vertices into one vertex per face fan (pinched.h).
#include "adaptex/core/pinched.h"

#include <numeric>

#include "adaptex/core/topology.h"

namespace adaptex {

PinchedSplit split_pinched_vertices(const TriMesh& mesh) {
  PinchedSplit out;
  out.mesh = mesh;
  const int nv = mesh.num_vertices();
  out.vertex_source.resize(nv);
  std::iota(out.vertex_source.begin(), out.vertex_source.end(), 0);
  const VertexFans fans = build_vertex_fans(mesh, build_edges(mesh));
  // The first fan of a vertex keeps it; further fans get copies.
  std::vector<int> fan_target(fans.num_fans(), -1);
  std::vector<int> fans_seen(nv, 0);
  for (int fan = 0; fan < fans.num_fans(); ++fan) {
    const int v = fans.fan_vertex[fan];
    if (fans_seen[v]++ == 0) {
      fan_target[fan] = v;
      continue;
    }
    if (fans_seen[v] == 2) ++out.pinched_vertices;
    fan_target[fan] = out.mesh.num_vertices();
    out.mesh.positions.push_back(mesh.positions[v]);
    out.vertex_source.push_back(v);
    ++out.added_vertices;
  }
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) out.mesh.faces[f][k] = fan_target[fans.corner_fan[3 * f + k]];
  return out;
}

}  // namespace adaptex
