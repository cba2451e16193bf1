#pragma once
/// \file overlap_certificate.h
/// O(F) proof that a flip-free remap has no overlapping UV triangles: simple, disjoint boundary images
/// bound the cover by 1 (Meisters & Olech, Duke Math. J. 30, 1963). Else safe_remap() counts pairs.
#include <vector>

#include "adaptex/core/parameterization.h"

namespace adaptex {

/// The input side of the certificate, built once per layout (O(F log F) for the edge table).
class OverlapCertificate {
 public:
  /// \param min_area degenerate-face area (SafeRemapOptions::min_area) \throw InvalidInputError bad wedge id
  OverlapCertificate(const Parameterization& before, double min_area);

  /// False when \p before is not a set of oriented charts: certifies() is then always false.
  bool applicable() const { return applicable_; }

  /// True only if \p after (flip-free) has no overlapping pair of UV triangles; false: not proven.
  /// \pre after.uv_faces == before.uv_faces \throw InvalidInputError other wedge or face counts
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
