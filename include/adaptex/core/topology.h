#pragma once
/// \file topology.h
/// Edge connectivity and topological invariants of a triangle mesh: components, boundary loops,
/// Euler characteristic, genus, non-manifold edges and vertices.
#include <span>
#include <vector>

#include "adaptex/core/mesh.h"

namespace adaptex {

/// The faces around every edge in compressed (CSR) form: `lists[e]` is a span of the faces of
/// edge e, in increasing order. One allocation for all edges (a vector per edge made build_edges()
/// cost 86 ns per face on venus, most of it in the allocator).
class EdgeFaceLists {
 public:
  /// Faces of edge \p e. \pre 0 <= e < size()
  std::span<const int> operator[](int e) const {
    return {faces_.data() + offsets_[e], static_cast<size_t>(offsets_[e + 1] - offsets_[e])};
  }
  /// Number of edges E.
  int size() const { return static_cast<int>(offsets_.size()) - 1; }
  /// Iterates the edges' spans in edge order (range-for over all edges).
  class Iterator {
   public:
    Iterator(const EdgeFaceLists* l, int e) : l_(l), e_(e) {}
    std::span<const int> operator*() const { return (*l_)[e_]; }
    Iterator& operator++() { ++e_; return *this; }
    bool operator!=(const Iterator& o) const { return e_ != o.e_; }
   private:
    const EdgeFaceLists* l_;
    int e_;
  };
  Iterator begin() const { return {this, 0}; }
  Iterator end() const { return {this, size()}; }
  /// Building (build_edges()): reserve(), then for every edge in order its faces, then end_edge().
  void reserve(size_t edges, size_t faces) { offsets_.reserve(edges + 1); faces_.reserve(faces); }
  void add_face(int f) { faces_.push_back(f); }
  void end_edge() { offsets_.push_back(static_cast<int>(faces_.size())); }

 private:
  std::vector<int> offsets_{0};  ///< E+1 offsets into faces_.
  std::vector<int> faces_;       ///< The lists, edge by edge.
};

/// Undirected edges of a mesh, with the faces on each side.
struct EdgeConnectivity {
  std::vector<std::array<int, 2>> edges;  ///< E edges as (a, b) with a < b.
  std::vector<std::array<int, 3>> face_edges;  ///< F: edge id of (v0,v1), (v1,v2), (v2,v0).
  EdgeFaceLists edge_faces;  ///< E: incident faces (1 = boundary, >2 = non-manifold).

  int num_edges() const { return static_cast<int>(edges.size()); }
  bool is_boundary(int e) const { return edge_faces[e].size() == 1; }
};

/// Builds the edge list. O(F) plus small per-vertex sorts (bucket_edges()). \pre face indices are in range.
EdgeConnectivity build_edges(const TriMesh& mesh);

/// The face sides of a triangle list grouped by undirected edge, in compressed form: the side of face
/// f from corner k to corner k + 1, joining a = min and b = max of its two indices, is a record in
/// a's bucket. Buckets are in increasing a, records in a bucket in increasing b, and the records of
/// one edge in increasing face (then corner) order: walking the buckets visits the edges sorted by
/// (a, b), as sorting (a, b, face) keys would, in O(F) plus the sorts of the (small) buckets.
struct EdgeBuckets {
  struct Record {
    int b, face, corner;
  };
  std::vector<int> start;       ///< V+1 offsets into records (V = 1 + the largest index).
  std::vector<Record> records;  ///< 3F records, bucket by bucket.
};
/// \pre every index of \p faces is >= 0 and < num_vertices (num_vertices may be larger than needed).
EdgeBuckets bucket_edges(const std::vector<Face>& faces, int num_vertices);

/// Vertex -> incident faces, in compressed (CSR) form.
struct VertexFaces {
  std::vector<int> offsets;  ///< V+1 offsets into faces.
  std::vector<int> faces;    ///< Incident face ids, vertex by vertex.
};
VertexFaces build_vertex_faces(const TriMesh& mesh);
/// The same for a triangle list over \p num_vertices indices (e.g. a layout's UV faces over its
/// wedges): faces in increasing order per vertex, a face listed once per corner at the vertex.
/// \pre every index of \p faces is >= 0 and < num_vertices
VertexFaces build_vertex_faces(const std::vector<Face>& faces, int num_vertices);

/// Face fans around vertices: the corners (f, k) of a vertex that are connected through edges shared
/// by two or more faces form one fan. A vertex of a manifold mesh has exactly one fan (a disk or a
/// half-disk); a *pinched* vertex has several (two surfaces, or two parts of one boundary, touching at
/// a single point).
struct VertexFans {
  std::vector<int> corner_fan;  ///< 3F: fan id of corner 3f+k (the corner of mesh.faces[f][k]).
  std::vector<int> fan_vertex;  ///< Fans: the vertex of each fan. Fans of a vertex are numbered in
                                ///< order of their first corner, so its first fan has the lowest id.
  int num_fans() const { return static_cast<int>(fan_vertex.size()); }
};

/// Groups the corners of every vertex into fans. O(F α(F)).
/// \pre \p ec = build_edges(mesh)
VertexFans build_vertex_fans(const TriMesh& mesh, const EdgeConnectivity& ec);

/// Topology of one connected component, counted on the surface whose pinched vertices are split
/// (one vertex per fan), so that euler == 2 - 2 genus - boundary_loops holds on orientable components.
struct ComponentTopology {
  int faces = 0;     ///< Faces of the component.
  int vertices = 0;  ///< Vertex fans of the component (= vertices when none is pinched).
  int edges = 0;     ///< Edges of the component.
  int euler = 0;     ///< vertices - edges + faces.
  int genus = 0;     ///< (2 - euler - boundary_loops) / 2, clamped at 0 (a non-orientable piece).
  /// Its faces can be wound consistently (core/orientation.h); genus is meaningful only then.
  /// True also when the mesh mixes windings: see consistently_oriented.
  bool orientable = true;
  /// Every edge shared by two faces of the component is traversed in opposite directions.
  bool consistently_oriented = true;
  std::vector<int> loops;  ///< Indices into MeshTopology::boundary_loops of its boundary loops.
};

/// Topological summary of a mesh.
struct MeshTopology {
  int num_vertices = 0, num_faces = 0, num_edges = 0;
  /// Connected components: faces are connected through shared edges, so a pinched vertex does not
  /// join two surfaces that only touch there (it belongs to each of them).
  int num_components = 0;
  std::vector<int> face_component;       ///< F: component of every face.
  std::vector<int> component_genus;      ///< Genus of each component (from its Euler characteristic).
  std::vector<int> component_loops;      ///< Number of boundary loops of each component.
  std::vector<ComponentTopology> components;  ///< Per component: counts, Euler characteristic, loops.
  /// Boundary loops as vertex cycles, traced fan by fan: from a boundary edge to the other boundary
  /// edge of the same fan at its end vertex, so a loop that passes twice through a pinched vertex
  /// is followed correctly and the face winding does not matter. A loop is listed in the direction
  /// of the winding of the face of its first edge (interior on the left on oriented meshes).
  std::vector<std::vector<int>> boundary_loops;
  std::vector<int> loop_component;       ///< Per boundary loop: its component.
  int euler_characteristic = 0;          ///< V - E + F over the whole mesh (V: vertices, not fans).
  int num_unreferenced_vertices = 0;     ///< Vertices used by no face.
  std::vector<std::array<int, 2>> nonmanifold_edges;  ///< Edges with more than two faces.
  std::vector<int> nonmanifold_vertices; ///< Vertices with more than one fan (pinched vertices).
  bool is_manifold() const { return nonmanifold_edges.empty() && nonmanifold_vertices.empty(); }
  int total_genus() const;
  int total_loops() const { return static_cast<int>(boundary_loops.size()); }
};

/// Computes the topological summary. Components, loops and genus are those of the surface with its
/// pinched vertices split (see ComponentTopology); on meshes with non-manifold edges they are only
/// indicative.
/// \pre face indices are in range
MeshTopology analyze_topology(const TriMesh& mesh);

}  // namespace adaptex
