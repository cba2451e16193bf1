// parameterize_disk() on the open shared meshes with one boundary loop (face.obj, camelhead.off).
#include <gtest/gtest.h>

#include "adaptex/core/topology.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/param/disk_param.h"
#include "adaptex/param/stretch.h"
#include "disk_fixtures.h"
#include "reference_stretch.h"
#include "test_support.h"

using namespace adaptex;

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
    EXPECT_NEAR(adaptex::test::reference_l2_stretch(m, p), r.final_l2, 1e-9 * r.final_l2);
    EXPECT_LT(r.final_l2, r.floater_l2);
    EXPECT_GE(r.iterations, 1);
    std::cout << name << ": F=" << m.num_faces() << " Floater L2 " << r.floater_l2 << " -> "
              << r.final_l2 << " after " << r.iterations << " Yoshizawa iterations\n";
  }
}
