#pragma once
/// \file point_transfer.h
/// Surface points carried from a mesh to a conforming refinement of it (adapt/refine.h: new vertices
/// on the original faces, same surface). The safeguard of adapt/session.h and surface_psnr()
/// (paint/asset_eval.h) keep one fixed set of surface samples; when a re-parameterization refines the
/// mesh, the same 3-D points are found on the refined faces, so the old and the new layout are judged
/// at exactly the same points.
#include <vector>

#include "adaptex/core/mesh.h"
#include "adaptex/paint/signal.h"

namespace adaptex {

/// The points \p pts on \p from, moved to \p to: each point lands on the child face (of its parent
/// face) that contains it, with the child's barycentrics of the same 3-D point (clamped to the child;
/// a parent whose children are all degenerate gives a child's centre).
/// \param parent_face size to.num_faces(): parent_face[c] = the face of \p from that child c lies on
/// \pre every child lies on its parent face (a conforming refinement); every pts[k].face < from.num_faces()
/// \throw InvalidInputError parent_face.size() != to.num_faces() or a parent index out of range
std::vector<SurfacePoint> transfer_points(const std::vector<SurfacePoint>& pts, const TriMesh& from,
                                          const TriMesh& to, const FaceData<int>& parent_face);

}  // namespace adaptex
