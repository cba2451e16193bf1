#pragma once
/// \file pinched.h
/// Splitting pinched vertices: a vertex where several separate fans of faces meet (two parts of a
/// boundary touching at one point, or two surfaces touching at one point) becomes one vertex per
/// fan, all at the same position. The result has the topology that analyze_topology() reports
/// (topology.h: components, loops and genus are those of the split surface). Common in scans and
/// sculpted meshes and harmless for a layout: the copies keep the exact position, so nothing moves.
#include <vector>

#include "adaptex/core/mesh.h"

namespace adaptex {

/// A mesh with its pinched vertices split.
struct PinchedSplit {
  TriMesh mesh;                    ///< Same faces (same order); copies appended after the input vertices.
  std::vector<int> vertex_source;  ///< V': input vertex of every output vertex (identity for the first V).
  int pinched_vertices = 0;        ///< Input vertices with more than one fan.
  int added_vertices = 0;          ///< Copies added (fans beyond the first, over all pinched vertices).
};

/// Splits every pinched vertex: its first fan (VertexFans order: the fan of its first corner) keeps
/// the vertex id, each further fan gets a new vertex with a bit-identical position. Fans are the
/// corner groups of build_vertex_fans(), i.e. connected through edges shared by two or more faces,
/// so a non-manifold edge is not split (that is the job of the mesh repair, io/mesh_io.h).
/// O(F α(F)).
/// \pre face indices are in range
/// \throw nothing
PinchedSplit split_pinched_vertices(const TriMesh& mesh);

}  // namespace adaptex
