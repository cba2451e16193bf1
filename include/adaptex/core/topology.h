#pragma once
/// \file topology.h
/// Edge connectivity and topological invariants of a triangle mesh: components, boundary loops,
/// Euler characteristic, genus, non-manifold edges and vertices.
#include <vector>

#include "adaptex/core/mesh.h"

namespace adaptex {

/// Undirected edges of a mesh, with the faces on each side.
struct EdgeConnectivity {
  std::vector<std::array<int, 2>> edges;  ///< E edges as (a, b) with a < b.
  std::vector<std::array<int, 3>> face_edges;  ///< F: edge id of (v0,v1), (v1,v2), (v2,v0).
  std::vector<std::vector<int>> edge_faces;    ///< E: incident faces (1 = boundary, >2 = non-manifold).

  int num_edges() const { return static_cast<int>(edges.size()); }
  bool is_boundary(int e) const { return edge_faces[e].size() == 1; }
};

/// Builds the edge list. O(F log F). \pre face indices are in range.
EdgeConnectivity build_edges(const TriMesh& mesh);

/// Vertex -> incident faces, in compressed (CSR) form.
struct VertexFaces {
  std::vector<int> offsets;  ///< V+1 offsets into faces.
  std::vector<int> faces;    ///< Incident face ids, vertex by vertex.
};
VertexFaces build_vertex_faces(const TriMesh& mesh);

/// Topological summary of a mesh.
struct MeshTopology {
  int num_vertices = 0, num_faces = 0, num_edges = 0;
  int num_components = 0;                ///< Connected components (through shared vertices).
  std::vector<int> face_component;       ///< F: component of every face.
  std::vector<int> component_genus;      ///< Genus of each component (from its Euler characteristic).
  std::vector<int> component_loops;      ///< Number of boundary loops of each component.
  std::vector<std::vector<int>> boundary_loops;  ///< Boundary loops as vertex cycles.
  int euler_characteristic = 0;          ///< V - E + F over the whole mesh.
  int num_unreferenced_vertices = 0;     ///< Vertices used by no face.
  std::vector<std::array<int, 2>> nonmanifold_edges;  ///< Edges with more than two faces.
  std::vector<int> nonmanifold_vertices; ///< Vertices whose face fan is not a single disk/half-disk.
  bool is_manifold() const { return nonmanifold_edges.empty() && nonmanifold_vertices.empty(); }
  int total_genus() const;
  int total_loops() const { return static_cast<int>(boundary_loops.size()); }
};

/// Computes the topological summary. Boundary loops and genus are only meaningful on manifold meshes.
MeshTopology analyze_topology(const TriMesh& mesh);

}  // namespace adaptex
