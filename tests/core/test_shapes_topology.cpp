// The meshes built in code have the topology their names promise (this is what every other test
// relies on), and analyze_topology() reports it.
#include <gtest/gtest.h>

#include <algorithm>

#include "adaptex/core/shapes.h"
#include "adaptex/core/topology.h"

using namespace adaptex;

struct ShapeCase {
  const char* name;
  TriMesh mesh;
  int components, genus, loops;
};

static std::vector<ShapeCase> cases() {
  return {
      {"plane", shapes::plane(8), 1, 0, 1},
      {"sphere", shapes::sphere(16, 8), 1, 0, 0},
      {"icosphere", shapes::icosphere(2), 1, 0, 0},
      {"torus", shapes::torus(24, 12), 1, 1, 0},
      {"double_torus", shapes::double_torus(32), 1, 2, 0},
      {"open_cylinder", shapes::open_cylinder(16, 4), 1, 0, 2},
      {"disk_with_3_holes", shapes::disk_with_holes(3, 24), 1, 0, 4},
      {"two_components", shapes::two_components(), 2, 1, 0},
      {"trefoil", shapes::trefoil_knot(120, 12), 1, 1, 0},
  };
}

TEST(Shapes, TopologyMatchesConstruction) {
  for (const ShapeCase& c : cases()) {
    SCOPED_TRACE(c.name);
    const MeshTopology t = analyze_topology(c.mesh);
    EXPECT_TRUE(t.is_manifold());
    EXPECT_EQ(t.num_components, c.components);
    EXPECT_EQ(t.total_genus(), c.genus);
    EXPECT_EQ(t.total_loops(), c.loops);
    EXPECT_EQ(t.num_unreferenced_vertices, 0);
    for (int f = 0; f < c.mesh.num_faces(); ++f) EXPECT_GT(face_area(c.mesh, f), 0.0) << "face " << f;
  }
}

TEST(Shapes, ClosedShapesAreOrientedOutward) {
  for (const ShapeCase& c : cases()) {
    if (c.loops != 0) continue;
    SCOPED_TRACE(c.name);
    double vol = 0;
    for (const Face& t : c.mesh.faces)
      vol += c.mesh.positions[t[0]].dot(c.mesh.positions[t[1]].cross(c.mesh.positions[t[2]]));
    EXPECT_GT(vol, 0.0);
  }
}

TEST(Topology, DetectsNonManifoldEdgeAndVertex) {
  const MeshTopology fan = analyze_topology(shapes::nonmanifold_fan());
  ASSERT_EQ(fan.nonmanifold_edges.size(), 1u);
  EXPECT_EQ(fan.nonmanifold_edges[0], (std::array<int, 2>{0, 1}));
  const MeshTopology bow = analyze_topology(shapes::bowtie_vertex());
  EXPECT_TRUE(bow.nonmanifold_edges.empty());
  ASSERT_EQ(bow.nonmanifold_vertices.size(), 1u);
  EXPECT_EQ(bow.nonmanifold_vertices[0], 0);
}

// bucket_edges(): every face side exactly once, in (a, b, face, corner) order, which is the order
// build_edges() and the remap's boundary walks rely on (they replaced a sort of (a, b, face) keys).
TEST(Topology, BucketEdgesVisitsEveryFaceSideInSortedOrder) {
  for (const TriMesh& mesh : {adaptex::shapes::torus(12, 7), adaptex::shapes::genus_surface(2, 4)}) {
    std::vector<Face> faces = mesh.faces;
    // Shuffle the faces (a fixed permutation) so the input order is not already sorted.
    for (size_t f = 0; f + 1 < faces.size(); f += 2) std::swap(faces[f], faces[faces.size() - 1 - f / 2]);
    const int extra = 5;  // a larger vertex count than needed leaves empty buckets
    const EdgeBuckets eb = bucket_edges(faces, mesh.num_vertices() + extra);
    ASSERT_EQ(eb.start.size(), static_cast<size_t>(mesh.num_vertices() + extra + 1));
    ASSERT_EQ(eb.records.size(), 3 * faces.size());
    std::vector<std::array<int, 4>> seen;
    for (size_t a = 0; a + 1 < eb.start.size(); ++a)
      for (int i = eb.start[a]; i < eb.start[a + 1]; ++i) {
        const EdgeBuckets::Record& r = eb.records[static_cast<size_t>(i)];
        const Face& t = faces[static_cast<size_t>(r.face)];
        const int u = t[r.corner], v = t[(r.corner + 1) % 3];
        EXPECT_EQ(static_cast<int>(a), std::min(u, v));
        EXPECT_EQ(r.b, std::max(u, v));
        seen.push_back({static_cast<int>(a), r.b, r.face, r.corner});
      }
    EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
    EXPECT_EQ(std::adjacent_find(seen.begin(), seen.end()), seen.end());
    EXPECT_EQ(seen.size(), 3 * faces.size());
  }
}
