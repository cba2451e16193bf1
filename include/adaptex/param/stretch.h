#pragma once
/// \file stretch.h
/// Sander et al. 2001 ("Texture mapping progressive meshes") L2 and L-infinity stretch (thesis
/// §2.1.3), normalized so that 1.0 is ideal, plus other distortion measures.
#include <array>
#include <vector>

#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"

namespace adaptex {

/// Singular values of the Jacobian of the map from the UV triangle to the 3-D triangle.
struct FaceStretch {
  double gamma_max = 0;  ///< Γ, largest singular value (L∞ stretch of the face).
  double gamma_min = 0;  ///< γ, smallest singular value.
  double l2() const;     ///< sqrt((Γ² + γ²) / 2).
};

/// Stretch of one triangle given its 3-D corners and UV corners.
/// Returns +inf singular values for a degenerate or flipped UV triangle.
FaceStretch face_stretch(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec2& t0,
                         const Vec2& t1, const Vec2& t2);

/// Summary metrics of a parameterization.
struct StretchStats {
  double l2 = 0;            ///< √(ΣA₃·L2²/ΣA₃) · √(ΣA₂/ΣA₃): 1.0 is ideal (isometry up to scale).
  double linf = 0;          ///< max_f Γ_f · √(ΣA₂/ΣA₃): 1.0 is ideal.
  double area_distortion = 0;   ///< Area-weighted mean of max(a,1/a), a = (A₂/ΣA₂)/(A₃/ΣA₃).
  double angle_distortion = 0;  ///< Area-weighted mean of Γ/γ (1.0 = conformal).
  int flipped = 0;          ///< UV triangles with negative signed area.
  int degenerate = 0;       ///< UV triangles with (near-)zero area.
};

/// Per-face L2 stretch, normalized like StretchStats::l2 (F values; +inf for flipped/degenerate).
std::vector<double> face_l2_stretch(const TriMesh& mesh, const Parameterization& param);

/// Computes all summary metrics. \pre param.uv_faces.size() == mesh.faces.size()
StretchStats measure_stretch(const TriMesh& mesh, const Parameterization& param);

/// Per-face L2 stretch of a single-chart map given per vertex (disk parameterizations):
/// \p vertex_uv has size V and face f uses mesh.faces[f] as UV indices. Normalized like
/// StretchStats::l2; +inf for flipped/degenerate faces.
std::vector<double> face_l2_stretch(const TriMesh& mesh, const std::vector<Vec2>& vertex_uv);

/// measure_stretch() for a per-vertex UV array (size V, indexed like mesh.positions).
StretchStats measure_stretch(const TriMesh& mesh, const std::vector<Vec2>& vertex_uv);

/// measure_stretch() and face_l2_stretch() of a per-vertex UV array in one pass over the faces (the
/// Yoshizawa loop needs both for every iterate). \p face_l2 receives F values. Only l2, linf,
/// flipped and degenerate are filled: area_distortion and angle_distortion stay 0 (the loop does
/// not use them; they cost a division per face).
/// \pre vertex_uv.size() == mesh.positions.size()
StretchStats measure_stretch(const TriMesh& mesh, const std::vector<Vec2>& vertex_uv,
                             std::vector<double>& face_l2);

/// Mesh L2 stretch (StretchStats::l2) of the per-vertex map \p vertex_uv scaled by (√a, 1/√a), for
/// every a in \p aspects, in one pass over the faces: the scaling keeps every UV area and maps the
/// squared Jacobian column lengths |∂p/∂u|², |∂p/∂v|² of a face to 1/a and a times theirs, so
/// L2(a)² = (P/a + Q·a) / (2 ΣA3) · ΣA2/ΣA3 with P = Σ A3 |∂p/∂u|², Q = Σ A3 |∂p/∂v|² (Sander et
/// al. 2001). Equals measure_stretch(mesh, scaled uv).l2 up to rounding (+inf for every a when a
/// UV triangle is flipped or degenerate). Returns aspects.size() values.
/// \pre vertex_uv.size() == mesh.positions.size(), every a > 0
std::vector<double> l2_stretch_of_aspects(const TriMesh& mesh, const std::vector<Vec2>& vertex_uv,
                                          const std::vector<double>& aspects);

/// Number of pairs of UV triangles whose interiors overlap (exact orientation predicates on a
/// uniform grid of buckets; independent of how the layout was made). Shared edges/vertices do not
/// count. \param max_pairs stop counting after this many.
long count_overlapping_triangles(const Parameterization& param, long max_pairs = 1000);

/// The pairs {f, g} (f < g, sorted) of UV triangles whose interiors overlap, as counted by
/// count_overlapping_triangles(); at most \p max_pairs of them (which ones is then unspecified).
std::vector<std::array<int, 2>> overlapping_triangle_pairs(const Parameterization& param, long max_pairs = 100000);

/// The faces of \p param whose UV triangle is flipped or degenerate (as measure_stretch() counts
/// them) or overlaps another (as overlapping_triangle_pairs() finds them, at most \p max_pairs
/// pairs), sorted and without repeats: empty for a valid layout. \p overlaps_among (F flags, if
/// not null): overlaps are looked for only between flagged faces.
std::vector<int> invalid_uv_faces(const Parameterization& param,
                                  const std::vector<char>* overlaps_among = nullptr,
                                  long max_pairs = 100000);

/// Whether the layout \p uv / \p faces (U wedge coordinates, F triangles of one chart) is valid
/// only up to rounding at its boundary: a boundary wedge lies within \p tol of a boundary edge
/// of another triangle (a zipped cut, a vertex on another part of the boundary). Moved and scaled
/// into a packing, such a layout can gain overlapping triangles. Boundary edges: those of one
/// triangle; a wedge on an endpoint of the edge is no contact (it stays there under any transform),
/// nor is a sliver's apex near its own base (a single triangle is never in contact).
/// \pre every index of \p faces is in [0, uv.size()), tol >= 0
bool boundary_near_contact(const std::vector<Vec2>& uv, const std::vector<Face>& faces, double tol);

/// Fraction of the texels of a \p res x \p res texture whose centre lies inside some UV triangle.
double texel_utilization(const Parameterization& param, int res);

}  // namespace adaptex
