// parameterize_disk() on the open shared meshes with one boundary loop (face.obj, camelhead.off).
#include <gtest/gtest.h>

#include <cmath>

#include "adaptex/core/topology.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/param/disk_param.h"
#include "adaptex/param/stretch.h"
#include "disk_fixtures.h"
#include "test_support.h"

using namespace adaptex;

namespace {

/// L2 stretch of Sander et al. 2001 (eq. for L2(M)), computed here from the definition and not with
/// measure_stretch(): per face, S_s and S_t are the partial derivatives of the map from UV to 3-D,
/// L2(T)^2 = (|S_s|^2 + |S_t|^2) / 2; the mesh value is the 3-D-area-weighted root mean square,
/// scaled by sqrt(UV area / 3-D area) so that a uniform scaling of the UVs does not change it.
double sander_l2(const TriMesh& m, const std::vector<Vec2>& uv) {
  double sum = 0, a3_total = 0, a2_total = 0;
  for (const Face& f : m.faces) {
    const Vec3 &q1 = m.positions[f[0]], &q2 = m.positions[f[1]], &q3 = m.positions[f[2]];
    const double s1 = uv[f[0]].x(), s2 = uv[f[1]].x(), s3 = uv[f[2]].x();
    const double t1 = uv[f[0]].y(), t2 = uv[f[1]].y(), t3 = uv[f[2]].y();
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

}  // namespace

TEST(DiskParamShared, OpenMeshesWithOneLoop) {
  ADAPTEX_REQUIRE_SHARED();
  for (const char* name : {"face.obj", "camelhead.off"}) {
    SCOPED_TRACE(name);
    const TriMesh m = read_mesh(*adaptex::test::shared_meshes_dir() / name);
    const MeshTopology topo = analyze_topology(m);
    ASSERT_EQ(topo.boundary_loops.size(), 1u);
    const DiskParamResult r = parameterize_disk(m, topo.boundary_loops[0]);
    const Parameterization p = adaptex::test::as_param(m, r.uv);
    const StretchStats st = measure_stretch(m, p);
    EXPECT_EQ(st.flipped, 0);
    EXPECT_EQ(st.degenerate, 0);
    EXPECT_EQ(count_overlapping_triangles(p), 0);
    EXPECT_TRUE(r.on_square);
    EXPECT_NEAR(sander_l2(m, r.uv), r.final_l2, 1e-9 * r.final_l2);
    EXPECT_LT(r.final_l2, r.floater_l2);
    EXPECT_GE(r.iterations, 1);
    std::cout << name << ": F=" << m.num_faces() << " Floater L2 " << r.floater_l2 << " -> "
              << r.final_l2 << " after " << r.iterations << " Yoshizawa iterations\n";
  }
}
