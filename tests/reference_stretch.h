#pragma once
/// \file reference_stretch.h
/// The L2 stretch of Sander, Snyder, Gortler, Hoppe, "Texture mapping progressive meshes",
/// SIGGRAPH 2001, computed in the tests from the definition and not with measure_stretch(), so that a
/// test checking a value produced by measure_stretch() (or by code that calls it) has an independent
/// reference.
#include <cmath>

#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"

namespace adaptex::test {

/// Per face, S_s and S_t are the partial derivatives of the affine map from UV to 3-D,
/// L2(T)^2 = (|S_s|^2 + |S_t|^2) / 2; the mesh value is the 3-D-area-weighted root mean square,
/// scaled by sqrt(UV area / 3-D area) so that a uniform scaling of the UVs does not change it.
/// \p param.uv_faces (F x 3 indices into \p param.uv) is parallel to \p m.faces.
/// \pre no UV triangle is degenerate (the value is then not finite).
inline double reference_l2_stretch(const TriMesh& m, const Parameterization& param) {
  double sum = 0, a3_total = 0, a2_total = 0;
  for (size_t f = 0; f < m.faces.size(); ++f) {
    const Face& t = m.faces[f];
    const Face& w = param.uv_faces[f];
    const Vec3 &q1 = m.positions[t[0]], &q2 = m.positions[t[1]], &q3 = m.positions[t[2]];
    const double s1 = param.uv[w[0]].x(), s2 = param.uv[w[1]].x(), s3 = param.uv[w[2]].x();
    const double t1 = param.uv[w[0]].y(), t2 = param.uv[w[1]].y(), t3 = param.uv[w[2]].y();
    const double a2 = ((s2 - s1) * (t3 - t1) - (s3 - s1) * (t2 - t1)) / 2;
    const double a3 = (q2 - q1).cross(q3 - q1).norm() / 2;
    const Vec3 ss = (q1 * (t2 - t3) + q2 * (t3 - t1) + q3 * (t1 - t2)) / (2 * a2);
    const Vec3 st = (q1 * (s3 - s2) + q2 * (s1 - s3) + q3 * (s2 - s1)) / (2 * a2);
    sum += a3 * (ss.squaredNorm() + st.squaredNorm()) / 2;
    a3_total += a3;
    a2_total += a2;
  }
  return std::sqrt(sum / a3_total) * std::sqrt(a2_total / a3_total);
}

}  // namespace adaptex::test
