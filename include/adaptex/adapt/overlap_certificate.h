#pragma once
/// \file overlap_certificate.h
/// A linear-time proof that a flip-free remap of a layout has no overlapping UV triangles, so that
/// safe_remap() (remap.h) needs the O(F log F) pair search (count_overlapping_triangles) only when the
/// proof fails.
///
/// The argument: let a chart be an oriented triangle mesh (every UV edge in one or two faces, the two
/// faces of an interior edge ordering it oppositely, every face of the same orientation, every
/// wedge on 0 or 2 boundary edges; "chart" here is a connected piece: faces joined by shared wedges). Map it by a piecewise-linear map that keeps every face's
/// orientation (no flip, no degenerate face). For a point p off the image of the boundary, the number
/// of faces covering p is the winding number of the image of the boundary cycle around p (the
/// argument principle for locally injective maps). If the images of the boundary loops are simple
/// closed polygons that pairwise do not touch, and the chart is connected, that number is at most 1
/// (Meisters & Olech, "Locally one-to-one mappings and a classical theorem on schlicht functions",
/// Duke Math. J. 30, 1963, for the disk; the same covering argument for any compact connected surface),
/// so the chart does not overlap itself. Charts whose images lie in pairwise disjoint boxes do not
/// overlap each other. Both tests are conservative: a touching pair of boundary edges, or boxes that
/// touch, make certifies() answer false (then count the pairs).
#include <vector>

#include "adaptex/core/parameterization.h"

namespace adaptex {

/// The input side of the certificate, built once per layout (O(F log F) for the edge table).
class OverlapCertificate {
 public:
  /// \param before the layout that will be remapped (its faces and charts are the after-layout's)
  /// \param min_area UV area at or below which a face counts as degenerate (SafeRemapOptions::min_area)
  /// \throw InvalidInputError a face refers to a wedge outside before.uv
  OverlapCertificate(const Parameterization& before, double min_area);

  /// False when \p before is not a set of oriented charts in the sense above (an edge in 3 faces, a
  /// pinched boundary wedge, a degenerate face, a chart with faces of both orientations): then
  /// certifies() is always false.
  bool applicable() const { return applicable_; }

  /// True only if \p after (the same faces as `before`, every face keeping its orientation with UV area
  /// above min_area) has no pair of UV triangles whose interiors overlap. False means "not proven".
  /// \pre after.uv_faces == before.uv_faces (the caller checked flips and degenerate faces)
  /// \throw InvalidInputError after has another number of wedges or faces than before
  bool certifies(const Parameterization& after) const;

 private:
  struct Edge {
    int a, b, chart;
  };
  bool applicable_ = false;
  size_t wedges_ = 0, faces_ = 0;
  int pieces_ = 0;                ///< Components of faces joined by shared wedges.
  std::vector<int> wedge_chart_;  ///< Piece of every wedge (-1: in no face).
  std::vector<Edge> boundary_;    ///< UV boundary edges (in one face only), with their piece.
};

}  // namespace adaptex
