#pragma once
/// \file cut.h
/// Thesis §3.2 "Topological surgery", after Gu, Gortler and Hoppe 2002 ("Geometry images", §3):
/// an initial cut graph by face peeling (a dual spanning tree of faces; the edges it does not cross
/// form the cut) with dangling-edge pruning, a short cut for closed genus-0 surfaces, slicing along
/// the cut (cut vertices are duplicated into wedges), and the shortest paths that the iterative
/// cut augmentation adds (see src/param/unwrap_chart.cpp). docs/surgery.md describes the algorithm and its choices.
///
/// A *cut* is a per-edge flag vector indexed like EdgeConnectivity::edges (1 = the edge is cut).
/// Boundary edges of the input are never flagged: they are open already.
#include <vector>

#include "adaptex/core/mesh.h"
#include "adaptex/core/topology.h"

namespace adaptex {

/// Vertex -> (neighbour, edge) adjacency in CSR form, with edge lengths, for graph searches.
struct EdgeGraph {
  std::vector<int> offsets;      ///< V+1 offsets into nbr / edge.
  std::vector<int> nbr;          ///< Neighbour vertex of each adjacency entry.
  std::vector<int> edge;         ///< Edge id (into EdgeConnectivity::edges) of each entry.
  std::vector<double> length;    ///< E: 3-D length of every edge.
};

/// Builds the adjacency of \p ec. O(V + E).
EdgeGraph build_edge_graph(const TriMesh& mesh, const EdgeConnectivity& ec);

/// Initial cut of one connected manifold component (GGH 2002 §3.1, with the loop-length ordering
/// of Erickson & Whittlesey 2005 so that the cut loops are short):
///  1. shortest-path forest T from a base vertex (closed surface) or from all boundary vertices;
///  2. face peeling: a spanning tree of the faces across non-T interior edges, longest loops first
///     (the edges not crossed form the cut graph, together with T and the boundary);
///  3. dangling-edge pruning: repeatedly drop cut edges with an endpoint of cut valence 1
///     (boundary edges count in the valence and are never dropped, so the result links all loops);
///  4. closed genus 0 (nothing left): the shortest path between two far-apart vertices (double
///     Dijkstra sweep: the farthest vertex b from any vertex, then the farthest a from b).
/// Slicing along the returned cut yields a topological disk.
/// \pre mesh is connected and manifold, \p ec = build_edges(mesh), \p graph = build_edge_graph()
/// \return E flags (1 = cut edge); original boundary edges are 0
/// \throw TopologyError the mesh has no faces
std::vector<char> initial_cut(const TriMesh& mesh, const EdgeConnectivity& ec,
                              const EdgeGraph& graph);

/// A disk produced by slicing a mesh along a cut.
struct SlicedDisk {
  TriMesh disk;                    ///< Positions per wedge; faces parallel to the input's faces.
  std::vector<int> wedge_vertex;   ///< Disk vertex -> input vertex (the id it keeps).
  std::vector<int> boundary_loop;  ///< The disk boundary as disk-vertex ids, interior on the left
                                   ///< (in the winding of the faces).
};

/// Slices \p mesh along \p cut: every vertex becomes one wedge per fan sector between cut/boundary
/// edges (a vertex of cut valence k >= 1 that is not on the original boundary becomes k wedges).
/// Checks that the result is a disk (Euler characteristic 1, exactly one boundary loop).
/// \pre \p ec = build_edges(mesh), cut.size() == E
/// \throw TopologyError the sliced mesh is not a topological disk (the message says why)
SlicedDisk slice_along_cut(const TriMesh& mesh, const EdgeConnectivity& ec,
                           const std::vector<char>& cut);

/// Per-vertex flag: the vertex lies on the cut or on the original boundary.
std::vector<char> cut_vertices(const TriMesh& mesh, const EdgeConnectivity& ec,
                               const std::vector<char>& cut);

/// Shortest path (Dijkstra on the mesh edges, 3-D edge length) from \p from to the nearest vertex
/// on the cut or boundary (GGH 2002 cut augmentation). The path touches the cut only at its last
/// vertex, so adding it keeps the sliced mesh a disk.
/// \return the edge ids of the path (empty if \p from already lies on the cut)
/// \throw TopologyError there is no cut/boundary vertex reachable from \p from
std::vector<int> shortest_path_to_cut(const EdgeGraph& graph, const std::vector<char>& on_cut,
                                      int from);

/// Geodesic (Dijkstra) distance of every vertex to the nearest vertex flagged in \p on_cut
/// (+inf where unreachable).
std::vector<double> distance_to_cut(const EdgeGraph& graph, const std::vector<char>& on_cut);

/// Total 3-D length of the flagged edges.
double cut_length(const EdgeGraph& graph, const std::vector<char>& cut);

}  // namespace adaptex
