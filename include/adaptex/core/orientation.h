#pragma once
/// \file orientation.h
/// Consistent face winding: two faces that share an edge are consistently oriented when they
/// traverse it in opposite directions. Scans and sculpted meshes sometimes mix windings; a layout
/// needs one winding per surface (the sliced disk of param/cut.h has one boundary loop only then),
/// so the readers (io/mesh_io.h) and unwrap() make the winding consistent first.
#include <vector>

#include "adaptex/core/mesh.h"
#include "adaptex/core/topology.h"

namespace adaptex {

/// Which faces to reverse so that every orientable surface piece has one winding.
struct FaceOrientation {
  std::vector<char> flip;           ///< F: 1 = reverse this face (swap corners 1 and 2).
  std::vector<char> non_orientable; ///< F: 1 = the face lies on a non-orientable piece (never flipped).
  int num_flipped = 0;              ///< Faces with flip = 1.
  int num_non_orientable_faces = 0; ///< Faces with non_orientable = 1.
};

/// Consistent winding by breadth-first propagation across edges shared by exactly two faces
/// (a non-manifold edge does not propagate). In every piece connected that way, the winding of the
/// larger part (ties: the part of the piece's lowest face) is kept and the other part is flipped,
/// so a consistently wound mesh gets no flips. A piece where the propagation meets itself with the
/// opposite winding is non-orientable (a Möbius band): none of its faces is flipped. O(F).
/// \pre face indices are in range
/// \throw nothing beyond std::bad_alloc
FaceOrientation orient_faces(const TriMesh& mesh);
/// As above with the edges already built. \pre \p ec = build_edges(mesh) \throw as above
FaceOrientation orient_faces(const TriMesh& mesh, const EdgeConnectivity& ec);

/// Reverses the faces with orientation.flip set (swaps their corners 1 and 2).
/// \pre orientation.flip.size() == mesh.faces.size()
/// \throw nothing
void apply_orientation(TriMesh& mesh, const FaceOrientation& orientation);

}  // namespace adaptex
